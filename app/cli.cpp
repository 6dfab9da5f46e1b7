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
#include <mutex>
#include <regex>
#include <set>

#include "base/error.h"
#include "base/file_util.h"
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
      "");
  // --help: N for a count without a limit that matters, else its range.
  return cmd.add_option(name, value, description)
      ->check(check)
      ->type_name(max >= 0x7fffffff ? std::string("N") : fmt::format("{}..{}", min, max))
      ->capture_default_str();
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
      "");
  return cmd.add_option(name, value, description)
      ->check(check)
      ->type_name(fmt::format("{}..{}", lo, hi));
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
      "");
  return cmd.add_option(name, value, description)
      ->check(check)
      ->type_name(fmt::format("{:g}..{:g}", lo, hi));
}

CLI::Option* add_choice(CLI::App& cmd, const std::string& name, std::string& value,
                        const std::string& description, const std::vector<std::string>& choices) {
  std::string names;
  for (const std::string& c : choices) names += (names.empty() ? "" : "|") + c;
  return cmd.add_option(name, value, description)
      ->check(CLI::IsMember(choices).description(""))
      ->type_name(names)
      ->capture_default_str();
}

namespace {

// --help in plain words: CLI11's layout, an option's kind as its type name says it (NAME, FILE,
// N, a range, a|b|c) with no validator text after it, flags without their "{false}", and a
// default as "(default X)" after the description, unless the description already says what the
// default is.
class PlainHelp : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* opt, bool positional) const override {
    if (positional || (opt->get_snames().empty() && opt->get_lnames().empty())) {
      return CLI::Formatter::make_option_name(opt, positional);
    }
    std::string names;
    for (const std::string& n : opt->get_snames()) names += (names.empty() ? "-" : ",-") + n;
    for (const std::string& n : opt->get_lnames()) names += (names.empty() ? "--" : ",--") + n;
    return names;
  }

  std::string make_option_opts(const CLI::Option* opt) const override {
    if (!opt->get_option_text().empty()) return " " + opt->get_option_text();
    std::string out;
    if (opt->get_type_size() != 0) {
      if (!opt->get_type_name().empty()) out += " " + opt->get_type_name();
      if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) {
        out += " ...";
      } else if (opt->get_expected_min() > 1) {
        out += fmt::format(" x {}", opt->get_expected());
      }
      if (opt->get_required()) out += " REQUIRED";
    }
    const auto list = [&out](const char* label, const std::set<CLI::Option*>& others) {
      if (others.empty()) return;
      out += fmt::format(" ({}", label);
      for (const CLI::Option* o : others) out += " " + o->get_name();
      out += ")";
    };
    list("needs", opt->get_needs());
    list("excludes", opt->get_excludes());
    return out;
  }

  std::string make_option_desc(const CLI::Option* opt) const override {
    const std::string& desc = opt->get_description();
    std::string value = opt->get_default_str();
    if (opt->get_type_size() == 0 || value.empty() || opt->get_required() ||
        desc.find("default") != std::string::npos) {
      return desc;
    }
    if (value.size() >= 2 && value.front() == '[' && value.back() == ']') {  // a list
      value = value.substr(1, value.size() - 2);
    }
    return fmt::format("{} (default {})", desc, value);
  }
};

void add_progress_option(CLI::App& cmd) {
  cmd.add_option_function<std::string>(
         "--progress",
         [](const std::string& mode) {
           set_progress_mode(mode == "never"    ? ProgressMode::never
                             : mode == "always" ? ProgressMode::always
                                                : ProgressMode::automatic);
         },
         "progress on standard error: auto (the default: on a terminal a line updating in "
         "place, else a plain line after 10 s and at most every 20 s), always (the updating "
         "line) or never; docs/cosim.md")
      ->check(CLI::IsMember({"auto", "always", "never"}).description(""))
      ->type_name("auto|always|never");
}

void add_common_options(CLI::App& cmd, const std::shared_ptr<PlainHelp>& help, bool top) {
  cmd.formatter(help);
  const std::vector<CLI::App*> subs = cmd.get_subcommands([](CLI::App*) { return true; });
  if (subs.empty() && !top) add_progress_option(cmd);  // a command that runs
  for (CLI::App* sub : subs) add_common_options(*sub, help, false);
}

}  // namespace

void add_common_options(CLI::App& app) {
  add_common_options(app, std::make_shared<PlainHelp>(), true);
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
                 "pipeline name (default: the configuration's `pipeline` key)")
      ->type_name("NAME");
  if (many_configs) {
    cmd.add_option("--config", configs,
                   "configuration file, or several (--config a.toml --config b.toml: one run each; "
                   "default: configs/<pipeline>/default.toml)")
        ->type_name("FILE");
  } else {
    cmd.add_option("--config", config,
                   "configuration file (default: configs/<pipeline>/default.toml)")
        ->type_name("FILE");
  }
  if (!rtl_options) return;
  cmd.add_flag("--no-build", no_build,
               "fail instead of Verilating RTL whose current content is not built yet");
  add_source_options(cmd);
  cmd.add_option("--rtl-plugin", plugin,
                 "a plugin file phongsim built before (phongsim build-rtl prints its path); "
                 "refused if any source it was built from has changed since")
      ->type_name("FILE");
}

void Target::add_source_options(CLI::App& cmd) {
  command = &cmd;
  cmd.add_option("--rtl", rtl,
                 "your RTL instead of phongsim's, implementing the pipeline's port contract "
                 "(docs/your-rtl.md): SystemVerilog files and folders (a folder gives its .sv and "
                 ".v files; files that declare packages go first), headers (.svh, .vh: their "
                 "folder is an include folder), +incdir+DIR and +define+NAME[=VALUE]")
      ->expected(1, -1)
      ->type_name("PATH");
  cmd.add_option("-f", lists_cwd,
                 "a file list of your RTL, its relative paths from the current folder (files, "
                 "+incdir+, +define+, -I, -D, nested -f/-F; // and # comments, $VAR)")
      ->type_name("FILE");
  cmd.add_option("-F", lists_here, "a file list whose relative paths are from its own folder")
      ->type_name("FILE");
  cmd.add_option("-I", include_dirs,
                 "an include folder of your RTL (searched before the folders of its files)")
      ->type_name("DIR");
  cmd.add_option("-D", defines, "a macro of your RTL: NAME or NAME=VALUE")
      ->type_name("NAME[=VALUE]");
  cmd.add_option("--top", top, "top module of your RTL (default: the built-in top's name)")
      ->type_name("MODULE");
}

void Target::add_simulator_option(CLI::App& cmd) {
  add_choice(cmd, "--simulator", simulator,
             "verilator (the plugin), or icarus: the same design compiled by Icarus Verilog "
             "(four-state: X or Z on an output is a failure; docs/cosim.md)",
             {"verilator", "icarus"});
  add_choice(cmd, "--x-init", x_init,
             "how the Verilated registers start: zero, or random (a plugin built with "
             "-x-assign unique -x-initial unique whose power-up state and X assignments "
             "come from --x-seed; docs/verification.md)",
             {"zero", "random"});
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
  std::error_code ec;
  if (config.empty() && configs.empty() && !pipeline.empty()) {
    in.emplace_back("the default configuration",
                    data_root() / "configs" / pipeline / "default.toml");
  }
  if (!user_rtl() && plugin.empty()) {  // phongsim's own RTL
    for (fs::recursive_directory_iterator it(data_root() / "rtl", ec), end; !ec && it != end;
         it.increment(ec)) {
      if (it->is_regular_file(ec)) in.emplace_back("phongsim's RTL", it->path());
    }
  }
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
  rtl.identity = {design.top,
                  !t.plugin.empty() ? "plugin"
                  : t.user_rtl()    ? "rtl"
                                    : "builtin",
                  t.simulator == "icarus" ? "icarus" : "verilator",
                  t.plugin,
                  {},
                  design.include_dirs,
                  design.defines,
                  design.params};
  if (!t.plugin.empty()) {
    const auto library = RtlLibrary::open_file(t.plugin, design);
    rtl.identity.sources = library->sources();
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
    for (const auto& f : design.files) rtl.identity.sources.files.push_back({f, file_hash(f)});
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
  rtl.identity.plugin = plugin.path;
  rtl.identity.sources = plugin_sources(plugin, design);
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

CosimSubject subject_of(const Loaded& l, const Target& t, const Stimulus& stimulus,
                        RtlIdentity* identity) {
  Rtl rtl = rtl_of(l, t);
  if (identity != nullptr) *identity = rtl.identity;
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

namespace {

ProgressMode& progress_mode() {
  static ProgressMode mode = ProgressMode::automatic;
  return mode;
}

// How progress appears: by --progress and whether stderr is a terminal.
enum class ProgressStyle { none, line, heartbeat };

ProgressStyle progress_style() {
  switch (progress_mode()) {
    case ProgressMode::never:
      return ProgressStyle::none;
    case ProgressMode::always:
      return ProgressStyle::line;
    case ProgressMode::automatic:
      break;
  }
  return isatty(STDERR_FILENO) != 0 ? ProgressStyle::line : ProgressStyle::heartbeat;
}

// Seconds from the environment variable `name`, when it is set; an unusable value is refused,
// naming it.
std::optional<double> seconds_from_env(const char* name) {
  const char* v = std::getenv(name);
  if (v == nullptr) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(v, &end);
  if (end == v || *end != '\0' || !(x >= 0 && x <= 86400)) {
    throw Error(fmt::format("{}='{}' is not a number of seconds (0..86400)", name, v));
  }
  return x;
}

// Seconds a task runs before its first progress: PHONGSIM_PROGRESS_AFTER, else 2 for the
// terminal line (short runs stay quiet) and 10 for heartbeats.
double progress_after(ProgressStyle style) {
  static const std::optional<double> after = seconds_from_env("PHONGSIM_PROGRESS_AFTER");
  return after.value_or(style == ProgressStyle::heartbeat ? 10.0 : 2.0);
}

// Seconds between heartbeat lines: PHONGSIM_PROGRESS_EVERY, else 20.
double heartbeat_every() {
  static const double every = seconds_from_env("PHONGSIM_PROGRESS_EVERY").value_or(20.0);
  return every;
}

// Elapsed time as a heartbeat line says it: 42s, 1m40s, 2h05m00s.
std::string elapsed_text(double seconds) {
  const auto s = static_cast<std::uint64_t>(seconds);
  if (s < 60) return fmt::format("{}s", s);
  if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}h{:02}m{:02}s", s / 3600, s / 60 % 60, s % 60);
}

using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

}  // namespace

void set_progress_mode(ProgressMode mode) { progress_mode() = mode; }

Progress progress_line(bool quiet) {
  const ProgressStyle style = quiet ? ProgressStyle::none : progress_style();
  if (style == ProgressStyle::none) return [](std::string_view, auto, auto) {};
  struct State {
    std::mutex mutex;  // cosim's workers report from their own threads
    Clock::time_point start = Clock::now();
    Clock::time_point next;  // the earliest time of the next line
    bool shown = false;      // a terminal line is on the screen
  };
  auto state = std::make_shared<State>();
  state->next = state->start + seconds(progress_after(style));
  // The terminal line: at most five updates a second.
  const Clock::duration every =
      seconds(style == ProgressStyle::heartbeat ? heartbeat_every() : 0.2);
  return [state, style, every](std::string_view what, std::uint64_t done, std::uint64_t total) {
    const std::lock_guard lock(state->mutex);
    const auto now = Clock::now();
    if (done == total && total != 0) {  // finished: clear the terminal line if one is shown
      if (state->shown) fmt::print(stderr, "\r\033[K");
      state->shown = false;
      return;
    }
    if (now < state->next) return;
    state->next = now + every;
    const double s = std::chrono::duration<double>(now - state->start).count();
    if (style == ProgressStyle::heartbeat) {
      fmt::print(stderr, "phongsim: {}: {}, {}\n", what,
                 total == 0 ? fmt::to_string(done) : fmt::format("{} of {}", done, total),
                 elapsed_text(s));
      return;
    }
    state->shown = true;
    if (total == 0) {
      fmt::print(stderr, "\r\033[K  {}: {} ({:.0f} s)", what, done, s);
    } else {
      fmt::print(stderr, "\r\033[K  {}: {}/{} ({:.0f} s)", what, done, total, s);
    }
  };
}

void install_tool_progress() {
  // Unusable values are refused now, before any work.
  (void)progress_after(ProgressStyle::line);
  (void)heartbeat_every();
  struct State {
    std::mutex mutex;  // helper programs may run from several threads
    bool shown = false;
    std::optional<Clock::time_point> last;  // the last heartbeat line
  };
  // The style is asked at each call: --progress is parsed after this is installed.
  set_wait_hook([state = std::make_shared<State>()](const std::vector<std::string>& argv,
                                                    double seconds_run, const fs::path& log) {
    const ProgressStyle style = progress_style();
    const std::lock_guard lock(state->mutex);
    if (seconds_run < 0) {
      if (state->shown) fmt::print(stderr, "\r\033[K");
      state->shown = false;
      return;
    }
    if (style == ProgressStyle::none || seconds_run < progress_after(style)) return;
    if (style == ProgressStyle::heartbeat) {
      const auto now = Clock::now();
      if (state->last && now - *state->last < seconds(heartbeat_every())) return;
      state->last = now;
    }
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
    if (style == ProgressStyle::heartbeat) {
      fmt::print(stderr, "phongsim: {}: {}{}\n", what, elapsed_text(seconds_run), steps);
      return;
    }
    fmt::print(stderr, "\r\033[K  {}: {:.0f} s{}", what, seconds_run, steps);
    state->shown = true;
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
