// Streams transactions through an RtlDut under source-idle and sink-backpressure patterns and
// checks the handshake rules. The cycle loop itself is sim/cosim/cycle_loop.h, run by the DUT a
// batch at a time (inside the plugin for Verilated RTL); the harness feeds it inputs and the
// stall patterns' decisions and hands what happened to the caller's hooks, which decide what the
// transactions mean: co-simulation (cosim.h) checks outputs against the model, eval collects them.
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
  // Stall patterns of shard k of a co-simulation are drawn from stream position k (0: the whole
  // run's own), so that shards do not repeat each other's stalls.
  std::uint64_t stall_stream = 0;
};

// Input vectors for the harness, from the hook: `vectors` (input fields each, back to back) are
// the next ones in order and stay valid until the hook is called again. `last`: no vectors after
// these; `outputs_due` then says how many outputs all the run's vectors owe (the run is finished
// once they are in), or stays unset when nobody knows (the run then ends kDrainCycles after the
// last input or output).
struct InputBatch {
  std::span<const std::int64_t> vectors;
  bool last = false;
  std::optional<std::uint64_t> outputs_due;
};

struct HarnessHooks {
  // The vectors from input `index` on.
  std::function<InputBatch(std::uint64_t index)> next_inputs;
  // What happened since the last call, in order: the acceptance cycle of each input accepted
  // (inputs are accepted in index order) and each output taken with its cycle. Returns how many
  // of the outputs are right: all of them to go on; fewer stops the run at the first wrong one
  // (the hook reports why).
  std::function<std::size_t(std::span<const std::uint64_t> accepted,
                            std::span<const std::int64_t> outputs,
                            std::span<const std::uint64_t> output_cycles)>
      check;
};

// unknown_value: a four-state DUT showed X or Z where a value was due (UnknownValue).
enum class StopReason { finished, stopped_by_hook, deadlock, protocol, assertion, unknown_value };

struct HarnessResult {
  StopReason reason = StopReason::finished;
  std::string message;       // for deadlock, protocol, assertion and unknown_value errors
  std::uint64_t cycles = 0;  // up to the stop (finished: the cycle all outputs were in)
  std::uint64_t inputs = 0;
  std::uint64_t outputs = 0;
  std::uint64_t first_output_cycle = 0;
  std::uint64_t last_output_cycle = 0;
  std::optional<std::uint64_t> waiting_input;  // on deadlock: input presented but not accepted
  // The stall patterns at work: cycles the source withheld an input it had, cycles an output
  // waited for the sink.
  std::uint64_t source_idle_cycles = 0;
  std::uint64_t sink_stall_cycles = 0;
  // The drain window after the run finished, in cycles (0 when it did not finish).
  std::uint64_t drain_cycles = 0;
};

// Resets the DUT and runs until the run is finished (every input accepted and every output due
// taken; then the sink stays ready with no input for a drain window — kTailCycles plus the stall
// patterns' longest stalls, or twice the longest stretch without a handshake the run had, if
// longer — so that an extra output after the last expected one still reaches the check hook), the
// hook stops it at a wrong output, no handshake happens for the timeout, or the DUT breaks the
// valid/ready rules (an output withdrawn or changed while the sink stalls it, or an RTL assertion).
// The result is the same as if every output were checked the cycle it is taken: a run stopped at a
// wrong output ends in that cycle.
HarnessResult run_harness(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                          const HarnessOptions& options, const HarnessHooks& hooks);

// Streams `vectors` (flattened, input_fields each) through the DUT without stalls and hands every
// output to `on_output`, without a model: the run ends once the DUT has been silent for
// kDrainCycles after the last input and output.
HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             std::span<const std::int64_t> vectors,
                             const std::function<void(std::span<const std::int64_t>)>& on_output);

// The same with the inputs drawn one at a time from `next` (it fills one vector and returns
// false when there are no more), so that a run's memory does not grow with its length.
HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             const std::function<bool(std::span<std::int64_t>)>& next,
                             const std::function<void(std::span<const std::int64_t>)>& on_output);

}  // namespace phongsim
