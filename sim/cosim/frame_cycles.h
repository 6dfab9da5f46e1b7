// Cycle accounting: what each pipeline's cycle model (sim/pipelines/registry.h,
// PipelineInfo::cycles) computes, the RTL's measurement is checked against, and `phongsim render`
// reports per frame.
#pragma once

#include <cstdint>
#include <vector>

namespace phongsim {

// Where the clocks of a stream through phongsim's RTL go, stall-free except where the sink says
// otherwise (docs/system.md): cycles = fill + outputs + setup + empty rows + stalls.
struct FrameCycles {
  std::uint64_t cycles = 0;            // from the first input offered to the last output taken
  std::uint64_t outputs = 0;           // output transactions (at most one per cycle)
  std::uint64_t fill_cycles = 0;       // the pipeline's own latency: registers in and out
  std::uint64_t setup_cycles = 0;      // control without an output: programs, rows, span headers
  std::uint64_t empty_row_cycles = 0;  // rows of a triangle's box that cover no pixel
  std::uint64_t stall_cycles = 0;      // outputs waiting for the sink (backpressure)
};

// The cycles of `n` vectors through a unit that takes one per clock with `latency`; each
// vector's own (PipelineInfo::cycles) is one cycle and one output.
[[nodiscard]] inline FrameCycles one_per_clock_cycles(int latency, std::uint64_t n,
                                                      std::vector<FrameCycles>* per_vector) {
  if (per_vector != nullptr) per_vector->assign(n, FrameCycles{.cycles = 1, .outputs = 1});
  if (n == 0) return {};
  const auto fill = static_cast<std::uint64_t>(latency);
  return {.cycles = fill + n, .outputs = n, .fill_cycles = fill};
}

}  // namespace phongsim
