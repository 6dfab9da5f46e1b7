#include "sim/cosim/cosim.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "base/error.h"
#include "base/temporaries.h"
#include "base/text.h"
#include "model/plan.h"
#include "sim/cosim/harness.h"
#include "sim/cosim/waveform.h"

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

// The scoreboard: expected outputs for vectors [first, first + count), computed by the model a
// batch ahead of the RTL (vectors are a pure function of seed and index, and kb's state follows
// the index order, which is also the acceptance order), compared with what the RTL produces a
// batch at a time. An output taken in cycle c is due to the oldest vector accepted before c that
// still owes outputs; none: an unexpected output.
class Scoreboard {
 public:
  Scoreboard(PipelineModel& model, const Stimulus& stimulus, const InputContract& contract,
             std::uint64_t seed, std::uint64_t first, std::uint64_t count)
      : model_(model),
        stimulus_(stimulus),
        seed_(seed),
        first_(first),
        count_(count),
        n_in_(model.inputs().size()),
        n_out_(model.outputs().size()),
        contract_(contract) {  // a fresh checker: this run starts from reset
    offset_.push_back(0);
    if (contract_.defined()) tally_.resize(contract_.clauses().size() + 1);
  }

  // The vectors from position `pos` (relative to first) on, with the model's outputs for them.
  InputBatch next(std::uint64_t pos) {
    const std::uint64_t n = std::min(batch_, count_ - std::min(count_, pos));
    inputs_.resize(n * n_in_);
    stimulus_.vectors(seed_, first_ + pos, n, inputs_);
    if (contract_.defined()) {
      const std::size_t at = clause_.size();
      clause_.resize(at + n);
      contract_.check(inputs_, n_in_, std::span(clause_).subspan(at));
    }
    counts_.clear();
    const std::size_t values = model_.eval_batch(inputs_, expected_, &counts_) * n_out_;
    for (const std::uint32_t c : counts_) {
      offset_.push_back(offset_.back() + c);
      single_ = single_ && c == 1;
    }
    // The batches decide nothing but the memory: the vectors and their order are the same.
    batch_ = next_cosim_batch(n, values);
    InputBatch b;
    b.vectors = inputs_;
    if (pos + n >= count_) {
      b.last = true;
      b.outputs_due = offset_.back() + base_output_;
    }
    return b;
  }

  // Checks a batch (see HarnessHooks::check); on a failure fills kind/report.
  std::size_t check(std::span<const std::uint64_t> accepted, std::span<const std::int64_t> outputs,
                    std::span<const std::uint64_t> cycles, std::string& kind, std::string& report,
                    CosimFailure& detail) {
    accept_.insert(accept_.end(), accepted.begin(), accepted.end());
    // The outputs in runs over many vectors (match_run); once a run fails to match, vector by
    // vector: the outputs from j on that the oldest vector still owes, compared in one pass
    // against its expected outputs (contiguous in both); a difference, or an output no vector
    // owes, goes to check_one one output at a time, which reports it.
    bool runs = true;
    for (std::size_t j = 0; j < cycles.size();) {
      if (runs) {
        const std::size_t m = match_run(cycles.subspan(j), outputs.data() + j * n_out_);
        j += m;
        runs = m > 0;
        continue;
      }
      drop_finished(cycles[j]);
      if (front_owes(cycles[j])) {
        const std::size_t m = std::min<std::uint64_t>(owed(front_) - seen_, cycles.size() - j);
        if (same(outputs.data() + j * n_out_, expected(front_, seen_), m * n_out_)) {
          if (seen_ == 0) latency(cycles[j] - accept_[front_ - base_]);
          seen_ += m;
          checked_ += m;
          j += m;
          continue;
        }
      }
      // The output before this one, for the failure reports (the batch's, else the last batch's).
      const std::int64_t* prev = j > 0           ? outputs.data() + (j - 1) * n_out_
                                 : last_.empty() ? nullptr
                                                 : last_.data();
      if (check_one(outputs.subspan(j * n_out_, n_out_), prev, cycles[j], kind, report, detail)) {
        ++j;
      } else {
        // The run stops in that cycle: it has accepted the inputs up to it (as the harness
        // counts them).
        if (contract_.defined()) {
          tally(static_cast<std::size_t>(
              std::upper_bound(accepted.begin(), accepted.end(), cycles[j]) - accepted.begin()));
        }
        return j;
      }
    }
    if (contract_.defined()) tally(accepted.size());
    if (!cycles.empty()) {
      const auto last = outputs.subspan((cycles.size() - 1) * n_out_, n_out_);
      last_.assign(last.begin(), last.end());
    }
    compact();
    return cycles.size();
  }

  [[nodiscard]] std::string pending() {
    drop_finished(UINT64_MAX);
    if (front_ >= accepted()) return "none";
    return fmt::format(
        "{} vectors still owe outputs, oldest vector {} (accepted at cycle {}, {} "
        "of {} outputs seen)",
        accepted() - front_, index(front_), accept_[front_ - base_], seen_, owed(front_));
  }

  // The vector whose output is due next, if any.
  [[nodiscard]] std::optional<std::uint64_t> next_due() {
    drop_finished(UINT64_MAX);
    if (front_ >= accepted()) return std::nullopt;
    return index(front_);
  }

  // The accepted vectors inside and outside the input contract (empty when there is none).
  [[nodiscard]] ContractCounts contract_counts() const {
    ContractCounts c;
    if (tally_.empty()) return c;
    c.in = tally_[0];
    c.by_clause.assign(tally_.begin() + 1, tally_.end());
    return c;
  }

  [[nodiscard]] std::uint64_t latency_min() const { return latency_min_; }
  [[nodiscard]] std::uint64_t latency_max() const { return latency_max_; }
  [[nodiscard]] std::optional<std::uint64_t> failing_index() const { return failing_index_; }

 private:
  // Positions (relative to first) are kept from base_ on: accept_[p - base_], offset_[p - base_]
  // (into expected_, whose element 0 is output number base_output_ of the run).
  [[nodiscard]] std::uint64_t accepted() const { return base_ + accept_.size(); }
  [[nodiscard]] std::uint64_t index(std::uint64_t pos) const { return first_ + pos; }
  [[nodiscard]] std::uint64_t owed(std::uint64_t pos) const {
    return offset_[pos - base_ + 1] - offset_[pos - base_];
  }
  [[nodiscard]] const std::int64_t* expected(std::uint64_t pos, std::uint64_t k) const {
    return expected_.data() + (offset_[pos - base_] + k) * n_out_;
  }
  // Whether the oldest vector still owes an output, accepted before `cycle`.
  [[nodiscard]] bool front_owes(std::uint64_t cycle) const {
    return front_ < accepted() && accept_[front_ - base_] < cycle && seen_ < owed(front_);
  }
  // Vectors accepted before `cycle` whose outputs are all seen leave the front.
  void drop_finished(std::uint64_t cycle) {
    while (front_ < accepted() && accept_[front_ - base_] < cycle && seen_ == owed(front_)) {
      ++front_;
      seen_ = 0;
    }
  }

  // The outputs `got` (taken in `cycles`) matched in order to the vectors that owe them, each
  // accepted before the cycle of its first output here, and compared in one pass (the expected
  // outputs of consecutive vectors are contiguous). Returns how many, with front_, seen_ and the
  // latencies moved past them; or 0, committing nothing, when the first output is due to no
  // vector or any output of the run differs: check_one then finds and reports which.
  std::size_t match_run(std::span<const std::uint64_t> cycles, const std::int64_t* got) {
    std::uint64_t p = front_, s = seen_;
    std::uint64_t lat_min = latency_min_, lat_max = latency_max_;
    std::size_t run = 0;
    if (single_ && s == 0) {
      // Every vector owes one output (LIRP, Lyon): output i is vector front_ + i's if each of them
      // was accepted before its output's cycle; one pass without a branch per output, on the
      // kernels' instruction set (it vectorizes). Otherwise the loop below finds where the run
      // ends.
      const std::size_t n = std::min<std::uint64_t>(cycles.size(), accepted() - p);
      if (all_before(accept_.data() + (p - base_), cycles.data(), n, lat_min, lat_max)) {
        run = n;
        p += n;
      }
    }
    while (run < cycles.size() && p < accepted()) {
      const std::uint64_t c = cycles[run];
      const std::uint64_t at = accept_[p - base_];
      if (at >= c) break;  // no vector owes this output yet
      const std::uint64_t owes = owed(p);
      if (s < owes) {
        if (s == 0) {
          lat_min = std::min(lat_min, c - at);
          lat_max = std::max(lat_max, c - at);
        }
        const std::uint64_t m = std::min<std::uint64_t>(owes - s, cycles.size() - run);
        run += m;
        s += m;
      }
      if (s == owes) {  // p is done (or owed nothing): the next output is a later vector's
        ++p;
        s = 0;
      }
    }
    if (run == 0 || !same(got, expected(front_, seen_), run * n_out_)) return 0;
    front_ = p;
    seen_ = s;
    latency_min_ = lat_min;
    latency_max_ = lat_max;
    checked_ += run;
    return run;
  }

  // Compares one RTL output (`prev`: the one before it, or null); on a failure fills
  // kind/report/detail and returns false.
  bool check_one(std::span<const std::int64_t> got, const std::int64_t* prev, std::uint64_t cycle,
                 std::string& kind, std::string& report, CosimFailure& detail) {
    const auto& outs = model_.outputs();
    const std::size_t n = outs.size();
    drop_finished(cycle);
    if (front_ >= accepted() || accept_[front_ - base_] >= cycle) {
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
      if (prev != nullptr && std::equal(got.begin(), got.end(), prev)) {
        report += "  it repeats the previous output: duplicated\n";
      }
      return false;
    }
    const std::int64_t* want = expected(front_, seen_);
    if (!std::equal(got.begin(), got.end(), want)) {
      kind = "mismatch";
      report = fmt::format("MISMATCH at cycle {}, vector {} (output {} of {} for it){}\n", cycle,
                           index(front_), seen_ + 1, owed(front_), hint(got, prev, cycle));
      report += "  inputs:\n";
      const auto& ins = model_.inputs();
      std::vector<std::int64_t> in(ins.size());
      stimulus_.vector(seed_, index(front_), in);
      for (std::size_t i = 0; i < ins.size(); ++i) {
        report += fmt::format("    {}  {}\n", field_head(ins[i]), value_text(ins[i], in[i]));
      }
      report += output_table(outs, want, got);
      failing_index_ = index(front_);
      detail.cycle = cycle;
      detail.vector = index(front_);
      detail.output = seen_;
      detail.outputs_of_vector = owed(front_);
      for (std::size_t i = 0; i < ins.size(); ++i)
        detail.inputs.push_back(field_value(ins[i], in[i]));
      for (std::size_t i = 0; i < n; ++i) {
        detail.outputs.push_back({outs[i].name, outs[i].fmt.str(), field_value(outs[i], want[i]),
                                  field_value(outs[i], got[i]), want[i] != got[i]});
      }
      return false;
    }
    if (seen_ == 0) latency(cycle - accept_[front_ - base_]);
    ++seen_;
    ++checked_;
    return true;
  }

  // Whether at[i] < cycle[i] for every i < n; if so, the latencies cycle[i] - at[i] folded into
  // lo and hi (else lo and hi are left as they were).
  static bool all_before(const std::uint64_t* at, const std::uint64_t* cycle, std::size_t n,
                         std::uint64_t& lo, std::uint64_t& hi) {
    std::uint64_t late = 0, low = lo, high = hi;
    fx::on_kernel_isa([&] {
      // Locals: through the captured references the loop would not vectorize.
      std::uint64_t l = 0, a = low, b = high;
      for (std::size_t i = 0; i < n; ++i) {
        l |= at[i] >= cycle[i] ? 1 : 0;
        a = std::min(a, cycle[i] - at[i]);
        b = std::max(b, cycle[i] - at[i]);
      }
      late = l;
      low = a;
      high = b;
    });
    if (late != 0) return false;
    lo = low;
    hi = high;
    return true;
  }

  // a[0..n) == b[0..n), without a branch per value or a library call (this runs per output).
  static bool same(const std::int64_t* a, const std::int64_t* b, std::size_t n) {
    std::uint64_t differ = 0;
    for (std::size_t i = 0; i < n; ++i) {
      differ |= static_cast<std::uint64_t>(a[i]) ^ static_cast<std::uint64_t>(b[i]);
    }
    return differ == 0;
  }

  void latency(std::uint64_t cycles) {
    latency_min_ = std::min(latency_min_, cycles);
    latency_max_ = std::max(latency_max_, cycles);
  }

  // Why an output might differ: it belongs to a later vector in flight (reordered/dropped) or
  // repeats the previous one (duplicated).
  std::string hint(std::span<const std::int64_t> got, const std::int64_t* prev,
                   std::uint64_t cycle) const {
    if (prev != nullptr && std::equal(got.begin(), got.end(), prev)) {
      return "; it repeats the previous output: duplicated?";
    }
    for (std::uint64_t p = front_; p < accepted() && accept_[p - base_] < cycle; ++p) {
      for (std::uint64_t k = (p == front_ ? seen_ + 1 : 0); k < owed(p); ++k) {
        if (std::equal(got.begin(), got.end(), expected(p, k))) {
          return fmt::format("; it is the expected output of vector {}: reordered or dropped?",
                             index(p));
        }
      }
    }
    return "";
  }

  // Counts the next `n` vectors the harness accepted against the contract: their clauses were
  // found when the batch was made (clause_, from clause_head_ on).
  void tally(std::size_t n) {
    const std::size_t end = std::min(clause_.size(), clause_head_ + n);
    // One counting pass per clause (and kIn, at 0): vectorized, where a count per vector would
    // wait on the previous one's store, or mispredict a branch on random stimulus.
    const std::int16_t* const from = clause_.data() + clause_head_;
    const std::size_t count = end - clause_head_;
    for (std::size_t t = 0; t < tally_.size(); ++t) {
      const auto clause = static_cast<std::int16_t>(static_cast<int>(t) + InputContract::kIn);
      std::uint32_t k = 0;
      for (std::size_t i = 0; i < count; ++i) k += from[i] == clause ? 1 : 0;
      tally_[t] += k;
    }
    clause_head_ = end;
    if (clause_head_ >= 4 * kCosimBatch) {
      clause_.erase(clause_.begin(), clause_.begin() + static_cast<std::ptrdiff_t>(clause_head_));
      clause_head_ = 0;
    }
  }

  // Forgets vectors that are done, now and then.
  void compact() {
    const std::uint64_t done = front_ - base_;
    if (done < 4 * kCosimBatch && offset_[done] * n_out_ < 4 * kCosimBatchValues) return;
    const std::uint64_t outputs_done = offset_[done];
    expected_.erase(expected_.begin(),
                    expected_.begin() + static_cast<std::ptrdiff_t>(outputs_done * n_out_));
    accept_.erase(accept_.begin(), accept_.begin() + static_cast<std::ptrdiff_t>(done));
    offset_.erase(offset_.begin(), offset_.begin() + static_cast<std::ptrdiff_t>(done));
    for (auto& o : offset_) o -= outputs_done;
    base_ += done;
    base_output_ += outputs_done;
  }

  PipelineModel& model_;
  const Stimulus& stimulus_;
  std::uint64_t seed_, first_, count_;
  std::size_t n_in_, n_out_;
  InputContract contract_;
  std::vector<std::int16_t> clause_;  // per generated vector not yet accepted: its clause
  std::size_t clause_head_ = 0;
  std::vector<std::uint64_t> tally_;   // accepted vectors in the contract, then per clause
  std::vector<std::int64_t> inputs_;   // the batch handed to the harness
  std::uint64_t batch_ = kCosimBatch;  // vectors in the next batch
  std::vector<std::uint32_t> counts_;
  bool single_ = true;                  // every vector made so far owes exactly one output
  std::vector<std::int64_t> expected_;  // outputs of vectors base_ .. (generated so far)
  std::vector<std::uint64_t> offset_;   // per vector from base_, into expected_ (in outputs)
  std::vector<std::uint64_t> accept_;   // acceptance cycle per accepted vector from base_
  std::uint64_t base_ = 0;
  std::uint64_t base_output_ = 0;
  std::uint64_t front_ = 0;         // the vector whose outputs are due next
  std::uint64_t seen_ = 0;          // of its outputs
  std::vector<std::int64_t> last_;  // the last output of the last batch checked
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
  ContractCounts contract;
  WaveNotes notes;  // the handshakes in the waveform's cycles, when the run wrote one
};

// Records the handshakes of the cycles [ho.trace_from, ho.trace_to] (the waveform's) in `notes`:
// accepts with their vector index (from `first`), outputs with their number in the run and the
// values taken; complete_notes adds what the model expected.
void note_handshakes(WaveNotes& notes, const HarnessOptions& ho, std::uint64_t first,
                     std::size_t n_out, std::uint64_t& accepted, std::uint64_t& taken,
                     std::span<const std::uint64_t> accepts, std::span<const std::int64_t> out,
                     std::span<const std::uint64_t> cycles) {
  const auto shown = [&](std::uint64_t c) { return c >= ho.trace_from && c <= ho.trace_to; };
  for (const std::uint64_t c : accepts) {
    if (shown(c)) notes.accepts.push_back({c, first + accepted});
    ++accepted;
  }
  for (std::size_t j = 0; j < cycles.size(); ++j) {
    if (shown(cycles[j])) {
      WaveNotes::Output o;
      o.cycle = cycles[j];
      o.number = taken;
      o.got.assign(out.begin() + static_cast<std::ptrdiff_t>(j * n_out),
                   out.begin() + static_cast<std::ptrdiff_t>((j + 1) * n_out));
      notes.outputs.push_back(std::move(o));
    }
    ++taken;
  }
}

// The model's outputs for the noted ones: a fresh model from `first` (the DUT's reset) numbers
// every output it gives, and which vector gives it.
void complete_notes(const CosimSubject& s, std::uint64_t seed, std::uint64_t first,
                    std::uint64_t accepted, WaveNotes& notes) {
  notes.fields = s.model.outputs();
  if (notes.outputs.empty()) return;
  const std::unique_ptr<PipelineModel> model = s.model.clone();
  model->reset();
  const std::size_t n_out = notes.fields.size();
  std::vector<std::int64_t> in(s.model.inputs().size()), out;
  std::uint64_t number = 0;
  auto next = notes.outputs.begin();
  for (std::uint64_t v = first; v < first + accepted && next != notes.outputs.end(); ++v) {
    s.stimulus.vector(seed, v, in);
    out.clear();
    const std::size_t n = model->eval(in, out);
    for (; next != notes.outputs.end() && next->number < number + n; ++next) {
      const std::size_t k = next->number - number;
      next->vector = v;
      next->index = k;
      next->expected.assign(out.begin() + static_cast<std::ptrdiff_t>(k * n_out),
                            out.begin() + static_cast<std::ptrdiff_t>((k + 1) * n_out));
    }
    number += n;
  }
  for (; next != notes.outputs.end(); ++next) next->owed = false;
}

// Runs vectors [first, first + count) (or the one in `only`) through a fresh DUT.
Phase run_phase(PipelineModel& model, RtlDut& dut, const Stimulus& stimulus,
                const InputContract& contract, const CosimOptions& o, const HarnessOptions& ho,
                std::uint64_t first, std::uint64_t count,
                const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) {
  Phase phase;
  model.reset();
  Scoreboard board(model, stimulus, contract, o.seed, first, count);
  HarnessHooks hooks;
  hooks.next_inputs = [&](std::uint64_t pos) { return board.next(pos); };
  std::uint64_t done = 0, reported = 0, noted_inputs = 0, noted_outputs = 0;
  const bool tracing = !ho.trace_path.empty();
  hooks.check = [&](std::span<const std::uint64_t> accepted, std::span<const std::int64_t> out,
                    std::span<const std::uint64_t> cycles) {
    if (tracing) {
      note_handshakes(phase.notes, ho, first, model.outputs().size(), noted_inputs, noted_outputs,
                      accepted, out, cycles);
    }
    if (progress) {
      done += accepted.size();
      if (done - reported >= 4096) {
        progress(done, count);
        reported = done;
      }
    }
    return board.check(accepted, out, cycles, phase.kind, phase.report, phase.detail);
  };
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
  } else if (phase.harness.reason == StopReason::unknown_value) {
    phase.kind = "unknown value";
    phase.report = fmt::format("UNKNOWN VALUE (X or Z): {}\n", phase.harness.message);
    if (const auto due = board.next_due()) {
      phase.report += fmt::format("  the output due next is vector {}'s\n", *due);
    }
    phase.detail.vector = board.next_due();
  } else if (phase.harness.reason == StopReason::protocol ||
             phase.harness.reason == StopReason::assertion) {
    const bool protocol = phase.harness.reason == StopReason::protocol;
    phase.kind = protocol ? "protocol" : "assertion";
    phase.report = fmt::format("{}: {}\n", protocol ? "HANDSHAKE VIOLATION" : "RTL ASSERTION",
                               phase.harness.message);
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
  phase.contract = board.contract_counts();
  phase.latency_min = board.latency_min();
  phase.latency_max = board.latency_max();
  if (board.failing_index()) phase.failing_index = board.failing_index();
  return phase;
}

// Failures where the harness took an output and the scoreboard rejected it.
bool rejects_an_output(const std::string& kind) {
  return kind == "mismatch" || kind == "unexpected output";
}

// The main run's vectors go to one or more DUTs, each from reset, as shards: a shard is a
// contiguous range of vectors run on a fresh DUT (and model), its stall patterns drawn from its
// own stream position. By default one shard per worker (--jobs), so that with one worker one DUT
// sees the whole stream; with reset_every, a shard every that many vectors, whatever the number
// of workers (which then changes nothing but the time). Shards begin at group starts when
// vectors depend on the ones before them.
struct Shard {
  std::uint64_t first = 0;
  std::uint64_t count = 0;
  std::uint64_t stream = 0;
};

bool splittable(const CosimSubject& s) { return s.independent_vectors || s.stimulus.has_groups(); }

std::vector<Shard> shards_of(const CosimSubject& s, const CosimOptions& o, std::uint64_t first,
                             std::uint64_t count) {
  std::vector<std::uint64_t> cuts;  // where shards after the first begin (before group starts)
  if (!o.only_index && splittable(s)) {
    if (o.reset_every > 0) {
      for (std::uint64_t at = o.reset_every; at < count; at += o.reset_every) {
        cuts.push_back(first + at);
      }
    } else {
      const std::uint64_t k = std::max<std::uint64_t>(o.jobs, 1);
      for (std::uint64_t i = 1; i < k; ++i) cuts.push_back(first + count / k * i);
    }
  }
  std::vector<Shard> shards;
  std::uint64_t start = first;
  for (std::size_t i = 0; i <= cuts.size(); ++i) {
    const std::uint64_t end =
        i == cuts.size() ? first + count : std::min(first + count, s.stimulus.group_start(cuts[i]));
    if (end > start || (i == cuts.size() && shards.empty())) {
      shards.push_back({start, end - start, shards.size()});
      start = end;
    }
  }
  return shards;
}

// Verilated models are created and destroyed one at a time.
std::mutex dut_mutex;

Phase run_shard(const CosimSubject& s, PipelineModel& model, const Stimulus& stimulus,
                const CosimOptions& o, HarnessOptions ho, const Shard& shard,
                const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) {
  ho.stall_stream = shard.stream;
  if (shard.stream != 0) ho.trace_path.clear();  // a passing run's waveform: the first cycles
  DutPtr dut;
  {
    const std::lock_guard lock(dut_mutex);
    dut = s.make_dut();
  }
  Phase p = run_phase(model, *dut, stimulus, s.contract, o, ho, shard.first, shard.count, progress);
  const std::lock_guard lock(dut_mutex);
  dut.reset();
  return p;
}

struct MainRun {
  Phase last;                                         // the failing shard's, or the last one's
  Shard shard;                                        // which
  std::uint64_t inputs = 0, outputs = 0, cycles = 0;  // summed up to it
  std::uint64_t source_idle = 0, sink_stalled = 0;    // likewise
  std::uint64_t duts = 0;                             // shards run up to it
  std::uint64_t longest_inputs = 0, longest_outputs = 0, drain = 0;  // the most of one shard
  ContractCounts contract;                                           // likewise
  Phase first;  // shard 0's, which alone writes a passing run's waveform (notes and counts)
};

// Runs the shards in order, `o.jobs` at a time, up to the first that fails (the lowest-numbered:
// a worker takes shards in order and finishes the one it has).
MainRun run_shards(const CosimSubject& s, const CosimOptions& o, const HarnessOptions& ho,
                   const std::vector<Shard>& shards) {
  std::vector<Phase> phases(shards.size());
  std::size_t failed = shards.size();
  const std::size_t jobs = std::min<std::size_t>(std::max(o.jobs, 1U), shards.size());
  // Progress: the inputs accepted by all workers so far, of all shards'.
  std::uint64_t total = 0;
  for (const Shard& sh : shards) total += sh.count;
  std::mutex progress_mutex;
  std::vector<std::uint64_t> done(jobs, 0), finished(jobs, 0);
  const auto report = [&](std::size_t w, std::uint64_t within) {
    if (!o.progress) return;
    const std::lock_guard lock(progress_mutex);
    done[w] = finished[w] + within;
    std::uint64_t all = 0;
    for (const std::uint64_t d : done) all += d;
    o.progress(all, total);
  };
  const auto run_one = [&](std::size_t w, PipelineModel& model, const Stimulus& stimulus,
                           std::size_t k) {
    phases[k] = run_shard(s, model, stimulus, o, ho, shards[k],
                          [&, w](std::uint64_t d, std::uint64_t) { report(w, d); });
    {
      const std::lock_guard lock(progress_mutex);
      finished[w] += shards[k].count;
    }
    report(w, 0);
  };
  if (jobs <= 1) {
    for (std::size_t k = 0; k < shards.size() && failed == shards.size(); ++k) {
      run_one(0, s.model, s.stimulus, k);
      if (!phases[k].kind.empty()) failed = k;
    }
  } else {
    std::atomic<std::size_t> next{0};
    std::atomic<std::size_t> first_failure{shards.size()};
    std::mutex error_mutex;
    std::exception_ptr error;
    std::vector<std::unique_ptr<PipelineModel>> models;
    std::vector<Stimulus> stimuli;
    for (std::size_t w = 0; w < jobs; ++w) {
      models.push_back(s.model.clone());
      stimuli.push_back(s.stimulus);
    }
    std::vector<std::thread> workers;
    for (std::size_t w = 0; w < jobs; ++w) {
      workers.emplace_back([&, w] {
        try {
          for (std::size_t k = next++; k < shards.size() && k < first_failure; k = next++) {
            run_one(w, *models[w], stimuli[w], k);
            if (phases[k].kind.empty()) continue;
            std::size_t f = first_failure;
            while (k < f && !first_failure.compare_exchange_weak(f, k)) {
            }
          }
        } catch (...) {
          const std::lock_guard lock(error_mutex);
          if (!error) error = std::current_exception();
          first_failure = 0;
        }
      });
    }
    for (auto& t : workers) t.join();
    if (error) std::rethrow_exception(error);
    failed = first_failure;
  }
  MainRun run;
  const std::size_t last = std::min(failed, shards.size() - 1);
  for (std::size_t k = 0; k <= last; ++k) {
    const HarnessResult& h = phases[k].harness;
    // A rejected output was taken, not checked right.
    const std::uint64_t outputs = h.outputs - (rejects_an_output(phases[k].kind) ? 1 : 0);
    run.inputs += h.inputs;
    run.outputs += outputs;
    run.cycles += h.cycles;
    run.source_idle += h.source_idle_cycles;
    run.sink_stalled += h.sink_stall_cycles;
    run.longest_inputs = std::max(run.longest_inputs, h.inputs);
    run.longest_outputs = std::max(run.longest_outputs, outputs);
    run.drain = std::max(run.drain, h.drain_cycles);
    run.contract.add(phases[k].contract);
  }
  run.duts = last + 1;
  if (last > 0) run.first = std::move(phases[0]);
  run.last = std::move(phases[last]);
  run.shard = shards[last];
  return run;
}

std::string repro_command(const CosimReport& r, std::optional<std::uint64_t> only) {
  const auto& o = r.options;
  std::string cmd = fmt::format("{} cosim --pipeline {}{}{} --seed {}", r.command, r.pipeline,
                                r.config_option, r.rtl_options, o.seed);
  if (only) {
    cmd += fmt::format(" --vector-index {}", *only);
  } else {
    cmd += fmt::format(" --vectors {}", o.random_vectors);
    if (!o.directed) cmd += " --no-directed";
  }
  cmd += fmt::format(" --source-idle {} --backpressure {}", o.source.str(), o.sink.str());
  if (o.timeout != 0) cmd += fmt::format(" --timeout {}", o.timeout);
  if (o.reset_every != 0) {
    cmd += fmt::format(" --reset-every {}", o.reset_every);
  } else if (o.jobs > 1 && !only) {
    cmd += fmt::format(" --jobs {}", o.jobs);  // the DUTs' shares of the stream
  }
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

// The failing vector beyond its ports: whether it lies inside the input contract, and the
// model's stage values (returned, and in `d`), from a fresh model and checker that have seen the
// vectors since the DUT's reset (from `first`; none when vectors are independent).
std::vector<StageValue> describe_vector(const CosimSubject& s, std::uint64_t seed,
                                        std::uint64_t first, CosimFailure& d) {
  if (d.kind != "mismatch" || !d.vector) return {};
  const std::uint64_t index = *d.vector;
  std::vector<std::int64_t> in(s.model.inputs().size()), out;
  const std::unique_ptr<PipelineModel> model = s.model.clone();
  model->reset();
  InputContract contract = s.contract;  // a copy is a checker of its own, from reset
  for (std::uint64_t v = s.independent_vectors ? index : first; v < index; ++v) {
    s.stimulus.vector(seed, v, in);
    if (contract.defined()) (void)contract.check(in);
    out.clear();
    (void)model->eval(in, out);
  }
  s.stimulus.vector(seed, index, in);
  if (contract.defined()) {
    const int c = contract.check(in);
    d.contract =
        c == InputContract::kIn ? "inside" : contract.clauses()[static_cast<std::size_t>(c)];
  }
  if (!s.stages) return {};
  std::vector<StageValue> values = s.stages(*model, in);
  for (const StageValue& v : values) {
    d.stages.push_back(
        {v.name, v.value.fmt.str(), v.value.raw, fx::to_real(v.value.raw, v.value.fmt)});
  }
  return values;
}

// The report's lines for describe_vector's findings (and the stage sightings, when looked for).
std::string vector_text(const CosimFailure& d) {
  std::string text;
  if (d.contract == "inside") {
    text += "  input contract: inside\n";
  } else if (!d.contract.empty()) {
    text += fmt::format(
        "  input contract: outside ({}): the accuracy claims do not hold there, bit-exactness "
        "does\n",
        d.contract);
  }
  if (d.stages.empty()) return text;
  text += "  the model's stages (named as in the pipeline's spec)";
  text += d.sightings.empty() ? ":\n" : ", and the design's signals of those names:\n";
  for (std::size_t i = 0; i < d.stages.size(); ++i) {
    const FieldValue& v = d.stages[i];
    std::string line = fmt::format("    {:<8} {:>7}  {}", v.name, v.format,
                                   phongsim::value_text(v.raw, fx::Format::parse(v.format)));
    if (i < d.sightings.size() && !d.sightings[i].signals.empty()) {
      std::vector<std::string> held, never;
      for (const StageSighting::Signal& g : d.sightings[i].signals) {
        (g.held ? held : never).push_back(g.path);
      }
      line = fmt::format("{:<48}", line);
      if (!held.empty()) line += fmt::format("  held by {}", fmt::join(held, ", "));
      if (!never.empty()) line += fmt::format("  NEVER on {}", fmt::join(never, ", "));
      if (v.name == d.first_differing_stage) line += "   <-- first to differ";
    }
    text += line + "\n";
  }
  if (!d.sightings.empty() && d.first_differing_stage.empty()) {
    bool any = false;
    for (const StageSighting& g : d.sightings) any = any || !g.signals.empty();
    text += any ? "  every stage signal held the model's value: the difference is after them\n"
                : "  no signal of the design is named after a stage (docs/your-rtl.md: stage "
                  "reports)\n";
  }
  return text;
}

// Looks for the model's stages in the traced failing run's waveform `fst` (cycles from
// `trace_from`): from the failing vector's acceptance (or the window's start) to the failing
// output. The first stage, in the spec's order, that has signals none of which held its value is
// the first to differ.
void locate_stages(const std::string& fst, const std::vector<StageValue>& values,
                   const WaveNotes& notes, std::uint64_t trace_from, CosimFailure& d) {
  std::uint64_t from = trace_from;
  for (const WaveNotes::Accept& a : notes.accepts) {
    if (a.vector == *d.vector) from = a.cycle;
  }
  d.sightings = find_stages(fst, values, 2 * from, 2 * d.cycle + 1);
  for (const StageSighting& g : d.sightings) {
    if (g.missed()) {
      d.first_differing_stage = g.stage;
      break;
    }
  }
}

// One line saying what failed and where (CosimFailure::message).
std::string failure_message(const CosimFailure& d, const std::string& harness) {
  if (d.kind == "mismatch" && d.vector) {
    std::string fields;
    const FieldComparison* first = nullptr;
    int differ = 0;
    for (const FieldComparison& f : d.outputs) {
      if (!f.differs) continue;
      ++differ;
      if (first == nullptr) first = &f;
    }
    if (first != nullptr && first->expected && first->got) {
      fields =
          fmt::format("{} is {} ({}) where the model gives {} ({})", first->name, first->got->raw,
                      first->got->real, first->expected->raw, first->expected->real);
      if (differ > 1)
        fields += fmt::format(", and {} more field{} differ", differ - 1, differ == 2 ? "" : "s");
    }
    return fmt::format("mismatch at cycle {}, vector {} (output {} of {}): {}{}{}", d.cycle,
                       *d.vector, d.output.value_or(0) + 1, d.outputs_of_vector, fields,
                       d.first_differing_stage.empty()
                           ? ""
                           : fmt::format("; first stage to differ: {}", d.first_differing_stage),
                       d.contract.empty() ? "" : fmt::format("; input contract: {}", d.contract));
  }
  if (d.kind == "unexpected output") {
    return fmt::format("unexpected output at cycle {}: no vector owes an output then", d.cycle);
  }
  return fmt::format("{}: {}", d.kind, harness);
}

}  // namespace

std::string value_text(std::int64_t raw, fx::Format fmt) {
  return fmt::format("0x{:0{}x} {:>6} {}", fx::to_bits(raw, fmt), (fmt.width() + 3) / 4, raw,
                     fx::to_real(raw, fmt));
}

std::string CosimReport::summary() const {
  std::string s = fmt::format("{} {}/{}: ", passed ? "PASS" : "FAIL", pipeline, config_name);
  if (options.only_index) {  // --vector-index: that vector alone
    s += fmt::format("vector {} alone ({}, seed {}{}), ", *options.only_index,
                     directed != 0 ? "directed" : "random", options.seed,
                     vectors == 0 ? ", not accepted" : "");
  } else {
    s += fmt::format("{} ({} directed + {} random, seed {}), ",
                     passed ? fmt::format("{} vectors", vectors)
                            : fmt::format("{} of {} vectors accepted", vectors, directed + random),
                     directed, random, options.seed);
  }
  if (contract) s += contract_text + ", ";
  s += fmt::format("{} output{} compared, {} mismatch{}, {} cycles; source {}, sink {}", outputs,
                   outputs == 1 ? "" : "s", mismatches, mismatches == 1 ? "" : "es", cycles,
                   options.source.str(), options.sink.str());
  s += fmt::format("; longest since reset {} vectors, {} outputs ({} DUT{})", longest_vectors,
                   longest_outputs, duts, duts == 1 ? "" : "s");
  if (passed) s += fmt::format("; drain {} cycles", drain_cycles);
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
  r.command = subject.command;
  r.config_option =
      subject.config_option.value_or(" --config " + shell_quoted(subject.cfg.origin()));
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
  if (count == 0) {
    throw Error(
        "nothing to check: the run has no vectors (--vectors 0 with --no-directed); a run that "
        "checks nothing cannot pass");
  }
  if (options.reset_every != 0 && !splittable(subject)) {
    throw Error(fmt::format(
        "--reset-every: {}'s vectors depend on the ones before them and it has no group starts "
        "to reset at",
        subject.pipeline));
  }

  HarnessOptions ho;
  ho.source = options.source;
  ho.sink = options.sink;
  ho.seed = options.seed;
  ho.timeout = options.timeout;
  if (!options.trace_path.empty()) {  // passing run: the first trace_window cycles
    ho.trace_path = options.trace_path;
    ho.trace_to = options.trace_window;
  }
  const std::vector<Shard> shards = shards_of(subject, options, first, count);
  const std::uint64_t shards_first = shards.front().first;
  MainRun run = run_shards(subject, options, ho, shards);
  const Phase& main = run.last;
  r.vectors = run.inputs;
  r.outputs = run.outputs;
  r.cycles = run.cycles;
  r.duts = run.duts;
  r.longest_vectors = run.longest_inputs;
  r.longest_outputs = run.longest_outputs;
  r.drain_cycles = run.drain;
  r.source_idle_cycles = run.source_idle;
  r.sink_stall_cycles = run.sink_stalled;
  if (subject.contract.defined()) {
    r.contract_clauses = subject.contract.clauses();
    r.contract = run.contract;
    r.contract->by_clause.resize(r.contract_clauses.size());
    r.contract_text = subject.contract.summary(*r.contract);
  }
  r.passed = main.kind.empty();
  if (!r.passed) {
    r.mismatches = rejects_an_output(main.kind) ? 1 : 0;
    r.outputs += r.mismatches;  // the output that failed was compared too
    r.failure_kind = main.kind;
    const std::uint64_t fail_cycle = main.harness.cycles - 1;
    r.failure_detail = main.detail;
    CosimFailure& d = *r.failure_detail;
    const std::vector<StageValue> stage_values =
        describe_vector(subject, options.seed, run.shard.first, d);
    // The same run again, traced around the failure: for the user's waveform, and to look for
    // the stages in the design's signals.
    const bool locate = !stage_values.empty() && subject.traceable;
    if (!options.trace_path.empty() || locate) {
      std::optional<TempDir> dir;
      ho.trace_path = options.trace_path;
      if (ho.trace_path.empty()) {
        dir.emplace("out");
        ho.trace_path = (dir->path() / "trace.fst").string();
      }
      ho.trace_from = fail_cycle > options.trace_window ? fail_cycle - options.trace_window : 0;
      ho.trace_to = fail_cycle + 1;
      ho.stall_stream = run.shard.stream;
      Phase traced;
      {
        DutPtr dut = make_dut();  // its waveform is complete once it is gone
        traced = run_phase(model, *dut, stimulus, subject.contract, options, ho, run.shard.first,
                           run.shard.count);
      }
      if (locate) locate_stages(ho.trace_path, stage_values, traced.notes, ho.trace_from, d);
      if (!options.trace_path.empty()) {
        complete_notes(subject, options.seed, run.shard.first, traced.harness.inputs, traced.notes);
        annotate_waveform(options.trace_path, traced.notes);
      }
    }
    d.message = failure_message(d, main.harness.message);
    r.failure =
        main.report + vector_text(d) +
        failure_context(r, options.only_index, main.failing_index, subject.independent_vectors);
    if (!options.trace_path.empty()) {
      r.failure += fmt::format("  waveform of cycles {}..{}: {}\n", ho.trace_from, ho.trace_to,
                               options.trace_path);
    }
  } else if (!options.trace_path.empty()) {
    Phase& traced = run.duts > 1 ? run.first : run.last;
    complete_notes(subject, options.seed, shards_first, traced.harness.inputs, traced.notes);
    annotate_waveform(options.trace_path, traced.notes);
  }
  if (!options.trace_path.empty()) r.trace_written = options.trace_path;

  // Measurement run: stall-free, random vectors, for throughput and latency.
  if (r.passed && options.measure_vectors > 0 && !options.only_index) {
    HarnessOptions mo;
    mo.timeout = options.timeout;
    DutPtr dut = make_dut();
    const Phase m = run_phase(model, *dut, stimulus, InputContract(), options, mo,
                              stimulus.directed_count(), options.measure_vectors);
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
      r.failure_detail = m.detail;
      r.failure_detail->in_measurement_run = true;
      (void)describe_vector(subject, options.seed, stimulus.directed_count(), *r.failure_detail);
      r.failure_detail->message = failure_message(*r.failure_detail, m.harness.message);
      r.failure =
          m.report + vector_text(*r.failure_detail) + "  (in the stall-free measurement run)\n" +
          failure_context(as_run, std::nullopt, m.failing_index, subject.independent_vectors);
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
