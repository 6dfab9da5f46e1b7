// phongsim synth: Yosys generic synthesis (and optionally iCE40 place and route) of a
// configuration's RTL: area, no latches (sim/explore/synth.h).
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "sim/explore/synth.h"

namespace phongsim::cli {
namespace {

struct SynthCli {
  Target target;
  bool ice40 = false;
  std::string json;
  bool check = false;
};

int run(const SynthCli& c) {
  if (c.check && c.ice40) throw Error("--check and --ice40 exclude each other");
  if (c.check && !c.json.empty()) throw Error("--check and --json exclude each other");
  check_distinct({{"--json", c.json}, {"--config", c.target.config}});
  JsonOutput json(c.json);
  const Loaded l = load(c.target);
  const RtlDesign d = design_of(l, c.target);
  if (c.check) {
    check_synthesizable(d, l.cfg.origin());
    fmt::print("{} ({}): synthesizes, no latches\n", l.cfg.origin(), d.top);
    return 0;
  }
  const SynthResult r =
      synthesize(d, l.cfg.origin(), SynthOptions{.generic = true, .ice40 = c.ice40}, stderr);
  std::FILE* const out = json.text();
  fmt::print(out, "{} ({}): {} cells, ~{} transistors, no latches{}", l.cfg.origin(), d.top,
             r.cells, r.transistors, r.cached ? " (cached)" : "");
  if (c.ice40) {
    fmt::print(out, "; iCE40 {}: {} LUT4, {} carry, {} SB_MAC16, {} FF, {}", kSynthIce40Device,
               r.lut4, r.carry, r.mac16, r.ff,
               r.fits ? fmt::format("fmax {:.2f} MHz", r.fmax_mhz) : std::string("does not fit"));
  }
  fmt::print(out, "\n");
  nlohmann::ordered_json j = json_document("synth");
  j["pipeline"] = l.pipeline->name;
  j["config"] = l.cfg.name();
  j["config_path"] = l.cfg.origin();
  j["top"] = d.top;
  j["key"] = r.key;
  j["cached"] = r.cached;
  j["generic"] = {{"cells", r.cells}, {"transistors", r.transistors}};
  j["ice40"] = nullptr;
  if (c.ice40) {
    j["ice40"] = {{"device", kSynthIce40Device},
                  {"lut4", r.lut4},
                  {"carry", r.carry},
                  {"mac16", r.mac16},
                  {"ff", r.ff},
                  {"fits", r.fits},
                  {"fmax_mhz",
                   r.fits ? nlohmann::ordered_json(r.fmax_mhz) : nlohmann::ordered_json(nullptr)}};
  }
  json.write(j);
  return 0;
}

}  // namespace

void add_synth(CLI::App& app, Action& action) {
  auto c = std::make_shared<SynthCli>();
  auto* cmd = app.add_subcommand(
      "synth",
      "Synthesize a configuration's RTL with Yosys (cells, transistor estimate; latches refused), "
      "cached by content");
  c->target.add_options(*cmd);
  cmd->add_flag("--ice40", c->ice40,
                "also iCE40 synthesis and nextpnr place and route (LUTs, DSPs, fmax)");
  cmd->add_option("--json", c->json,
                  "also write the result as JSON (docs/json.md; - is standard output)");
  cmd->add_flag("--check", c->check,
                "only check that it synthesizes without latches (Yosys synth, no flattening, no "
                "statistics: seconds instead of minutes)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
