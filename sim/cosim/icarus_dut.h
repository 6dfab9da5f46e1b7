// A second simulator: the same design run by Icarus Verilog (Debian's iverilog) behind the
// RtlDut interface, so the harness, stall patterns and scoreboard that check Verilator's build
// check Icarus's the same way (`phongsim cosim|eval --simulator icarus`, docs/cosim.md).
//
// The design is compiled with `iverilog -g2012` together with a generated testbench that
// instantiates the top with the configuration's parameters and serves the harness's per-cycle
// protocol (rtl_dut.h) over a pipe to a `vvp` process: one line per settle and per clock. Icarus
// is four-state, so an X or Z where Verilator would see a 0 or 1 shows: X/Z on a handshake
// output, or on a data output while it is valid, is an Error naming the port and cycle. An RTL
// $error counts as a failed assertion, as with Verilator.
#pragma once

#include <cstdio>

#include "model/pipeline.h"
#include "sim/cosim/rtl_plugin.h"

namespace phongsim {

// Checks the design's ports against the contract (check_ports: one line naming the first
// difference), then compiles `design` (errors from iverilog in the Error, one line each) into a
// temporary directory that lives as long as the factory; each DUT is one vvp process. `model` must
// outlive the factory.
[[nodiscard]] DutFactory icarus_duts(const RtlDesign& design, const PipelineModel& model,
                                     std::FILE* log);

}  // namespace phongsim
