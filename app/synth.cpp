// phongsim synth: Yosys generic synthesis (and optionally iCE40 place and route) of a
// configuration's RTL, or of every built-in configuration (--all): area, logic depth per register,
// no latches (sim/explore/synth.h).
#include <fmt/format.h>

#include <algorithm>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/paths.h"
#include "sim/explore/synth.h"

namespace phongsim::cli {
namespace {

struct SynthCli {
  Target target;
  bool ice40 = false;
  std::string json;
  bool check = false;
  bool all = false;
  bool stages = false;
};

// The first line of a result: area, depth, iCE40.
void print_summary(std::FILE* out, const std::string& label, const RtlDesign& d,
                   const SynthResult& r, bool ice40) {
  fmt::print(out, "{} ({}): {} cells, ~{} transistors, depth {} levels, no latches{}", label, d.top,
             r.cells, r.transistors, r.depth, r.cached ? " (cached)" : "");
  if (ice40) {
    fmt::print(out, "; iCE40 {}: {} LUT4, {} carry, {} SB_MAC16, {} FF, {}", kSynthIce40Device,
               r.lut4, r.carry, r.mac16, r.ff,
               r.fits ? fmt::format("fmax {:.2f} MHz", r.fmax_mhz) : std::string("does not fit"));
  }
  fmt::print(out, "\n");
}

// The depth table: one row per register and output port, deepest first.
void print_stages(std::FILE* out, const SynthResult& r) {
  std::size_t width = 4;
  for (const StageDepth& s : r.stages) width = std::max(width, s.to.size() + (s.output ? 9 : 0));
  fmt::print(out, "  logic depth (gate levels) into each register and output, deepest first:\n");
  fmt::print(out, "  {:>6} {:>5}  {:<{}}  {}\n", "levels", "bits", "into", width, "from");
  for (const StageDepth& s : r.stages) {
    fmt::print(out, "  {:>6} {:>5}  {:<{}}  {}\n", s.levels, s.bits,
               s.output ? s.to + " (output)" : s.to, width, s.from.empty() ? "-" : s.from);
  }
}

// One configuration's result: the synth document's keys after `schema` and `command`.
nlohmann::ordered_json result_json(const Loaded& l, const RtlDesign& d, const SynthResult& r,
                                   bool ice40) {
  nlohmann::ordered_json j;
  j["pipeline"] = l.pipeline->name;
  j["config"] = l.cfg.name();
  j["config_path"] = l.cfg.origin();
  j["top"] = d.top;
  j["key"] = r.key;
  j["cached"] = r.cached;
  j["generic"] = {{"cells", r.cells}, {"transistors", r.transistors}, {"depth", r.depth}};
  j["ice40"] = nullptr;
  if (ice40) {
    j["ice40"] = {{"device", kSynthIce40Device},
                  {"lut4", r.lut4},
                  {"carry", r.carry},
                  {"mac16", r.mac16},
                  {"ff", r.ff},
                  {"fits", r.fits},
                  {"fmax_mhz",
                   r.fits ? nlohmann::ordered_json(r.fmax_mhz) : nlohmann::ordered_json(nullptr)}};
  }
  j["stages"] = nlohmann::ordered_json::array();
  for (const StageDepth& s : r.stages) {
    j["stages"].push_back({{"to", s.to},
                           {"output", s.output},
                           {"bits", s.bits},
                           {"levels", s.levels},
                           {"from", s.from.empty() ? nlohmann::ordered_json(nullptr)
                                                   : nlohmann::ordered_json(s.from)}});
  }
  return j;
}

// --all: every configuration in configs/ (of the pipeline given, else of every pipeline).
int run_all(const SynthCli& c) {
  if (!c.target.config.empty()) throw Error("--all and --config exclude each other");
  if (c.target.user_rtl() || !c.target.top.empty()) {
    throw Error("--all synthesizes the built-in RTL: no --rtl or --top");
  }
  if (c.check && !c.json.empty()) throw Error("--check and --json exclude each other");
  std::vector<const PipelineInfo*> which;
  if (!c.target.pipeline.empty()) {
    which.push_back(&find_pipeline(c.target.pipeline));
  } else {
    for (const auto& p : pipelines()) which.push_back(&p);
  }
  JsonOutput json(c.json);
  nlohmann::ordered_json j = json_document("synth");
  j["kind"] = "all";
  j["configs"] = nlohmann::ordered_json::array();
  for (const PipelineInfo* p : which) {
    for (const auto& file : pipeline_configs(*p)) {
      Target t = c.target;
      t.pipeline = p->name;
      t.config = file.string();
      const Loaded l = load(t);
      const RtlDesign d = design_of(l, t);
      const std::string label = file.lexically_relative(data_root()).string();  // configs/...
      if (c.check) {
        check_synthesizable(d, l.cfg.origin());
        fmt::print("{} ({}): synthesizes, no latches\n", label, d.top);
        continue;
      }
      // A failing iCE40 flow (Yosys 0.23's synth_ice40 -dsp aborts on quad_walker) does not cost
      // the configuration its generic numbers: it is synthesized again without it and the
      // failure reported with its result.
      SynthResult r;
      std::string ice40_error;
      try {
        r = synthesize(d, l.cfg.origin(), SynthOptions{.generic = true, .ice40 = c.ice40}, stderr);
      } catch (const Error& e) {
        if (!c.ice40) throw;
        ice40_error = e.what();
        r = synthesize(d, l.cfg.origin(), SynthOptions{.generic = true, .ice40 = false}, stderr);
      }
      const bool ice40 = c.ice40 && ice40_error.empty();
      print_summary(json.text(), label, d, r, ice40);
      if (!ice40_error.empty()) fmt::print(json.text(), "  iCE40 failed: {}\n", ice40_error);
      if (c.stages) print_stages(json.text(), r);
      std::fflush(json.text());
      nlohmann::ordered_json result = result_json(l, d, r, ice40);
      result["ice40_error"] = ice40_error.empty() ? nlohmann::ordered_json(nullptr)
                                                  : nlohmann::ordered_json(ice40_error);
      j["configs"].push_back(std::move(result));
    }
  }
  if (!c.check) json.write(j);
  return 0;
}

int run(const SynthCli& c) {
  if (c.check && c.ice40) throw Error("--check and --ice40 exclude each other");
  if (c.all) return run_all(c);
  if (c.check && !c.json.empty()) throw Error("--check and --json exclude each other");
  check_outputs({{"--json", c.json}}, c.target.inputs());
  JsonOutput json(c.json);
  const Loaded l = load(c.target);
  const RtlDesign d = design_of(l, c.target);
  if (c.check) {
    check_synthesizable(d, l.cfg.origin());
    fmt::print("{} ({}): synthesizes, no latches\n", l.cfg.origin(), d.top);
    return 0;
  }
  const SynthOptions options{.generic = true, .ice40 = c.ice40};
  const SynthResult r = synthesize(d, l.cfg.origin(), options, stderr);
  print_summary(json.text(), l.cfg.origin(), d, r, c.ice40);
  print_stages(json.text(), r);
  nlohmann::ordered_json j = json_document("synth");
  const nlohmann::ordered_json result = result_json(l, d, r, c.ice40);
  for (const auto& [k, v] : result.items()) j[k] = v;
  j["builtin"] = nullptr;
  if (c.target.user_rtl()) {  // your design against phongsim's, same configuration
    const RtlDesign ours = rtl_design(*l.pipeline, l.cfg);
    const SynthResult b = synthesize(ours, l.cfg.origin(), options, stderr);
    const auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };
    std::string line = fmt::format(
        "against phongsim's {}: {} vs {} cells ({:.2f}x), ~{} vs ~{} transistors ({:.2f}x), depth "
        "{} vs {} levels",
        ours.top, r.cells, b.cells, ratio(r.cells, b.cells), r.transistors, b.transistors,
        ratio(r.transistors, b.transistors), r.depth, b.depth);
    if (c.ice40) {
      line += fmt::format("; iCE40 {} vs {} LUT4, fmax {} vs {} MHz", r.lut4, b.lut4,
                          r.fits ? fmt::format("{:.1f}", r.fmax_mhz) : "-",
                          b.fits ? fmt::format("{:.1f}", b.fmax_mhz) : "-");
    }
    fmt::print(json.text(), "{}\n", line);
    j["builtin"] = result_json(l, ours, b, c.ice40);
  }
  json.write(j);
  return 0;
}

}  // namespace

void add_synth(CLI::App& app, Action& action) {
  auto c = std::make_shared<SynthCli>();
  auto* cmd = app.add_subcommand(
      "synth",
      "Synthesize a configuration's RTL with Yosys (cells, transistor estimate, logic depth per "
      "register; latches refused), cached by content");
  // Synthesis reads sources: no plugin (--rtl-plugin) and no Verilation (--no-build).
  c->target.add_options(*cmd, false);
  c->target.add_source_options(*cmd);
  cmd->add_flag("--ice40", c->ice40,
                "also iCE40 synthesis and nextpnr place and route (LUTs, DSPs, fmax)");
  cmd->add_flag("--all", c->all,
                "every configuration in configs/ (of the pipeline given, else of every pipeline), "
                "one line each");
  cmd->add_flag("--stages", c->stages,
                "with --all: also each configuration's depth table (a single configuration always "
                "prints it)");
  cmd->add_option("--json", c->json,
                  "also write the result as JSON (docs/json.md; - is standard output)");
  cmd->add_flag("--check", c->check,
                "only check that it synthesizes without latches (Yosys synth, no flattening, no "
                "statistics: seconds instead of minutes)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
