#include "sim/cosim/harness.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <vector>

namespace phongsim {
namespace {

constexpr std::size_t kStallBlock = 4096;   // cycles of stall decisions per refill
constexpr std::size_t kOutputBlock = 4096;  // outputs (and accepts) recorded per call

// The stall patterns' decisions, drawn every cycle in cycle order (so they do not depend on what
// the DUT does) a block of cycles ahead.
class Stalls {
 public:
  Stalls(const HarnessOptions& o)
      : source_(o.source),
        sink_(o.sink),
        source_rng_(o.seed, kSourceStream, o.stall_stream),
        sink_rng_(o.seed, kSinkStream, o.stall_stream),
        source_bits_(kStallBlock),
        sink_bits_(kStallBlock) {}

  void next_block(CycleBatch& b) {
    b.stall_base += b.stall_count;
    decide(source_, source_rng_, b.stall_base, source_bits_);
    decide(sink_, sink_rng_, b.stall_base, sink_bits_);
    b.source = source_bits_.data();
    b.sink = sink_bits_.data();
    b.stall_count = kStallBlock;
  }

 private:
  static void decide(const StallPattern& p, Rng& rng, std::uint64_t base,
                     std::vector<std::uint8_t>& bits) {
    if (p.never_stalls()) {  // active() every cycle, no random numbers drawn
      std::fill(bits.begin(), bits.end(), 1);
      return;
    }
    for (std::size_t i = 0; i < bits.size(); ++i) bits[i] = p.active(base + i, rng) ? 1 : 0;
  }

  const StallPattern& source_;
  const StallPattern& sink_;
  Rng source_rng_;
  Rng sink_rng_;
  std::vector<std::uint8_t> source_bits_;
  std::vector<std::uint8_t> sink_bits_;
};

}  // namespace

HarnessResult run_harness(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                          const HarnessOptions& options, const HarnessHooks& hooks) {
  CycleBatch b;
  b.input_fields = input_fields;
  b.output_fields = output_fields;
  b.timeout = options.timeout != 0
                  ? options.timeout
                  : 100000 + options.source.longest_stall() + options.sink.longest_stall();
  b.tail = kTailCycles + options.source.longest_stall() + options.sink.longest_stall();
  std::vector<std::int64_t> held(output_fields);
  b.held = held.data();
  if (!options.trace_path.empty()) {
    b.trace_path = options.trace_path.c_str();
    b.trace_from = options.trace_from;
    b.trace_to = options.trace_to;
  }
  // With a waveform, one output per call: a run stopped at a wrong output then dumps no cycle
  // beyond it.
  const std::size_t per_call = options.trace_path.empty() ? kOutputBlock : 1;
  std::vector<std::int64_t> outputs(per_call * output_fields);
  std::vector<std::uint64_t> output_cycles(per_call);
  std::vector<std::uint64_t> accept_cycles(kOutputBlock);
  b.outputs = outputs.data();
  b.output_cycles = output_cycles.data();
  b.output_capacity = per_call;
  b.accept_cycles = accept_cycles.data();
  b.accept_capacity = accept_cycles.size();
  Stalls stalls(options);
  stalls.next_block(b);

  HarnessResult r;
  CycleState st;
  dut.reset();
  while (true) {
    // An X or Z stops the run where it showed; the outputs taken before it are checked first.
    std::optional<std::string> unknown;
    try {
      dut.run(b, st);
    } catch (const UnknownValue& e) {
      unknown = e.what();
    }
    r.source_idle_cycles = st.source_idle;
    r.sink_stall_cycles = st.sink_stalled;
    const std::uint64_t inputs_before = st.inputs - b.accepts_written;
    const std::uint64_t outputs_before = st.outputs - b.outputs_written;
    const std::size_t good =
        b.accepts_written + b.outputs_written == 0
            ? 0
            : hooks.check(std::span(accept_cycles.data(), b.accepts_written),
                          std::span(outputs.data(), b.outputs_written * output_fields),
                          std::span(output_cycles.data(), b.outputs_written));
    // A wrong output stops the run in its cycle, unless an assertion fired in that same cycle
    // (the assertion is checked first).
    if (good < b.outputs_written &&
        !(b.stop == LoopStop::assertion && output_cycles[good] == st.cycle)) {
      const std::uint64_t at = output_cycles[good];
      r.reason = StopReason::stopped_by_hook;
      r.cycles = at + 1;
      r.outputs = outputs_before + good + 1;
      r.inputs =
          inputs_before + static_cast<std::uint64_t>(
                              std::upper_bound(accept_cycles.begin(),
                                               accept_cycles.begin() + b.accepts_written, at) -
                              accept_cycles.begin());
      r.first_output_cycle = outputs_before == 0 ? output_cycles[0] : st.first_output_cycle;
      r.last_output_cycle = at;
      return r;
    }
    b.accepts_written = 0;
    b.outputs_written = 0;
    r.inputs = st.inputs;
    r.outputs = st.outputs;
    r.first_output_cycle = st.first_output_cycle;
    r.last_output_cycle = st.last_output_cycle;
    if (unknown) {
      r.reason = StopReason::unknown_value;
      r.message = *unknown;
      r.cycles = st.cycle + 1;
      return r;
    }
    switch (b.stop) {
      case LoopStop::need_inputs: {
        const InputBatch in = hooks.next_inputs(st.next_index);
        b.inputs = in.vectors.data();
        b.input_base = st.next_index;
        b.input_count = in.vectors.size() / input_fields;
        b.inputs_final = in.last;
        if (in.last) {
          if (in.outputs_due) {
            b.outputs_due = *in.outputs_due;
          } else {
            b.drain = kDrainCycles;
          }
        }
        break;
      }
      case LoopStop::need_stalls:
        stalls.next_block(b);
        break;
      case LoopStop::buffer_full:
        break;
      case LoopStop::finished:
        r.cycles = st.finish_cycles;
        r.drain_cycles = st.tail_end + 1 - st.finish_cycles;
        return r;
      case LoopStop::deadlock:
        r.reason = StopReason::deadlock;
        if (st.presenting) r.waiting_input = st.next_index;
        r.message = fmt::format(
            "cycle {}: no handshake for {} cycles ({} inputs accepted, {} outputs taken{})",
            st.cycle, b.timeout, r.inputs, r.outputs,
            st.presenting ? ", an input is waiting for in_ready" : "");
        r.cycles = st.cycle + 1;
        return r;
      case LoopStop::held_changed:
        r.reason = StopReason::protocol;
        r.message = fmt::format("cycle {}: output {} while the sink was stalling it", st.cycle,
                                b.held_withdrawn ? "withdrawn (valid dropped)" : "changed");
        r.cycles = st.cycle;
        return r;
      case LoopStop::assertion:
        r.reason = StopReason::assertion;
        r.message = fmt::format(
            "cycle {}: the design's $error, $fatal or assertion fired (its message above)",
            st.cycle);
        r.cycles = st.cycle + 1;
        return r;
    }
  }
}

HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             std::span<const std::int64_t> vectors,
                             const std::function<void(std::span<const std::int64_t>)>& on_output) {
  HarnessHooks hooks;
  // 1024 vectors at a time, as a co-simulation's scoreboard hands them over.
  hooks.next_inputs = [&](std::uint64_t index) {
    constexpr std::size_t kBatch = 1024;
    const std::size_t at = std::min<std::size_t>(index * input_fields, vectors.size());
    InputBatch in;
    in.vectors = vectors.subspan(at, std::min(kBatch * input_fields, vectors.size() - at));
    in.last = at + in.vectors.size() == vectors.size();
    return in;
  };
  hooks.check = [&](std::span<const std::uint64_t>, std::span<const std::int64_t> outputs,
                    std::span<const std::uint64_t> cycles) {
    for (std::size_t i = 0; i < cycles.size(); ++i) {
      on_output(outputs.subspan(i * output_fields, output_fields));
    }
    return cycles.size();
  };
  return run_harness(dut, input_fields, output_fields, HarnessOptions{}, hooks);
}

HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             const std::function<bool(std::span<std::int64_t>)>& next,
                             const std::function<void(std::span<const std::int64_t>)>& on_output) {
  // A batch at a time: the harness asks for more only once it has taken the previous batch.
  constexpr std::size_t kBatch = 1024;
  std::vector<std::int64_t> buffer(kBatch * input_fields);
  HarnessHooks hooks;
  hooks.next_inputs = [&](std::uint64_t) {
    std::size_t n = 0;
    bool more = true;
    while (n < kBatch && (more = next(std::span(buffer).subspan(n * input_fields, input_fields)))) {
      ++n;
    }
    InputBatch in;
    in.vectors = std::span<const std::int64_t>(buffer).first(n * input_fields);
    in.last = !more;
    return in;
  };
  hooks.check = [&](std::span<const std::uint64_t>, std::span<const std::int64_t> outputs,
                    std::span<const std::uint64_t> cycles) {
    for (std::size_t i = 0; i < cycles.size(); ++i) {
      on_output(outputs.subspan(i * output_fields, output_fields));
    }
    return cycles.size();
  };
  return run_harness(dut, input_fields, output_fields, HarnessOptions{}, hooks);
}

}  // namespace phongsim
