// Real area and speed of a configuration's RTL: Yosys generic synthesis (cells, transistor
// estimate) and iCE40 synthesis with place and route (LUTs, carries, DSPs, flip-flops, fmax),
// cached by content so a sweep pays for each configuration once.
//
// The design (top, sources, parameters: sim/cosim/rtl_plugin.h) is what the co-simulation
// Verilates; its parameters become yosys `chparam -set`. Both flows refuse latches.
//
// Generic: `synth -flatten -top <top>`; `cells` is the flattened cell count, `transistors` Yosys's
// `stat -tech cmos` estimate after `dffunmap` (enables and synchronous resets become gates so the
// flip-flops are costed; the few asynchronous-reset flip-flops have no cost in Yosys's table and
// are left out).
//
// Logic depth (the generic flow's clock estimate, for every design, fitting an iCE40 or not): the
// longest chain of Yosys's internal gates ($_NOT_, $_AND_, $_OR_, $_XOR_, $_MUX_, ... as `synth`'s
// ABC mapping leaves them, before `dffunmap`: each gate counts one level) from a start point (an
// input port or a flip-flop's output) to an end point (any input of a flip-flop but its clock —
// data, enable, reset — or an output port). It is counted per destination register, named by its
// RTL name with the hierarchy path (`u_core.prod_q`: the public wire holding the flip-flop's output
// whose name ends in `_q`, `_q2`, ..., innermost first), and per output port, with the start point
// of the deepest path into it: the register whose inputs are deepest is where another pipeline
// register would pay. Levels are not converted into a frequency: the gates have no delays here.
//
// iCE40: the top is wrapped in serial shift registers (so that any port width needs five pins),
// flattened on its own and mapped with `synth_ice40 -dsp -noflatten`; lut4/carry/mac16/ff count the
// top's cells only, not the wrapper's. nextpnr-ice40 then places and routes the whole on an
// UltraPlus UP5K (kSynthIce40Device: the largest iCE40 with SB_MAC16 DSPs, 5280 LCs and 8 DSPs)
// aiming at kSynthIce40TargetMhz with a fixed seed; fmax_mhz is what it achieved. A design that
// does not fit the device (more DSPs or LCs than it has) gets fits = false and fmax_mhz = 0.
//
// Cache: rtl_cache_dir() / "synth" / <key>.json, the key hashing the top's RTL sources (contents),
// the -G parameters, the options, the flow and the tool versions (`yosys -V`,
// `nextpnr-ice40 --version`).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "sim/cosim/rtl_plugin.h"

namespace phongsim {

inline constexpr const char* kSynthIce40Device = "up5k";   // nextpnr-ice40 --up5k
inline constexpr const char* kSynthIce40Package = "sg48";  // --package
inline constexpr int kSynthIce40TargetMhz = 100;           // --freq: above what iCE40 reaches
inline constexpr int kSynthIce40Seed = 1;                  // --seed: reproducible placement

struct SynthOptions {
  bool generic = true;
  bool ice40 = false;
};

// Logic depth into one destination: a register (all flip-flops of one RTL register) or an
// output port.
struct StageDepth {
  std::string to;           // "u_core.prod_q", or the output port's name
  bool output = false;      // `to` is an output port
  std::int64_t bits = 0;    // flip-flops (or port bits) in the destination
  std::int64_t levels = 0;  // gates on the deepest path into it
  std::string from;         // where that path starts: a register or an input port ("" if constant)
};

struct SynthResult {
  // Yosys generic synthesis (synth -top; flattened): cell count and `stat -tech cmos` transistor
  // estimate.
  std::int64_t cells = -1, transistors = -1;
  // Logic depth in gate levels (the largest of `stages`) and per destination, deepest first, then
  // by name.
  std::int64_t depth = -1;
  std::vector<StageDepth> stages;
  // iCE40: synth_ice40 -dsp (SB_MAC16 for large multipliers), then nextpnr-ice40 on the UP5K. A
  // design that does not fit has fits = false and fmax_mhz = 0.
  std::int64_t lut4 = -1, carry = -1, mac16 = -1, ff = -1;
  bool fits = true;
  double fmax_mhz = -1;
  bool cached = false;  // came from the cache
  std::string key;      // cache key
};

// Synthesizes the configuration's RTL top with its -G parameters, checking there are no latches
// (Error otherwise). Returns a cached result without running the tools when there is one; new
// results are written to the cache atomically. `log` (may be null) gets one line per synthesis or
// place-and-route run. Errors: a missing tool (naming it and its Debian package), a failing tool
// (with the last line of its log).
// `label` (the configuration file) names the design in messages.
SynthResult synthesize(const RtlDesign& design, const std::string& label,
                       const SynthOptions& options, std::FILE* log);

// Logic depth of a flattened Yosys netlist (`write_json` of the generic flow) of module `top`:
// one StageDepth per register and output port, deepest first. Error on a combinational loop.
std::vector<StageDepth> logic_depth(const std::string& netlist_json, const std::string& top);

// The quick check of the test suite: Yosys generic `synth` (not flattened, no statistics) of the
// design with its parameters, `check -assert`, no latches. Error naming the problem otherwise.
void check_synthesizable(const RtlDesign& design, const std::string& label);

}  // namespace phongsim
