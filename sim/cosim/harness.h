// Cycle loop that streams transactions through an RtlDut under source-idle and sink-backpressure
// patterns and checks the handshake rules. What the transactions mean is left to the caller's
// hooks: co-simulation (cosim.h) checks outputs against the model, eval collects them.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "sim/cosim/rtl_dut.h"
#include "sim/cosim/stall.h"

namespace phongsim {

struct HarnessOptions {
  StallPattern source;     // when the source offers its next transaction
  StallPattern sink;       // when the sink is ready
  std::uint64_t seed = 1;  // for random stall patterns
  // Cycles without any handshake before "deadlock"; 0 = automatic: 100000 plus the longest
  // stall the two patterns can make.
  std::uint64_t timeout = 0;
  // Waveform: cycles [trace_from, trace_to] go to trace_path when it is not empty.
  std::string trace_path;
  std::uint64_t trace_from = 0;
  std::uint64_t trace_to = UINT64_MAX;
};

struct HarnessHooks {
  // Fills input transaction `index`; returns false when there are no more.
  std::function<bool(std::uint64_t index, std::span<std::int64_t> in)> next_input;
  // The DUT accepted input `index` in `cycle`.
  std::function<void(std::uint64_t index, std::uint64_t cycle)> accepted;
  // The DUT produced an output in `cycle`; return false to stop (e.g. on a mismatch).
  std::function<bool(std::span<const std::int64_t> out, std::uint64_t cycle)> output;
  // Called once all inputs are accepted: true when no more outputs are due.
  std::function<bool(std::uint64_t cycle)> finished;
};

enum class StopReason { finished, stopped_by_hook, deadlock, protocol };

struct HarnessResult {
  StopReason reason = StopReason::finished;
  std::string message;       // for deadlock and protocol errors
  std::uint64_t cycles = 0;  // up to the stop (finished: the cycle all outputs were in)
  std::uint64_t inputs = 0;
  std::uint64_t outputs = 0;
  std::uint64_t first_output_cycle = 0;
  std::uint64_t last_output_cycle = 0;
  std::optional<std::uint64_t> waiting_input;  // on deadlock: input presented but not accepted
};

// Resets the DUT and runs until the hooks say finished, a hook stops the run, no handshake
// happens for the timeout, or the DUT breaks the valid/ready rules (an output withdrawn or
// changed while the sink stalls it, or an RTL assertion). Once finished, it keeps the sink
// ready for kTailCycles more cycles so that an extra output after the last expected one still
// reaches the output hook.
inline constexpr std::uint64_t kTailCycles = 64;
HarnessResult run_harness(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                          const HarnessOptions& options, const HarnessHooks& hooks);

// Streams `vectors` (flattened, input_fields each) through the DUT without stalls and hands every
// output to `on_output`, without a model: the run ends once the DUT has been silent for
// kDrainCycles after the last input and output.
inline constexpr std::uint64_t kDrainCycles = 1000;
HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             std::span<const std::int64_t> vectors,
                             const std::function<void(std::span<const std::int64_t>)>& on_output);

// The same with the inputs drawn one at a time from `next` (it fills one vector and returns
// false when there are no more), so that a run's memory does not grow with its length.
HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             const std::function<bool(std::span<std::int64_t>)>& next,
                             const std::function<void(std::span<const std::int64_t>)>& on_output);

}  // namespace phongsim
