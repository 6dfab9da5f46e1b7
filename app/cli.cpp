#include "app/cli.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>

#include "base/error.h"
#include "base/paths.h"
#include "base/process.h"
#include "base/text.h"
#include "sim/cosim/icarus_dut.h"

namespace phongsim::cli {
namespace fs = std::filesystem;

CLI::Option* add_count(CLI::App& cmd, const std::string& name, std::uint64_t& value,
                       const std::string& description, std::uint64_t max, std::uint64_t min) {
  const CLI::Validator check(
      [min, max](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return fmt::format("'{}' is not a whole number >= {}", text, min);
        }
        if (text.size() > 20 || std::stod(text) > static_cast<double>(max) ||
            (text.size() == 20 && text > "18446744073709551615")) {
          return fmt::format("{} is out of range (at most {})", text, max);
        }
        if (std::stoull(text) < min) {
          return fmt::format("{} is out of range (at least {})", text, min);
        }
        return "";
      },
      fmt::format("{}..{}", min, max));
  return cmd.add_option(name, value, description)->check(check)->capture_default_str();
}

CLI::Option* add_int(CLI::App& cmd, const std::string& name, int& value,
                     const std::string& description, int lo, int hi) {
  const CLI::Validator check(
      [lo, hi](std::string& text) -> std::string {
        const std::string_view digits =
            !text.empty() && text[0] == '-' ? std::string_view(text).substr(1) : text;
        if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos) {
          return fmt::format("'{}' is not a whole number", text);
        }
        if (digits.size() > 10 || std::stoll(text) < lo || std::stoll(text) > hi) {
          return fmt::format("{} is out of range ({}..{})", text, lo, hi);
        }
        return "";
      },
      fmt::format("{}..{}", lo, hi));
  return cmd.add_option(name, value, description)->check(check);
}

CLI::Option* add_real(CLI::App& cmd, const std::string& name, double& value,
                      const std::string& description, double lo, double hi) {
  const CLI::Validator check(
      [lo, hi](std::string& text) -> std::string {
        double x = 0;
        const auto* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, x);
        if (text.empty() || ec != std::errc{} || ptr != end || !std::isfinite(x)) {
          return fmt::format("'{}' is not a number", text);
        }
        if (x < lo || x > hi) return fmt::format("{} is out of range ({}..{})", text, lo, hi);
        return "";
      },
      fmt::format("{}..{}", lo, hi));
  return cmd.add_option(name, value, description)->check(check);
}

bool quick_mode() {
  static const bool quick = [] {
    const char* q = std::getenv("PHONGSIM_QUICK");
    const bool on = q != nullptr && std::string_view(q) == "1";
    if (on) {
      fmt::print(stderr,
                 "phongsim: PHONGSIM_QUICK=1: sizes reduced (a smoke test, not a result)\n");
    }
    return on;
  }();
  return quick;
}

std::uint64_t quick_cap(std::uint64_t value, std::uint64_t cap) {
  return quick_mode() ? std::min(value, cap) : value;
}

void Target::add_options(CLI::App& cmd, bool rtl_options, bool many_configs) {
  cmd.add_option("pipeline,--pipeline", pipeline,
                 "pipeline name (default: the configuration's `pipeline` key)");
  if (many_configs) {
    cmd.add_option("--config", configs,
                   "configuration file, or several (--config a.toml --config b.toml: one run each; "
                   "default: configs/<pipeline>/default.toml)");
  } else {
    cmd.add_option("--config", config,
                   "configuration file (default: configs/<pipeline>/default.toml)");
  }
  if (!rtl_options) return;
  cmd.add_flag("--no-build", no_build,
               "fail instead of Verilating RTL whose current content is not built yet");
  add_source_options(cmd);
  cmd.add_option("--rtl-plugin", plugin,
                 "a plugin file phongsim built before (phongsim build-rtl prints its path); "
                 "refused if any source it was built from has changed since");
}

void Target::add_source_options(CLI::App& cmd) {
  command = &cmd;
  cmd.add_option("--rtl", rtl,
                 "your RTL instead of phongsim's, implementing the pipeline's port contract "
                 "(docs/your-rtl.md): SystemVerilog files and folders (a folder gives its .sv and "
                 ".v files; files that declare packages go first), headers (.svh, .vh: their "
                 "folder is an include folder), +incdir+DIR and +define+NAME[=VALUE]")
      ->expected(1, -1);
  cmd.add_option("-f", lists_cwd,
                 "a file list of your RTL, its relative paths from the current folder (files, "
                 "+incdir+, +define+, -I, -D, nested -f/-F; // and # comments, $VAR)");
  cmd.add_option("-F", lists_here, "a file list whose relative paths are from its own folder");
  cmd.add_option("-I", include_dirs,
                 "an include folder of your RTL (searched before the folders of its files)");
  cmd.add_option("-D", defines, "a macro of your RTL: NAME or NAME=VALUE");
  cmd.add_option("--top", top,
                 "top module of --rtl or --rtl-plugin (default: the built-in top's name)");
}

void Target::add_simulator_option(CLI::App& cmd) {
  cmd.add_option("--simulator", simulator,
                 "verilator (the plugin), or icarus: the same design compiled by Icarus Verilog "
                 "(four-state: X or Z on an output is a failure; docs/cosim.md)")
      ->check(CLI::IsMember({"verilator", "icarus"}))
      ->capture_default_str();
  cmd.add_option("--x-init", x_init,
                 "how the Verilated registers start: zero, or random (a plugin built with "
                 "-x-assign unique -x-initial unique whose power-up state and X assignments "
                 "come from --x-seed; docs/verification.md)")
      ->check(CLI::IsMember({"zero", "random"}))
      ->capture_default_str();
  x_seed_opt = add_count(cmd, "--x-seed", x_seed, "seed of the power-up state (--x-init random)",
                         0x7fffffff, 1);
}

void Target::check_x_init() const {
  if (x_init != "random") {
    if (x_seed_opt != nullptr && *x_seed_opt) throw Error("--x-seed needs --x-init random");
    return;
  }
  if (simulator == "icarus") {
    throw Error(
        "--x-init random is a Verilator build option; Icarus Verilog is four-state: its registers "
        "start X, and an X on a valid output already fails the run");
  }
  if (!plugin.empty()) {
    throw Error("--x-init random builds a plugin of its own: not with --rtl-plugin");
  }
}

std::vector<std::pair<std::string, fs::path>> Target::inputs() const {
  std::vector<std::pair<std::string, fs::path>> in{{"--config", config}, {"--rtl-plugin", plugin}};
  for (const std::string& c : configs) in.emplace_back("--config", c);
  const auto hdl = [](const fs::path& f) {
    static const std::vector<std::string> kinds = {".sv", ".v", ".svh", ".vh", ".svi", ".inc"};
    return std::find(kinds.begin(), kinds.end(), f.extension().string()) != kinds.end();
  };
  // The RTL as its options name it (a list that cannot be read is the command's error later).
  RtlSources s;
  try {
    s = sources();
  } catch (const Error&) {
    for (const std::string& p : rtl) s.files.emplace_back(p);
  }
  std::error_code ec;
  for (const fs::path& list : s.lists) in.emplace_back("-f", list);
  for (const fs::path& dir : s.include_dirs) {  // what an `include may read there
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->is_regular_file(ec) && hdl(it->path())) in.emplace_back("-I", it->path());
    }
  }
  for (const fs::path& p : s.files) {
    in.emplace_back("--rtl", p);
    const bool folder = fs::is_directory(p, ec);
    const fs::path dir = folder ? p : p.parent_path().empty() ? fs::path(".") : p.parent_path();
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->is_regular_file(ec) && (folder || hdl(it->path()))) {
        in.emplace_back("--rtl", it->path());
      }
    }
  }
  return in;
}

std::string Target::x_init_mode() const {
  if (simulator == "icarus") return "x";
  return x_init;
}

Loaded load(const Target& t) {
  if (t.config.empty() && t.pipeline.empty()) {
    throw Error("give a pipeline or --config (see phongsim list)");
  }
  if (!t.pipeline.empty()) (void)find_pipeline(t.pipeline);  // unknown: list the known ones
  const std::string config = !t.config.empty()
                                 ? t.config
                                 : (data_root() / "configs" / t.pipeline / "default.toml").string();
  Loaded l{Config::load(config), nullptr, nullptr};
  l.pipeline = &find_pipeline(t.pipeline.empty() ? l.cfg.pipeline() : t.pipeline);
  l.model = make_model(*l.pipeline, l.cfg);
  return l;
}

RtlSources Target::sources() const {
  RtlSources s;
  if (command == nullptr) return s;
  // Each option's values in the order given, taken in the order the options came.
  std::map<const CLI::Option*, std::size_t> next;
  for (const CLI::Option* opt : command->parse_order()) {
    const std::vector<std::string>& values = opt->results();
    const std::string& name = opt->get_name();
    const std::size_t at = next[opt];
    if (name == "--rtl") {
      // --rtl takes all its words at once (and may come only once in a row).
      if (at == 0) add_rtl_words(rtl, s);
      next[opt] = values.size();
    } else if (at < values.size()) {
      const std::string& v = values[at];
      next[opt] = at + 1;
      if (name == "-f" || name == "-F") {
        add_file_list(v, name == "-F", s);
      } else if (name == "-I" || name == "-D") {
        const std::vector<std::string> words{name, v};
        add_rtl_words(words, s, name);
      }
    }
  }
  return s;
}

RtlSources Target::checked_sources() const {
  RtlSources s = sources();
  if (s.files.empty() && (!s.include_dirs.empty() || !s.defines.empty())) {
    throw Error(
        "-I, -D, +incdir+ and +define+ go with your RTL (--rtl or -f): phongsim's own RTL takes "
        "neither");
  }
  return s;
}

std::string Target::rtl_options() const {
  std::string s;
  if (command == nullptr || !user_rtl()) return s;
  std::map<const CLI::Option*, std::size_t> next;
  for (const CLI::Option* opt : command->parse_order()) {
    const std::string& name = opt->get_name();
    const std::vector<std::string>& values = opt->results();
    const std::size_t at = next[opt];
    if (name == "--rtl") {
      if (at == 0) {
        s += " --rtl";
        for (const std::string& w : values) s += " " + shell_quoted(w);
      }
      next[opt] = values.size();
    } else if ((name == "-f" || name == "-F" || name == "-I" || name == "-D") &&
               at < values.size()) {
      s += fmt::format(" {} {}", name, shell_quoted(values[at]));
      next[opt] = at + 1;
    }
  }
  if (!top.empty()) s += " --top " + shell_quoted(top);
  return s;
}

RtlDesign design_of(const Loaded& l, const Target& t) {
  if (!t.top.empty() && !t.user_rtl() && t.plugin.empty()) {
    throw Error("--top needs --rtl or -f (or --rtl-plugin, for a plugin built from them)");
  }
  if (!t.plugin.empty() && (t.user_rtl() || !t.include_dirs.empty() || !t.defines.empty())) {
    throw Error("give --rtl (or -f, -I, -D) or --rtl-plugin, not both: a plugin records its RTL");
  }
  return rtl_design(*l.pipeline, l.cfg, t.checked_sources(), t.top);
}

Rtl rtl_of(const Loaded& l, const Target& t) {
  t.check_x_init();
  RtlDesign design = design_of(l, t);
  if (t.x_init == "random") design.x_init = XInit::random;
  design.coverage = !t.coverage_prefix.empty();
  design.coverage_toggle = t.coverage_toggle;
  Rtl rtl;
  if (!t.plugin.empty()) {
    const auto library = RtlLibrary::open_file(t.plugin, design);
    const PipelineModel* model = l.model.get();
    rtl.make_dut = [library, model]() { return library->create(*model); };
    // It runs as it was built: its Verilator flags are the ones it records.
    const std::string extra = library->verilator_extra();
    rtl.label = fmt::format("plugin {}{}", t.plugin,
                            extra.empty() ? "" : fmt::format(" (Verilator flags: {})", extra));
    rtl.options = " --rtl-plugin " + shell_quoted(t.plugin) +
                  (t.top.empty() ? "" : " --top " + shell_quoted(t.top));
    return rtl;
  }
  if (t.simulator == "icarus") {
    if (!t.plugin.empty())
      throw Error("--rtl-plugin is a Verilator build: not with --simulator icarus");
    rtl.make_dut = icarus_duts(design, *l.model, stderr);
    rtl.label = !t.user_rtl() ? fmt::format("built-in {} in Icarus Verilog", design.top)
                              : fmt::format("{} from --rtl in Icarus Verilog", design.top);
    rtl.options = " --simulator icarus" + t.rtl_options();
    return rtl;
  }
  RtlPlugin plugin;
  rtl.make_dut =
      rtl_duts(design, *l.model, t.no_build ? RtlBuild::never : RtlBuild::if_missing, stderr,
               &plugin, static_cast<std::uint32_t>(t.x_init_seed()), t.coverage_prefix);
  const std::string x_init =
      std::string(!design.coverage         ? ""
                  : design.coverage_toggle ? "; coverage"
                                           : "; line coverage") +
      (design.x_init == XInit::random ? fmt::format("; x-init random, seed {}", t.x_seed) : "");
  const std::string key = plugin.key.substr(0, 16);  // as the cache folder names it
  if (!t.user_rtl()) {
    rtl.label = fmt::format("built-in {} ({}{})", design.top, key, x_init);
  } else {
    rtl.label = fmt::format(
        "{} from --rtl, {} file{}{} ({}{})", design.top, design.files.size(),
        design.files.size() == 1 ? "" : "s",
        design.defines.empty() ? "" : fmt::format(", {}", fmt::join(design.defines, " ")), key,
        x_init);
    rtl.options = t.rtl_options();
  }
  if (design.x_init == XInit::random) {
    rtl.options += fmt::format(" --x-init random --x-seed {}", t.x_seed);
  }
  return rtl;
}

namespace {
std::string& invocation_text() {
  static std::string text = "phongsim";
  return text;
}
}  // namespace

void set_invocation(std::string_view argv0) { invocation_text() = shell_quoted(argv0); }
const std::string& invocation() { return invocation_text(); }

CosimSubject subject_of(const Loaded& l, const Target& t, const Stimulus& stimulus) {
  Rtl rtl = rtl_of(l, t);
  CosimSubject s{std::string(l.pipeline->name),
                 l.cfg,
                 *l.model,
                 stimulus,
                 l.pipeline->independent_vectors,
                 std::move(rtl.make_dut),
                 std::move(rtl.label),
                 std::move(rtl.options),
                 l.pipeline->contract(*l.model, l.cfg),
                 invocation(),
                 t.config.empty() ? "" : " --config " + shell_quoted(t.config),
                 l.pipeline->stages};
  s.traceable = t.simulator != "icarus";
  return s;
}

std::optional<fs::path> inside(const fs::path& path, const fs::path& dir) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  const fs::path d = fs::weakly_canonical(fs::absolute(dir), ec);
  const fs::path rel = p.lexically_relative(d);
  if (rel.empty() || *rel.begin() == ".." || rel == ".") return std::nullopt;
  return rel;
}

bool progress_shown() { return isatty(STDERR_FILENO) != 0; }

// Seconds a task runs before its progress line appears: PHONGSIM_PROGRESS_AFTER, else 2 (short
// runs stay quiet). An unusable value is refused once, naming it.
double progress_after() {
  static const double after = [] {
    const char* v = std::getenv("PHONGSIM_PROGRESS_AFTER");
    if (v == nullptr) return 2.0;
    char* end = nullptr;
    const double x = std::strtod(v, &end);
    if (end == v || *end != '\0' || !(x >= 0 && x <= 86400)) {
      throw Error(
          fmt::format("PHONGSIM_PROGRESS_AFTER='{}' is not a number of seconds (0..86400)", v));
    }
    return x;
  }();
  return after;
}

Progress progress_line(bool quiet) {
  if (quiet || !progress_shown()) return [](std::string_view, auto, auto) {};
  const auto after = std::chrono::duration<double>(progress_after());
  using Clock = std::chrono::steady_clock;
  struct State {
    Clock::time_point start = Clock::now();
    Clock::time_point last;
    bool shown = false;
  };
  auto state = std::make_shared<State>();
  return [state, after](std::string_view what, std::uint64_t done, std::uint64_t total) {
    const auto now = Clock::now();
    if (done == total && total != 0) {  // finished: clear the line if one is shown
      if (state->shown) fmt::print(stderr, "\r\033[K");
      state->shown = false;
      return;
    }
    if (now - state->start < after || now - state->last < std::chrono::milliseconds(200)) {
      return;
    }
    state->last = now;
    state->shown = true;
    const double s = std::chrono::duration<double>(now - state->start).count();
    if (total == 0) {
      fmt::print(stderr, "\r\033[K  {}: {} ({:.0f} s)", what, done, s);
    } else {
      fmt::print(stderr, "\r\033[K  {}: {}/{} ({:.0f} s)", what, done, total, s);
    }
  };
}

void install_tool_progress() {
  if (!progress_shown()) return;
  set_wait_hook([shown = false, after = progress_after()](const std::vector<std::string>& argv,
                                                          double seconds,
                                                          const fs::path& log) mutable {
    if (seconds < 0) {
      if (shown) fmt::print(stderr, "\r\033[K");
      shown = false;
      return;
    }
    if (seconds < after) return;
    std::string what = fs::path(argv.front()).filename().string();
    if (what == "cmake" || what == fs::path(cmake_program()).filename().string()) {
      const bool build = std::find(argv.begin(), argv.end(), "--build") != argv.end();
      what = build ? "Verilating (building the plugins)" : "Verilating (configuring)";
    }
    std::string steps;
    if (!log.empty()) {  // ninja's last "[done/total]" in the log
      std::ifstream in(log, std::ios::binary | std::ios::ate);
      const auto size = static_cast<std::streamoff>(in.tellg());
      in.seekg(std::max<std::streamoff>(0, size - 4096));
      std::string tail((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      static const std::regex kStep(R"(\[(\d+)/(\d+)\])");
      for (std::sregex_iterator it(tail.begin(), tail.end(), kStep), end; it != end; ++it) {
        steps = " " + it->str();
      }
    }
    fmt::print(stderr, "\r\033[K  {}: {:.0f} s{}", what, seconds, steps);
    shown = true;
  });
}

std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // XML 1.0 allows no control characters but tab and newlines.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += '?';
        } else {
          out += c;
        }
    }
  }
  return out;
}

// JUnit XML as CI systems read it: one testsuite per pipeline, one testcase per run, the
// first-failure report as the failure's text.
std::string junit_xml(std::span<const CosimRun> runs) {
  std::size_t failures = 0;
  double seconds = 0;
  for (const CosimRun& r : runs) {
    failures += r.report.passed ? 0 : 1;
    seconds += r.seconds;
  }
  std::string x = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<testsuites name=\"phongsim cosim\" tests=\"{}\" failures=\"{}\" time=\"{:.3f}\">\n",
      runs.size(), failures, seconds);
  for (std::size_t i = 0; i < runs.size();) {
    std::size_t j = i;
    std::size_t suite_failures = 0;
    double suite_seconds = 0;
    while (j < runs.size() && runs[j].report.pipeline == runs[i].report.pipeline) {
      suite_failures += runs[j].report.passed ? 0 : 1;
      suite_seconds += runs[j].seconds;
      ++j;
    }
    x += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" time=\"{:.3f}\">\n",
                     xml_escaped(runs[i].report.pipeline), j - i, suite_failures, suite_seconds);
    for (; i < j; ++i) {
      const CosimReport& r = runs[i].report;
      x += fmt::format(
          "    <testcase classname=\"{}.{}\" name=\"source {} sink {} seed {}\" time=\"{:.3f}\">\n",
          xml_escaped(r.pipeline), xml_escaped(r.config_name), xml_escaped(r.options.source.str()),
          xml_escaped(r.options.sink.str()), r.options.seed, runs[i].seconds);
      if (!r.passed) {
        x += fmt::format("      <failure type=\"{}\" message=\"{}\">{}</failure>\n",
                         xml_escaped(r.failure_kind),
                         xml_escaped(r.failure_detail ? r.failure_detail->message : r.summary()),
                         xml_escaped(r.failure));
      }
      x += fmt::format("      <system-out>{}</system-out>\n    </testcase>\n",
                       xml_escaped(r.summary()));
    }
    x += "  </testsuite>\n";
  }
  return x + "</testsuites>\n";
}

}  // namespace phongsim::cli
