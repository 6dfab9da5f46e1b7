// Speed of one pipeline configuration: the model alone, the Verilated RTL alone (no checking),
// and the full co-simulation, in vectors per second, with their ratios. A benchmark prints
// numbers; no test asserts a timing.
#pragma once

#include <cstdint>
#include <string>

#include "model/config.h"
#include "sim/cosim.h"
#include "sim/pipelines.h"

namespace phongsim {

struct BenchReport {
  std::uint64_t vectors = 0;
  double model_per_s = 0;  // model evaluations per second
  double rtl_per_s = 0;    // vectors per second through the Verilated RTL, outputs discarded
  double rtl_cycles_per_s = 0;
  double cosim_per_s = 0;  // vectors per second with model, RTL and scoreboard
  [[nodiscard]] std::string table() const;
};

BenchReport bench(const PipelineInfo& pipeline, const Config& cfg, PipelineModel& model,
                  const DutFactory& make_dut, std::uint64_t vectors);

}  // namespace phongsim
