// The harness's cycle loop (sim/cosim/harness.h), one batch at a time: the harness hands over
// input vectors and the stall patterns' decisions for a range of cycles, the loop drives the DUT
// until it needs more of either, its output buffer is full, or the run ends, and records every
// accepted input and every output taken (with its cycle). The harness then checks the batch and
// calls again. Plain data and a template, so the same loop runs in the harness on any RtlDut and
// inside a Verilated plugin on the top itself (verilated_dut.h), without a virtual call per cycle.
//
// One cycle (the rules of docs/cosim.md):
//   the source pattern decides whether the next input is presented (a presented input stays
//   until accepted); inputs are driven while the clock is low; settle; sample in_ready and
//   out_valid; an output held by the sink last cycle must still be valid and unchanged; an
//   output is taken when the sink is ready; clock; an RTL assertion stops the run; an input is
//   accepted when it was presented and in_ready was high.
// Once every input is in and the run's outputs are in (finish rule below), the sink stays ready
// and no input comes for a drain window, so that an extra output still shows: at least `tail`
// cycles, and at least twice the longest stretch without a handshake the run had (a design that
// can fall silent that long can also answer that late). No handshake for `timeout` cycles before
// the drain is a deadlock.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace phongsim {

// After the last expected output the sink stays ready at least this many cycles (the harness adds
// the stall patterns' longest stalls), so that an extra output still reaches the checks.
inline constexpr std::uint64_t kTailCycles = 1024;
// Without a model to say how many outputs are due (eval, bench): the run ends once the DUT has
// been silent this many cycles after the last input and output.
inline constexpr std::uint64_t kDrainCycles = 1000;

enum class LoopStop : std::uint8_t {
  need_inputs,   // every supplied input is presented and more may come
  need_stalls,   // the stall decisions supplied are used up
  buffer_full,   // the output or accept record is full
  finished,      // the run is over (after its drain window)
  deadlock,      // no handshake for `timeout` cycles
  held_changed,  // an output the sink stalled was withdrawn or changed
  assertion,     // an RTL assertion fired
};

// What the harness hands the loop for one call, and what the call recorded. The caller owns
// every buffer.
struct CycleBatch {
  // ---- fixed for a run ----
  std::size_t input_fields = 0;
  std::size_t output_fields = 0;
  std::uint64_t timeout = 100000;
  std::uint64_t tail = kTailCycles;
  // Finish rule: every input in, and `outputs_due` outputs taken; or, when drain > 0 (no model
  // says how many outputs are due), no input accepted and no output taken for `drain` cycles.
  std::uint64_t outputs_due = UINT64_MAX;
  std::uint64_t drain = 0;
  // Waveform of cycles [trace_from, trace_to] when trace_path is set.
  const char* trace_path = nullptr;
  std::uint64_t trace_from = 0;
  std::uint64_t trace_to = UINT64_MAX;
  std::int64_t* held = nullptr;  // output_fields: the output the sink stalled last cycle

  // ---- supplied before a call ----
  const std::int64_t* inputs = nullptr;  // vectors input_base .. input_base + input_count - 1
  std::uint64_t input_base = 0;
  std::uint64_t input_count = 0;
  bool inputs_final = false;             // no vectors after these
  const std::uint8_t* source = nullptr;  // per cycle from stall_base: 1 = source active
  const std::uint8_t* sink = nullptr;    // ... 1 = sink ready
  std::uint64_t stall_base = 0;
  std::uint64_t stall_count = 0;
  std::int64_t* outputs = nullptr;  // output_capacity outputs of output_fields each
  std::uint64_t* output_cycles = nullptr;
  std::size_t output_capacity = 0;
  std::uint64_t* accept_cycles = nullptr;  // accept_capacity entries
  std::size_t accept_capacity = 0;

  // ---- recorded by a call (the caller zeroes the counts after reading them) ----
  std::size_t outputs_written = 0;
  std::size_t accepts_written = 0;
  LoopStop stop = LoopStop::need_inputs;
  bool held_withdrawn = false;  // held_changed: out_valid dropped (else the data changed)
};

// The loop's state between calls; zero for a new run.
struct CycleState {
  std::uint64_t cycle = 0;       // the cycle the next call starts with
  std::uint64_t next_index = 0;  // the next input to present
  std::uint64_t inputs = 0;      // accepted
  std::uint64_t outputs = 0;     // taken
  std::uint64_t first_output_cycle = 0;
  std::uint64_t last_output_cycle = 0;
  std::uint64_t last_progress = 0;  // last handshake (deadlock detection)
  std::uint64_t last_activity = 0;  // last handshake, not reset by finishing (drain rule)
  std::uint64_t finish_cycles = 0;  // the run's length: set when it finished (before the tail)
  std::uint64_t tail_end = 0;
  std::uint64_t longest_quiet = 0;  // the longest stretch of cycles without a handshake so far
  std::uint64_t source_idle = 0;    // cycles the source pattern withheld the next input
  std::uint64_t sink_stalled = 0;   // cycles an output waited for the sink
  bool presenting = false;
  bool inputs_done = false;
  bool output_held = false;
  bool tailing = false;
  bool tracing = false;
};

// The loop over any DUT with the per-cycle methods of RtlDut (rtl_dut.h).
template <class Dut>
void run_cycles(Dut& dut, CycleBatch& b, CycleState& st) {
  const std::size_t n_in = b.input_fields;
  const std::size_t n_out = b.output_fields;
  for (;; ++st.cycle) {
    const std::uint64_t c = st.cycle;
    // Everything that may make the loop return comes first: the cycle then restarts cleanly.
    if (c - b.stall_base >= b.stall_count) {
      b.stop = LoopStop::need_stalls;
      return;
    }
    if (b.outputs_written == b.output_capacity || b.accepts_written == b.accept_capacity) {
      b.stop = LoopStop::buffer_full;
      return;
    }
    const bool source_active = b.source[c - b.stall_base] != 0;
    const bool sink_active = b.sink[c - b.stall_base] != 0;
    if (!st.presenting && !st.inputs_done && source_active) {
      if (st.next_index < b.input_base + b.input_count) {
        dut.set_input(std::span(b.inputs + (st.next_index - b.input_base) * n_in, n_in));
        st.presenting = true;
      } else if (b.inputs_final) {
        st.inputs_done = true;
      } else {
        b.stop = LoopStop::need_inputs;
        return;
      }
    } else if (!source_active && !st.presenting && !st.inputs_done) {
      ++st.source_idle;
    }
    if (b.trace_path != nullptr) {
      if (!st.tracing && c == b.trace_from) {
        dut.open_trace(b.trace_path);
        st.tracing = true;
      } else if (st.tracing && c > b.trace_to) {
        dut.close_trace();
        st.tracing = false;
      }
    }
    const bool ready = sink_active || st.tailing;
    dut.set_in_valid(st.presenting);
    dut.set_out_ready(ready);
    dut.settle();

    const bool in_fire = st.presenting && dut.in_ready();
    const bool out_valid = dut.out_valid();
    std::int64_t* out = b.outputs + b.outputs_written * n_out;
    if (out_valid) dut.output(std::span(out, n_out));
    if (st.output_held && (!out_valid || !std::equal(out, out + n_out, b.held))) {
      b.stop = LoopStop::held_changed;
      b.held_withdrawn = !out_valid;
      return;
    }
    st.output_held = out_valid && !ready;
    if (st.output_held) {
      std::copy(out, out + n_out, b.held);
      ++st.sink_stalled;
    }
    if (out_valid && ready) {
      if (st.outputs == 0) st.first_output_cycle = c;
      st.last_output_cycle = c;
      ++st.outputs;
      st.longest_quiet = std::max(st.longest_quiet, c - st.last_progress);
      st.last_progress = st.last_activity = c;
      b.output_cycles[b.outputs_written++] = c;
    }
    dut.clock();
    if (dut.assertion_failed()) {
      b.stop = LoopStop::assertion;
      return;
    }
    if (in_fire) {
      b.accept_cycles[b.accepts_written++] = c;
      ++st.next_index;
      ++st.inputs;
      st.presenting = false;
      st.longest_quiet = std::max(st.longest_quiet, c - st.last_progress);
      st.last_progress = st.last_activity = c;
    }
    if (st.tailing) {
      if (c >= st.tail_end) {
        b.stop = LoopStop::finished;
        return;
      }
      continue;  // the drain window is bounded: no deadlock in it
    }
    if (st.inputs_done && !st.presenting &&
        (b.drain > 0 ? c - st.last_activity >= b.drain : st.outputs >= b.outputs_due)) {
      st.finish_cycles = c + 1;  // the run proper; the drain only watches for extra outputs
      st.tail_end = c + std::max(b.tail, 2 * st.longest_quiet);
      st.tailing = true;
      st.last_progress = c;
    }
    if (c - st.last_progress > b.timeout) {
      b.stop = LoopStop::deadlock;
      return;
    }
  }
}

}  // namespace phongsim
