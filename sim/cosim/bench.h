// Speed of one pipeline configuration: the model alone, the Verilated RTL alone (no checking),
// and the full co-simulation, in vectors and outputs per second, with their ratios. A benchmark
// prints numbers; no test asserts a timing.
#pragma once

#include <cstdint>
#include <string>

#include "model/config.h"
#include "sim/cosim/cosim.h"

namespace phongsim {

// Rates in input vectors and output transactions (pixels) per second; they differ for pipelines
// whose inputs are programs (kb: a span's words produce its pixels).
struct BenchRate {
  double vectors_per_s = 0;
  double outputs_per_s = 0;
};

struct BenchReport {
  std::uint64_t vectors = 0;
  BenchRate model;  // model evaluations alone
  BenchRate rtl;    // the Verilated RTL alone, outputs discarded
  BenchRate cosim;  // model, RTL and scoreboard
  double rtl_cycles_per_s = 0;
  [[nodiscard]] std::string table() const;  // ratios are of outputs per second
};

BenchReport bench(const CosimSubject& subject, std::uint64_t vectors);

}  // namespace phongsim
