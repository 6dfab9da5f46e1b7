#include "sim/cosim/cosim.h"

#include <fmt/format.h>

#include <algorithm>
#include <deque>
#include <limits>
#include <vector>

#include "sim/cosim/harness.h"

namespace phongsim {
namespace {

std::string value_text(const Field& f, std::int64_t raw) {
  return phongsim::value_text(raw, f.fmt);
}

std::string field_head(const Field& f) { return fmt::format("{:<8} {:>7}", f.name, f.fmt.str()); }

FieldValue field_value(const Field& f, std::int64_t raw) {
  return {f.name, f.fmt.str(), raw, fx::to_real(raw, f.fmt)};
}

// Output fields as a table with expected and got side by side, differing fields marked.
std::string output_table(const std::vector<Field>& fields, const std::int64_t* want,
                         std::span<const std::int64_t> got) {
  std::size_t column = 16;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    column = std::max(column, value_text(fields[i], want[i]).size() + 4);
  }
  // "  outputs:" then up to where the values start ("    " + field_head + "  " = 22 columns).
  std::string s = fmt::format("  outputs:{:12}{:<{}}got\n", "", "expected", column);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    s += fmt::format("    {}  {:<{}}{}{}\n", field_head(fields[i]), value_text(fields[i], want[i]),
                     column, value_text(fields[i], got[i]),
                     want[i] != got[i] ? "   <-- differs" : "");
  }
  return s;
}

// One input transaction between acceptance and its last output.
struct InFlight {
  std::uint64_t index = 0;  // vector index
  std::uint64_t accept_cycle = 0;
  std::vector<std::int64_t> in;
  std::vector<std::int64_t> expected;  // count * output fields
  std::size_t count = 0;
  std::size_t seen = 0;
};

class Scoreboard {
 public:
  Scoreboard(PipelineModel& model) : model_(model) {}

  void accept(std::uint64_t index, std::uint64_t cycle, std::span<const std::int64_t> in) {
    InFlight t;
    t.index = index;
    t.accept_cycle = cycle;
    t.in.assign(in.begin(), in.end());
    t.count = model_.eval(in, t.expected);
    queue_.push_back(std::move(t));
    drop_finished();
  }

  // Compares one RTL output; on a failure fills kind/report/detail and returns false.
  bool check(std::span<const std::int64_t> got, std::uint64_t cycle, std::string& kind,
             std::string& report, CosimFailure& detail) {
    const auto& outs = model_.outputs();
    const std::size_t n = outs.size();
    drop_finished();
    if (queue_.empty()) {
      kind = "unexpected output";
      detail.cycle = cycle;
      for (std::size_t i = 0; i < n; ++i) {
        detail.outputs.push_back(
            {outs[i].name, outs[i].fmt.str(), std::nullopt, field_value(outs[i], got[i]), true});
      }
      report = fmt::format(
          "UNEXPECTED OUTPUT at cycle {}: the model expects no output now (all {} checked "
          "outputs matched); duplicated or extra output\n  got:\n",
          cycle, checked_);
      for (std::size_t i = 0; i < n; ++i) {
        report += fmt::format("    {}  {}\n", field_head(outs[i]), value_text(outs[i], got[i]));
      }
      if (last_.size() == n && std::equal(last_.begin(), last_.end(), got.begin())) {
        report += "  it repeats the previous output: duplicated\n";
      }
      return false;
    }
    InFlight& t = queue_.front();
    const std::int64_t* want = t.expected.data() + t.seen * n;
    if (!std::equal(got.begin(), got.end(), want)) {
      kind = "mismatch";
      report = fmt::format("MISMATCH at cycle {}, vector {} (output {} of {} for it){}\n", cycle,
                           t.index, t.seen + 1, t.count, hint(got));
      report += "  inputs:\n";
      const auto& ins = model_.inputs();
      for (std::size_t i = 0; i < ins.size(); ++i) {
        report += fmt::format("    {}  {}\n", field_head(ins[i]), value_text(ins[i], t.in[i]));
      }
      report += output_table(outs, want, got);
      failing_index_ = t.index;
      detail.cycle = cycle;
      detail.vector = t.index;
      detail.output = t.seen;
      detail.outputs_of_vector = t.count;
      for (std::size_t i = 0; i < ins.size(); ++i) {
        detail.inputs.push_back(field_value(ins[i], t.in[i]));
      }
      for (std::size_t i = 0; i < n; ++i) {
        detail.outputs.push_back({outs[i].name, outs[i].fmt.str(), field_value(outs[i], want[i]),
                                  field_value(outs[i], got[i]), want[i] != got[i]});
      }
      return false;
    }
    if (t.seen == 0) {
      const std::uint64_t latency = cycle - t.accept_cycle;
      latency_min_ = std::min(latency_min_, latency);
      latency_max_ = std::max(latency_max_, latency);
    }
    last_.assign(got.begin(), got.end());
    ++t.seen;
    ++checked_;
    return true;
  }

  // True when every accepted input has produced all its outputs.
  bool drained() {
    drop_finished();
    return queue_.empty();
  }

  [[nodiscard]] std::string pending() {
    drop_finished();
    if (queue_.empty()) return "none";
    const InFlight& t = queue_.front();
    return fmt::format(
        "{} vectors still owe outputs, oldest vector {} (accepted at cycle {}, {} "
        "of {} outputs seen)",
        queue_.size(), t.index, t.accept_cycle, t.seen, t.count);
  }

  // The vector whose output is due next, if any.
  [[nodiscard]] std::optional<std::uint64_t> next_due() {
    drop_finished();
    if (queue_.empty()) return std::nullopt;
    return queue_.front().index;
  }

  [[nodiscard]] std::uint64_t latency_min() const { return latency_min_; }
  [[nodiscard]] std::uint64_t latency_max() const { return latency_max_; }
  [[nodiscard]] std::optional<std::uint64_t> failing_index() const { return failing_index_; }

 private:
  void drop_finished() {
    while (!queue_.empty() && queue_.front().seen == queue_.front().count) queue_.pop_front();
  }

  // Why an output might differ: it belongs to a later vector (reordered/dropped) or repeats the
  // previous one (duplicated).
  std::string hint(std::span<const std::int64_t> got) const {
    const std::size_t n = model_.outputs().size();
    if (last_.size() == n && std::equal(last_.begin(), last_.end(), got.begin())) {
      return "; it repeats the previous output: duplicated?";
    }
    for (std::size_t q = 0; q < queue_.size(); ++q) {
      const InFlight& t = queue_[q];
      for (std::size_t k = (q == 0 ? t.seen + 1 : 0); k < t.count; ++k) {
        if (std::equal(got.begin(), got.end(), t.expected.begin() + k * n)) {
          return fmt::format("; it is the expected output of vector {}: reordered or dropped?",
                             t.index);
        }
      }
    }
    return "";
  }

  PipelineModel& model_;
  std::deque<InFlight> queue_;
  std::vector<std::int64_t> last_;
  std::uint64_t checked_ = 0;
  std::uint64_t latency_min_ = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t latency_max_ = 0;
  std::optional<std::uint64_t> failing_index_;
};

struct Phase {
  HarnessResult harness;
  std::string kind;
  std::string report;
  CosimFailure detail;
  std::uint64_t latency_min = 0;
  std::uint64_t latency_max = 0;
  std::optional<std::uint64_t> failing_index;
};

// Runs vectors [first, first + count) (or the one in `only`) through a fresh DUT.
Phase run_phase(PipelineModel& model, RtlDut& dut, const Stimulus& stimulus, const CosimOptions& o,
                const HarnessOptions& ho, std::uint64_t first, std::uint64_t count,
                const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) {
  Phase phase;
  model.reset();
  Scoreboard board(model);
  std::vector<std::int64_t> current(model.inputs().size());
  HarnessHooks hooks;
  hooks.next_input = [&](std::uint64_t pos, std::span<std::int64_t> in) {
    if (pos >= count) return false;
    stimulus.vector(o.seed, first + pos, in);
    std::copy(in.begin(), in.end(), current.begin());
    return true;
  };
  hooks.accepted = [&](std::uint64_t pos, std::uint64_t cycle) {
    board.accept(first + pos, cycle, current);
    if (progress && pos % 4096 == 0) progress(pos, count);
  };
  hooks.output = [&](std::span<const std::int64_t> out, std::uint64_t cycle) {
    return board.check(out, cycle, phase.kind, phase.report, phase.detail);
  };
  hooks.finished = [&](std::uint64_t) { return board.drained(); };
  phase.harness = run_harness(dut, model.inputs().size(), model.outputs().size(), ho, hooks);
  if (phase.harness.reason == StopReason::deadlock) {
    phase.kind = "deadlock";
    phase.report =
        fmt::format("DEADLOCK: {}\n  pending: {}\n", phase.harness.message, board.pending());
    if (phase.harness.waiting_input) {
      phase.report +=
          fmt::format("  waiting for in_ready: vector {}\n", first + *phase.harness.waiting_input);
    }
    phase.detail.vector = board.next_due();
  } else if (phase.harness.reason == StopReason::protocol) {
    phase.kind = "protocol";
    phase.report = fmt::format("HANDSHAKE VIOLATION: {}\n", phase.harness.message);
    if (const auto due = board.next_due()) {
      phase.report += fmt::format("  the offending output is the one due for vector {}\n", *due);
    }
    phase.detail.vector = board.next_due();
  }
  if (!phase.kind.empty()) {
    phase.detail.kind = phase.kind;
    phase.detail.message = phase.harness.message;
    if (phase.detail.cycle == 0) phase.detail.cycle = phase.harness.cycles - 1;
  }
  phase.latency_min = board.latency_min();
  phase.latency_max = board.latency_max();
  if (board.failing_index()) phase.failing_index = board.failing_index();
  return phase;
}

// Failures where the harness took an output and the scoreboard rejected it.
bool rejects_an_output(const std::string& kind) {
  return kind == "mismatch" || kind == "unexpected output";
}

std::string repro_command(const CosimReport& r, std::optional<std::uint64_t> only) {
  const auto& o = r.options;
  std::string cmd = fmt::format("phongsim cosim --pipeline {} --config {}{} --seed {}", r.pipeline,
                                r.config_path, r.rtl_options, o.seed);
  if (only) {
    cmd += fmt::format(" --vector-index {}", *only);
  } else {
    cmd += fmt::format(" --vectors {}", o.random_vectors);
    if (!o.directed) cmd += " --no-directed";
  }
  cmd += fmt::format(" --source-idle {} --backpressure {}", o.source.str(), o.sink.str());
  if (o.timeout != 0) cmd += fmt::format(" --timeout {}", o.timeout);
  return cmd;
}

// Where a failure happened and how to get it again: appended to every failure report.
std::string failure_context(const CosimReport& r, std::optional<std::uint64_t> only,
                            std::optional<std::uint64_t> failing_index, bool independent) {
  const auto& o = r.options;
  std::string s =
      fmt::format("  pipeline {}, config {} ({}), seed {}, source idle {}, sink backpressure {}\n",
                  r.pipeline, r.config_name, r.config_path, o.seed, o.source.str(), o.sink.str());
  s += fmt::format("  reproduce: {}\n", repro_command(r, only));
  if (failing_index && !only && independent) {
    s += fmt::format("  this vector alone: {}\n", repro_command(r, failing_index));
  }
  return s;
}

}  // namespace

std::string value_text(std::int64_t raw, fx::Format fmt) {
  return fmt::format("0x{:0{}x} {:>6} {}", fx::to_bits(raw, fmt), (fmt.width() + 3) / 4, raw,
                     fx::to_real(raw, fmt));
}

std::string CosimReport::summary() const {
  const std::string vectors_in =
      passed ? fmt::format("{} vectors", vectors)
             : fmt::format("{} of {} vectors accepted", vectors, directed + random);
  std::string s = fmt::format(
      "{} {}/{}: {} ({} directed + {} random, seed {}), {} outputs, {} mismatches, {} cycles; "
      "source {}, sink {}",
      passed ? "PASS" : "FAIL", pipeline, config_name, vectors_in, directed, random, options.seed,
      outputs, mismatches, cycles, options.source.str(), options.sink.str());
  if (throughput > 0) {
    s += fmt::format("; throughput {:.3f}/clock, latency {}", throughput, latency_min);
    if (latency_max != latency_min) s += fmt::format("..{}", latency_max);
    s += " cycles";
  }
  if (!passed) s += fmt::format("; first failure: {}", failure_kind);
  if (!rtl_label.empty()) s += fmt::format("; RTL: {}", rtl_label);
  return s;
}

CosimReport cosim(const CosimSubject& subject, const CosimOptions& options) {
  CosimReport r;
  r.pipeline = subject.pipeline;
  r.rtl_label = subject.rtl_label;
  r.rtl_options = subject.rtl_options;
  r.config_name = subject.cfg.name();
  r.config_path = subject.cfg.origin();
  r.options = options;
  PipelineModel& model = subject.model;
  const Stimulus& stimulus = subject.stimulus;
  const DutFactory& make_dut = subject.make_dut;
  const std::uint64_t directed = options.directed ? stimulus.directed_count() : 0;

  // Main run: the requested stimulus under the requested stall patterns.
  std::uint64_t first = options.directed ? 0 : stimulus.directed_count();
  std::uint64_t count = directed + options.random_vectors;
  if (options.only_index) {
    first = *options.only_index;
    count = 1;
  }
  r.directed = options.only_index ? (first < stimulus.directed_count() ? 1 : 0) : directed;
  r.random = count - r.directed;

  HarnessOptions ho;
  ho.source = options.source;
  ho.sink = options.sink;
  ho.seed = options.seed;
  ho.timeout = options.timeout;
  if (!options.trace_path.empty()) {  // passing run: the first trace_window cycles
    ho.trace_path = options.trace_path;
    ho.trace_to = options.trace_window;
  }
  Phase main;
  {
    DutPtr dut = make_dut();
    main = run_phase(model, *dut, stimulus, options, ho, first, count, options.progress);
  }
  r.vectors = main.harness.inputs;
  r.outputs = main.harness.outputs - (rejects_an_output(main.kind) ? 1 : 0);
  r.cycles = main.harness.cycles;
  r.passed = main.kind.empty();
  if (!r.passed) {
    r.mismatches = rejects_an_output(main.kind) ? 1 : 0;
    r.failure_kind = main.kind;
    const std::uint64_t fail_cycle = main.harness.cycles - 1;
    r.failure = main.report + failure_context(r, options.only_index, main.failing_index,
                                              subject.independent_vectors);
    r.failure_detail = main.detail;
    if (!options.trace_path.empty()) {  // same run again, waveform only around the failure
      ho.trace_from = fail_cycle > options.trace_window ? fail_cycle - options.trace_window : 0;
      ho.trace_to = fail_cycle + 1;
      DutPtr dut = make_dut();
      (void)run_phase(model, *dut, stimulus, options, ho, first, count);
      r.failure += fmt::format("  waveform of cycles {}..{}: {}\n", ho.trace_from, ho.trace_to,
                               options.trace_path);
    }
  }
  if (!options.trace_path.empty()) r.trace_written = options.trace_path;

  // Measurement run: stall-free, random vectors, for throughput and latency.
  if (r.passed && options.measure_vectors > 0 && !options.only_index) {
    HarnessOptions mo;
    mo.timeout = options.timeout;
    DutPtr dut = make_dut();
    const Phase m = run_phase(model, *dut, stimulus, options, mo, stimulus.directed_count(),
                              options.measure_vectors);
    if (!m.kind.empty()) {
      // Report it as the run that reproduces it: these vectors, stall-free, no directed ones.
      CosimReport as_run = r;
      as_run.options.directed = false;
      as_run.options.random_vectors = options.measure_vectors;
      as_run.options.source = StallPattern();
      as_run.options.sink = StallPattern();
      r.passed = false;
      r.mismatches = rejects_an_output(m.kind) ? 1 : 0;
      r.failure_kind = m.kind;
      r.failure =
          m.report + "  (in the stall-free measurement run)\n" +
          failure_context(as_run, std::nullopt, m.failing_index, subject.independent_vectors);
      r.failure_detail = m.detail;
      r.failure_detail->in_measurement_run = true;
    } else if (m.harness.outputs > 1) {
      r.measured = true;
      r.throughput =
          static_cast<double>(m.harness.outputs - 1) /
          static_cast<double>(m.harness.last_output_cycle - m.harness.first_output_cycle);
      r.latency_min = m.latency_min;
      r.latency_max = m.latency_max;
    }
  }
  return r;
}

}  // namespace phongsim
