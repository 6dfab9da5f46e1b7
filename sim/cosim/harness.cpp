#include "sim/cosim/harness.h"

#include <fmt/format.h>

#include <optional>
#include <vector>

namespace phongsim {

HarnessResult run_harness(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                          const HarnessOptions& options, const HarnessHooks& hooks) {
  const std::uint64_t timeout =
      options.timeout != 0 ? options.timeout
                           : 100000 + options.source.longest_stall() + options.sink.longest_stall();
  Rng source_rng(options.seed, kSourceStream, 0);
  Rng sink_rng(options.seed, kSinkStream, 0);
  std::vector<std::int64_t> in(input_fields);
  std::vector<std::int64_t> out(output_fields);
  std::vector<std::int64_t> held(output_fields);  // output offered but not taken last cycle

  HarnessResult r;
  dut.reset();
  std::uint64_t next_index = 0;
  bool presenting = false;
  bool inputs_done = false;
  bool output_held = false;
  std::uint64_t last_progress = 0;
  bool tracing = false;
  std::optional<std::uint64_t> tail_end;  // set once the hooks say finished

  for (std::uint64_t cycle = 0;; ++cycle) {
    if (!options.trace_path.empty()) {
      if (!tracing && cycle == options.trace_from) {
        dut.open_trace(options.trace_path);
        tracing = true;
      } else if (tracing && cycle > options.trace_to) {
        dut.close_trace();
        tracing = false;
      }
    }
    // Drive this cycle's inputs while the clock is low. A presented transaction stays until
    // accepted; the source pattern only decides when the next one starts. Both patterns are
    // drawn every cycle, so their sequences do not depend on what the DUT does.
    const bool source_active = options.source.active(cycle, source_rng);
    const bool sink_active = options.sink.active(cycle, sink_rng);
    if (!presenting && !inputs_done && source_active) {
      if (hooks.next_input(next_index, in)) {
        dut.set_input(in);
        presenting = true;
      } else {
        inputs_done = true;
      }
    }
    const bool ready = sink_active || tail_end.has_value();
    dut.set_in_valid(presenting);
    dut.set_out_ready(ready);
    dut.settle();

    const bool in_fire = presenting && dut.in_ready();
    const bool out_valid = dut.out_valid();
    if (out_valid) dut.output(out);
    if (output_held && (!out_valid || out != held)) {
      r.reason = StopReason::protocol;
      r.message = fmt::format("cycle {}: output {} while the sink was stalling it", cycle,
                              out_valid ? "changed" : "withdrawn (valid dropped)");
      r.cycles = cycle;
      return r;
    }
    output_held = out_valid && !ready;
    if (output_held) held = out;

    bool keep_going = true;
    if (out_valid && ready) {
      if (r.outputs == 0) r.first_output_cycle = cycle;
      r.last_output_cycle = cycle;
      ++r.outputs;
      last_progress = cycle;
      keep_going = hooks.output(out, cycle);
    }
    dut.clock();
    if (dut.assertion_failed()) {
      r.reason = StopReason::protocol;
      r.message = fmt::format("cycle {}: an RTL assertion failed (message above)", cycle);
      r.cycles = cycle + 1;
      return r;
    }
    if (in_fire) {
      hooks.accepted(next_index, cycle);
      ++next_index;
      ++r.inputs;
      presenting = false;
      last_progress = cycle;
    }
    if (!keep_going) {
      r.reason = StopReason::stopped_by_hook;
      r.cycles = cycle + 1;
      return r;
    }
    if (tail_end) {
      if (cycle >= *tail_end) return r;
    } else if (inputs_done && !presenting && hooks.finished(cycle)) {
      r.cycles = cycle + 1;  // the run proper; the tail only watches for extra outputs
      tail_end = cycle + kTailCycles;
      last_progress = cycle;
    }
    if (cycle - last_progress > timeout) {
      r.reason = StopReason::deadlock;
      if (presenting) r.waiting_input = next_index;
      r.message = fmt::format(
          "cycle {}: no handshake for {} cycles ({} inputs accepted, {} outputs taken{})", cycle,
          timeout, r.inputs, r.outputs, presenting ? ", an input is waiting for in_ready" : "");
      r.cycles = cycle + 1;
      return r;
    }
  }
}

HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             std::span<const std::int64_t> vectors,
                             const std::function<void(std::span<const std::int64_t>)>& on_output) {
  const std::size_t count = vectors.size() / input_fields;
  std::size_t i = 0;
  return stream_vectors(
      dut, input_fields, output_fields,
      [&](std::span<std::int64_t> v) {
        if (i >= count) return false;
        const auto src = vectors.subspan(i * input_fields, input_fields);
        std::copy(src.begin(), src.end(), v.begin());
        ++i;
        return true;
      },
      on_output);
}

HarnessResult stream_vectors(RtlDut& dut, std::size_t input_fields, std::size_t output_fields,
                             const std::function<bool(std::span<std::int64_t>)>& next,
                             const std::function<void(std::span<const std::int64_t>)>& on_output) {
  std::uint64_t last_activity = 0;
  HarnessHooks hooks;
  hooks.next_input = [&](std::uint64_t, std::span<std::int64_t> v) { return next(v); };
  hooks.accepted = [&](std::uint64_t, std::uint64_t cycle) { last_activity = cycle; };
  hooks.output = [&](std::span<const std::int64_t> o, std::uint64_t cycle) {
    on_output(o);
    last_activity = cycle;
    return true;
  };
  hooks.finished = [&](std::uint64_t cycle) { return cycle - last_activity >= kDrainCycles; };
  return run_harness(dut, input_fields, output_fields, HarnessOptions{}, hooks);
}

}  // namespace phongsim
