// phongsim synth: Yosys generic synthesis (and optionally iCE40 place and route) of a
// configuration's RTL: area, no latches (sim/explore/synth.h).
#include <fmt/format.h>

#include "app/commands.h"
#include "base/error.h"
#include "sim/explore/synth.h"

namespace phongsim::cli {
namespace {

struct SynthCli {
  Target target;
  bool ice40 = false;
  bool check = false;
};

int run(const SynthCli& c) {
  const Loaded l = load(c.target);
  const RtlDesign d = design_of(l, c.target);
  if (c.check) {
    if (c.ice40) throw Error("--check and --ice40 exclude each other");
    check_synthesizable(d, l.cfg.origin());
    fmt::print("{} ({}): synthesizes, no latches\n", l.cfg.origin(), d.top);
    return 0;
  }
  const SynthResult r =
      synthesize(d, l.cfg.origin(), SynthOptions{.generic = true, .ice40 = c.ice40}, stderr);
  fmt::print("{} ({}): {} cells, ~{} transistors, no latches{}", l.cfg.origin(), d.top, r.cells,
             r.transistors, r.cached ? " (cached)" : "");
  if (c.ice40) {
    fmt::print("; iCE40 {}: {} LUT4, {} carry, {} SB_MAC16, {} FF, {}", kSynthIce40Device, r.lut4,
               r.carry, r.mac16, r.ff,
               r.fits ? fmt::format("fmax {:.2f} MHz", r.fmax_mhz) : std::string("does not fit"));
  }
  fmt::print("\n");
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
  cmd->add_flag("--check", c->check,
                "only check that it synthesizes without latches (Yosys synth, no flattening, no "
                "statistics: seconds instead of minutes)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
