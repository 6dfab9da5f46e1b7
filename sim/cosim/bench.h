// Speed of one pipeline configuration, every part on its own and together, on the same random
// vectors: the model (its batch API), a hand-written native kernel of the default configuration
// (the model's headroom), the Verilated RTL through the harness (no checking), the same top in a
// bare Verilator loop (the harness's headroom), and the full co-simulation; in vectors and outputs
// per second, with their ratios (with `jobs` > 1: the co-simulation with that many workers, and as
// many bare loops at once, the machine's own scaling); and the same RTL in Icarus Verilog through
// the same harness, on fewer vectors (Icarus is slow), for the Verilator/Icarus ratio. Each part
// but Icarus is timed in three rounds, the fastest kept. A benchmark prints numbers; no test
// asserts a timing.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "model/config.h"
#include "sim/cosim/cosim.h"

namespace phongsim {

// Rates in input vectors and output transactions (pixels) per second; they differ for pipelines
// whose inputs are programs (kb: a span's words produce its pixels).
struct BenchRate {
  double vectors_per_s = 0;
  double outputs_per_s = 0;
  double cycles_per_s = 0;  // RTL only
};

// A native kernel: the contract of PipelineModel::eval_batch, from the reset state.
using NativeKernel =
    std::function<std::size_t(std::span<const std::int64_t> in, std::vector<std::int64_t>& out)>;

struct BenchReport {
  std::uint64_t vectors = 0;
  BenchRate stimulus;               // Stimulus::vectors and InputContract::check, vectors only
  BenchRate model;                  // PipelineModel::eval_batch
  std::optional<BenchRate> native;  // when a native kernel applies to the configuration
  BenchRate rtl;                    // the Verilated RTL through the harness, outputs discarded
  BenchRate bare_rtl;               // the Verilated top in a bare loop (RtlDut::bare_run)
  BenchRate cosim;                  // model, RTL and scoreboard, one worker
  unsigned jobs = 1;                // > 1: co-simulation with that many workers too
  BenchRate cosim_jobs;
  BenchRate bare_rtl_jobs;  // `jobs` bare loops at once, each on its own thread (all together)
  std::string native_note;  // why there is no native figure, or what it was checked against
  // The RTL in Icarus Verilog through the harness, on the first icarus_vectors bench vectors
  // (about kIcarusCycles cycles' worth); absent when not measured.
  std::optional<BenchRate> icarus;
  std::uint64_t icarus_vectors = 0;

  // The co-simulation / RTL ratio a co-simulation on one core would reach if its only costs
  // besides the RTL were the stimulus and the model, each at its own measured rate (per vector:
  // 1/rtl / (1/rtl + 1/stimulus + 1/model)): what the co-simulation's bookkeeping is measured
  // against, and its floor when the goal is above it.
  [[nodiscard]] double cosim_ceiling() const;

  // How the machine scales the RTL alone: `jobs` bare loops at once against one (cycles per
  // second); the yardstick for the co-simulation's jobs / 1 job.
  [[nodiscard]] double bare_jobs_ratio() const;

  [[nodiscard]] std::string table() const;  // ratios are of outputs per second (RTL: cycles)
};

// Icarus's share of a bench: as many of the bench vectors as take about this many cycles in the
// Verilated RTL (at least one), since Icarus simulates some 10^3 to 10^4 cycles per second.
inline constexpr std::uint64_t kIcarusCycles = 5000;

// `native`: the pipeline's kernel when it implements this configuration (else empty); it is run
// on the bench vectors and must give the model's outputs bit for bit (Error otherwise).
// `icarus` (optional): makes the DUT factory of the same design in Icarus Verilog (icarus_dut.h;
// called once the bench vectors are made), timed through the harness on about `icarus_cycles`
// cycles' worth of the vectors.
BenchReport bench(const CosimSubject& subject, std::uint64_t vectors, const NativeKernel& native,
                  unsigned jobs = 1, const std::function<DutFactory()>& icarus = {},
                  std::uint64_t icarus_cycles = kIcarusCycles);

}  // namespace phongsim
