#include "app/cli.h"

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>

#include "base/error.h"
#include "base/paths.h"
#include "sim/cosim/icarus_dut.h"

namespace phongsim::cli {
namespace fs = std::filesystem;

CLI::Option* add_count(CLI::App& cmd, const std::string& name, std::uint64_t& value,
                       const std::string& description, std::uint64_t max) {
  const CLI::Validator check(
      [max](std::string& text) -> std::string {
        if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
          return fmt::format("'{}' is not a whole number >= 0", text);
        }
        if (text.size() > 20 || std::stod(text) > static_cast<double>(max) ||
            (text.size() == 20 && text > "18446744073709551615")) {
          return fmt::format("{} is out of range (at most {})", text, max);
        }
        return "";
      },
      fmt::format("0..{}", max));
  return cmd.add_option(name, value, description)->check(check)->capture_default_str();
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
  cmd.add_option("--rtl", rtl,
                 "your RTL instead of phongsim's: SystemVerilog files and folders (a folder "
                 "gives its *.sv files; *_pkg.sv first) that implement the pipeline's port "
                 "contract (docs/your-rtl.md)")
      ->expected(1, -1);
  cmd.add_option("--top", top, "top module of --rtl (default: the built-in top's name)");
  cmd.add_option("--rtl-plugin", plugin,
                 "a plugin file phongsim built before (phongsim build-rtl prints its path); "
                 "refused if any source it was built from has changed since");
}

void Target::add_simulator_option(CLI::App& cmd) {
  cmd.add_option("--simulator", simulator,
                 "verilator (the plugin), or icarus: the same design compiled by Icarus Verilog "
                 "(four-state: X or Z on an output is a failure; docs/cosim.md)")
      ->check(CLI::IsMember({"verilator", "icarus"}))
      ->capture_default_str();
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

RtlDesign design_of(const Loaded& l, const Target& t) {
  if (!t.top.empty() && t.rtl.empty()) throw Error("--top needs --rtl");
  if (!t.plugin.empty() && !t.rtl.empty()) throw Error("give --rtl or --rtl-plugin, not both");
  std::vector<fs::path> files(t.rtl.begin(), t.rtl.end());
  return rtl_design(*l.pipeline, l.cfg, std::move(files), t.top);
}

namespace {

std::string quoted(const std::string& s) {
  if (s.find_first_of(" \t\"'\\$") == std::string::npos) return s;
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

Rtl rtl_of(const Loaded& l, const Target& t) {
  const RtlDesign design = design_of(l, t);
  Rtl rtl;
  if (!t.plugin.empty()) {
    const auto library = RtlLibrary::open_file(t.plugin, design);
    const PipelineModel* model = l.model.get();
    rtl.make_dut = [library, model]() { return library->create(*model); };
    rtl.label = fmt::format("plugin {}", t.plugin);
    rtl.options = " --rtl-plugin " + quoted(t.plugin);
    return rtl;
  }
  if (t.simulator == "icarus") {
    if (!t.plugin.empty())
      throw Error("--rtl-plugin is a Verilator build: not with --simulator icarus");
    rtl.make_dut = icarus_duts(design, *l.model, stderr);
    rtl.label = t.rtl.empty() ? fmt::format("built-in {} in Icarus Verilog", design.top)
                              : fmt::format("{} from --rtl in Icarus Verilog", design.top);
    rtl.options = " --simulator icarus";
    for (const auto& p : t.rtl) rtl.options += (&p == &t.rtl.front() ? " --rtl " : " ") + quoted(p);
    if (!t.top.empty()) rtl.options += " --top " + quoted(t.top);
    return rtl;
  }
  RtlPlugin plugin;
  rtl.make_dut = rtl_duts(design, *l.model, t.no_build ? RtlBuild::never : RtlBuild::if_missing,
                          stderr, &plugin);
  if (t.rtl.empty()) {
    rtl.label = fmt::format("built-in {} ({})", design.top, plugin.key);
  } else {
    rtl.label = fmt::format("{} from --rtl, {} file{} ({})", design.top, design.files.size(),
                            design.files.size() == 1 ? "" : "s", plugin.key);
    rtl.options = " --rtl";
    for (const auto& p : t.rtl) rtl.options += " " + quoted(p);
    if (!t.top.empty()) rtl.options += " --top " + quoted(t.top);
  }
  return rtl;
}

CosimSubject subject_of(const Loaded& l, const Target& t, const Stimulus& stimulus) {
  Rtl rtl = rtl_of(l, t);
  return CosimSubject{std::string(l.pipeline->name), l.cfg, *l.model, stimulus,
                      l.pipeline->independent_vectors, std::move(rtl.make_dut),
                      std::move(rtl.label), std::move(rtl.options),
                      // The default run (about a million outputs) makes 16 shards.
                      l.pipeline->default_vectors / 16};
}

Progress progress_line(bool quiet) {
  if (quiet || isatty(STDERR_FILENO) == 0) return [](std::string_view, auto, auto) {};
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  return [last](std::string_view what, std::uint64_t done, std::uint64_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (done != total && now - *last < std::chrono::milliseconds(200)) return;
    *last = now;
    if (total == 0) {
      fmt::print(stderr, "\r\033[K  {}: {}", what, done);
    } else {
      fmt::print(stderr, "\r\033[K  {}: {}/{}", what, done, total);
    }
    if (done == total) fmt::print(stderr, "\r\033[K");
  };
}

}  // namespace phongsim::cli
