// Does the co-simulation framework (sim/harness.*, sim/cosim.*) really catch broken RTL? Without
// Verilator: FakeDut is a correct L-stage valid/ready pipeline computing the lirp model, with
// one injectable fault. Every fault must fail with the right kind and a report that pins it
// down; the fault-free DUT must pass under every stall pattern.
//
// Unless a test says otherwise: seed 7, the 1859 directed vectors plus 2000 random ones, no
// stalls, so vector i is accepted in cycle i and its output is taken in cycle i + L. The
// expected cycles below follow from that.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <memory>
#include <optional>
#include <regex>
#include <span>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "model/config.h"
#include "model/fixed.h"
#include "model/lirp.h"
#include "sim/cosim/cosim.h"
#include "sim/cosim/harness.h"
#include "sim/cosim/rtl_dut.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/stall.h"
#include "sim/pipelines/registry.h"

namespace {

namespace fx = phongsim::fx;
using phongsim::Config;
using phongsim::CosimOptions;
using phongsim::CosimReport;
using phongsim::DutDeleter;
using phongsim::DutPtr;
using phongsim::LirpFormats;
using phongsim::LirpModel;
using phongsim::StallPattern;

constexpr const char* kConfigPath = PHONGSIM_SOURCE_DIR "/configs/lirp/default.toml";
constexpr std::size_t kLatency = 3;
constexpr std::uint64_t kSeed = 7;
constexpr std::uint64_t kDirected = 11 * 13 * 13;  // 11 a corners x 13 x 13 p corners (S1.10)
constexpr std::uint64_t kRandom = 2000;
constexpr std::uint64_t kVectors = kDirected + kRandom;
constexpr std::uint64_t kTimeout = 200;
constexpr std::uint64_t kK = 2500;  // victim transaction: a random vector, so its outputs are
                                    // unlike its neighbours' (directed ones repeat)

// ---- the fake RTL ----

enum class Fault {
  none,
  corrupt_lsb,           // flip bit 0 of one output field of #k
  drop,                  // never emit #k
  duplicate,             // emit #k twice
  swap,                  // emit #k+1 before #k
  stall_forever,         // in_ready stays low once #k is accepted
  withdraw_valid,        // the first output after #k held by the sink loses out_valid a cycle
  change_while_stalled,  // ... or has its data changed
  never_ready_output,    // out_valid never asserted for anything after #k
};

struct FaultSpec {
  Fault fault = Fault::none;
  std::int64_t k = 0;  // transaction ordinal, in acceptance order from 0; -1 = before the first
  std::vector<std::int64_t> trigger;   // corrupt_lsb: hit the first transaction with these inputs
  std::vector<std::int64_t> trigger2;  // ... or with these
  std::size_t field = 1;               // corrupt_lsb: output field (p_y)
};

FaultSpec Inject(Fault fault, std::int64_t k, std::size_t field = 1) {
  FaultSpec f;
  f.fault = fault;
  f.k = k;
  f.field = field;
  return f;
}

// What the fake did, for exact expectations in runs with stalls. Outlives the DUTs.
struct Probe {
  int instances = 0;
  std::optional<std::uint64_t> fault_cycle;    // cycle in which the fault first hit the ports
  std::optional<std::uint64_t> fault_ordinal;  // transaction it hit
};

// A correct pipeline of `latency` registers with bubble-collapsing backpressure: a stage advances
// when the next one is empty or advancing; the last stage is the output register, held while
// out_ready is low. Accepted in cycle c, visible in cycle c + latency at the earliest.
class FakeDut final : public phongsim::RtlDut {
 public:
  FakeDut(const LirpFormats& formats, std::size_t latency, FaultSpec fault, Probe* probe)
      : model_(formats),
        fault_(std::move(fault)),
        probe_(probe),
        stages_(latency),
        moves_(latency) {
    if (probe_ != nullptr) ++probe_->instances;
  }

  void reset() override {
    for (auto& s : stages_) s.reset();
    cycle_ = 0;
    accepted_ = 0;
    in_valid_ = out_ready_ = in_ready_ = out_valid_ = false;
    withdraw_now_ = protocol_fault_done_ = trigger_used_ = false;
  }
  void set_input(std::span<const std::int64_t> fields) override {
    in_.assign(fields.begin(), fields.end());
  }
  void set_in_valid(bool valid) override { in_valid_ = valid; }
  void set_out_ready(bool ready) override { out_ready_ = ready; }

  void settle() override {
    const auto& head = stages_.back();
    out_valid_ = head.has_value() && Visible(*head);
    const bool fire = out_valid_ && out_ready_;
    // The duplicated transaction stays in the output register for a second handshake.
    const bool leaves =
        fire && !(Is(Fault::duplicate) && Ordinal(*head) == fault_.k && !head->repeated);
    const std::size_t last = stages_.size() - 1;
    moves_[last] = leaves;
    bool free_next = !head.has_value() || leaves;
    for (std::size_t j = last; j-- > 0;) {
      moves_[j] = stages_[j].has_value() && free_next;
      free_next = !stages_[j].has_value() || moves_[j];
    }
    in_ready_ = free_next && !(Is(Fault::stall_forever) && Ordinal(accepted_) > fault_.k);
  }

  [[nodiscard]] bool in_ready() const override { return in_ready_; }
  [[nodiscard]] bool out_valid() const override { return out_valid_; }
  void output(std::span<std::int64_t> fields) const override {
    const auto& out = stages_.back()->out;
    std::copy(out.begin(), out.end(), fields.begin());
  }

  void clock() override {
    auto& head = stages_.back();
    if (out_valid_ && out_ready_) {
      if (head->faulty) Record(cycle_, head->ordinal);
      if (Is(Fault::duplicate) && Ordinal(*head) == fault_.k && !head->repeated) {
        head->repeated = true;
        head->faulty = true;  // the second handshake is the fault
      }
    }
    withdraw_now_ = false;
    if (out_valid_ && !out_ready_ && !protocol_fault_done_ && Ordinal(*head) > fault_.k) {
      if (Is(Fault::withdraw_valid)) {
        withdraw_now_ = true;
        protocol_fault_done_ = true;
        Record(cycle_ + 1, head->ordinal);
      } else if (Is(Fault::change_while_stalled)) {
        head->out[0] ^= 1;
        protocol_fault_done_ = true;
        Record(cycle_ + 1, head->ordinal);
      }
    }
    for (std::size_t j = stages_.size(); j-- > 0;) {  // downstream first: frees the next stage
      if (!moves_[j]) continue;
      if (j + 1 < stages_.size()) stages_[j + 1] = std::move(stages_[j]);
      stages_[j].reset();
    }
    if (in_valid_ && in_ready_) Accept();
    ++cycle_;
  }

  [[nodiscard]] std::uint64_t cycle() const override { return cycle_; }
  [[nodiscard]] bool assertion_failed() const override { return false; }
  void open_trace(const std::string&) override {}
  void close_trace() override {}

 private:
  struct Entry {
    std::uint64_t ordinal = 0;
    std::vector<std::int64_t> out;
    bool faulty = false;    // its next handshake shows the fault
    bool repeated = false;  // duplicate: first handshake done
  };

  [[nodiscard]] bool Is(Fault f) const { return fault_.fault == f; }
  static std::int64_t Ordinal(std::uint64_t n) { return static_cast<std::int64_t>(n); }
  static std::int64_t Ordinal(const Entry& e) { return Ordinal(e.ordinal); }

  [[nodiscard]] bool Visible(const Entry& e) const {
    if (Is(Fault::never_ready_output) && Ordinal(e) > fault_.k) return false;
    // Swap: #k waits until #k+1 is in (so the swap is never seen as data changing under valid).
    if (Is(Fault::swap) && Ordinal(e) == fault_.k && Ordinal(accepted_) < fault_.k + 2) {
      return false;
    }
    return !withdraw_now_;
  }

  void Record(std::uint64_t cycle, std::uint64_t ordinal) {
    if (probe_ == nullptr || probe_->fault_cycle) return;
    probe_->fault_cycle = cycle;
    probe_->fault_ordinal = ordinal;
  }

  void Accept() {
    Entry e;
    e.ordinal = accepted_++;
    (void)model_.eval(in_, e.out);
    const std::int64_t n = Ordinal(e);
    if (Is(Fault::corrupt_lsb)) {
      const bool hit = fault_.trigger.empty()
                           ? n == fault_.k
                           : !trigger_used_ && (in_ == fault_.trigger || in_ == fault_.trigger2);
      if (hit) {
        trigger_used_ = true;
        e.out[fault_.field] ^= 1;
        e.faulty = true;
      }
    }
    if (Is(Fault::drop) && n == fault_.k) return;  // accepted, never stored
    if (Is(Fault::drop) && n == fault_.k + 1) e.faulty = true;
    if (Is(Fault::swap) && n == fault_.k + 1) {
      for (auto& s : stages_) {
        if (s && Ordinal(*s) == fault_.k) {
          std::swap(s->out, e.out);
          s->faulty = true;
        }
      }
    }
    stages_[0] = std::move(e);
  }

  LirpModel model_;  // its own copy: the DUT computes independently of the scoreboard's model
  FaultSpec fault_;
  Probe* probe_;
  std::vector<std::optional<Entry>> stages_;  // [0] input side ... [L-1] output register
  std::vector<bool> moves_;                   // per stage: advances at this edge
  std::vector<std::int64_t> in_;
  std::uint64_t cycle_ = 0;
  std::uint64_t accepted_ = 0;
  bool in_valid_ = false;
  bool out_ready_ = false;
  bool in_ready_ = false;
  bool out_valid_ = false;
  bool withdraw_now_ = false;
  bool protocol_fault_done_ = false;
  bool trigger_used_ = false;
};

// ---- expected report text ----

// One field line of a report, as specified by cosim.cpp's describe().
// One value as the reports print it: bit pattern, raw integer, real.
std::string Value(const phongsim::Field& f, std::int64_t raw) {
  return fmt::format("0x{:0{}x} {:>6} {}", fx::to_bits(raw, f.fmt), (f.fmt.width() + 3) / 4, raw,
                     fx::to_real(raw, f.fmt));
}

// A report line for one field: name, format, value.
std::string Describe(const phongsim::Field& f, std::int64_t raw) {
  return fmt::format("{:<8} {:>7}  {}", f.name, f.fmt.str(), Value(f, raw));
}

class Cosim : public testing::Test {
 protected:
  Config cfg_ = Config::load(kConfigPath);
  const phongsim::PipelineInfo& lirp_ = phongsim::find_pipeline("lirp");
  std::unique_ptr<phongsim::PipelineModel> model_ = phongsim::make_model(lirp_, cfg_);
  LirpFormats formats_ = dynamic_cast<const LirpModel&>(*model_).formats();
  phongsim::Stimulus stimulus_ = lirp_.make_stimulus(*model_, cfg_);

  static CosimOptions Options(const std::string& source = "none",
                              const std::string& sink = "none") {
    CosimOptions o;
    o.seed = kSeed;
    o.random_vectors = kRandom;
    o.timeout = kTimeout;
    o.source = StallPattern::parse(source);
    o.sink = StallPattern::parse(sink);
    return o;
  }

  // shard_vectors > 0: the main run split into shards of about that many vectors (cosim.h).
  CosimReport Run(const FaultSpec& fault, const CosimOptions& o, Probe* probe = nullptr,
                  std::uint64_t shard_vectors = 0) {
    const phongsim::DutFactory factory = [&] {
      return DutPtr(new FakeDut(formats_, kLatency, fault, probe), DutDeleter{});
    };
    const phongsim::CosimSubject subject{"lirp",  cfg_, *model_, stimulus_,    true,
                                         factory, "",   "",      shard_vectors};
    return phongsim::cosim(subject, o);
  }

  std::vector<std::int64_t> Inputs(std::uint64_t index) const {
    std::vector<std::int64_t> in(model_->inputs().size());
    stimulus_.vector(kSeed, index, in);
    return in;
  }
  std::vector<std::int64_t> Outputs(std::uint64_t index) {
    std::vector<std::int64_t> out;
    LirpModel m(formats_);
    (void)m.eval(Inputs(index), out);
    return out;
  }

  // The MISMATCH block for vector `index` receiving `got` in `cycle`.
  std::string Mismatch(std::uint64_t cycle, std::uint64_t index, const std::string& hint,
                       const std::vector<std::int64_t>& got) {
    std::string s = fmt::format("MISMATCH at cycle {}, vector {} (output 1 of 1 for it){}\n", cycle,
                                index, hint);
    s += "  inputs:\n";
    const auto in = Inputs(index);
    for (std::size_t i = 0; i < in.size(); ++i) {
      s += "    " + Describe(model_->inputs()[i], in[i]) + "\n";
    }
    const auto want = Outputs(index);
    std::size_t column = 16;  // widest expected value + 4
    for (std::size_t i = 0; i < want.size(); ++i) {
      column = std::max(column, Value(model_->outputs()[i], want[i]).size() + 4);
    }
    s += "  outputs:" + std::string(12, ' ') + "expected" + std::string(column - 8, ' ') + "got\n";
    for (std::size_t i = 0; i < want.size(); ++i) {
      const auto& f = model_->outputs()[i];
      const std::string w = Value(f, want[i]);
      s += "    " + Describe(f, want[i]) + std::string(column - w.size(), ' ') + Value(f, got[i]) +
           (want[i] != got[i] ? "   <-- differs" : "") + "\n";
    }
    return s;
  }

  // The lines cosim appends to every main-run failure.
  static std::string Context(const CosimOptions& o, std::optional<std::uint64_t> alone) {
    std::string patterns =
        fmt::format("--source-idle {} --backpressure {}", o.source.str(), o.sink.str());
    if (o.timeout != 0) patterns += fmt::format(" --timeout {}", o.timeout);
    const std::string cmd =
        fmt::format("phongsim cosim --pipeline lirp --config {} --seed {}", kConfigPath, o.seed);
    std::string s = fmt::format(
        "  pipeline lirp, config default ({}), seed {}, source idle {}, sink backpressure {}\n",
        kConfigPath, o.seed, o.source.str(), o.sink.str());
    if (o.only_index) {
      s += fmt::format("  reproduce: {} --vector-index {} {}\n", cmd, *o.only_index, patterns);
    } else {
      s += fmt::format("  reproduce: {} --vectors {} {}\n", cmd, o.random_vectors, patterns);
      if (alone)
        s += fmt::format("  this vector alone: {} --vector-index {} {}\n", cmd, *alone, patterns);
    }
    return s;
  }
};

// ---- the fake itself ----

TEST_F(Cosim, SetupMatchesTheBrief) {
  EXPECT_EQ(formats_.p, (fx::Format{true, 1, 10}));
  EXPECT_EQ(formats_.a, (fx::Format{false, 1, 10}));
  EXPECT_EQ(formats_.out, (fx::Format{true, 1, 10}));
  EXPECT_EQ(formats_.out_round, fx::Round::half_even);
  EXPECT_EQ(formats_.out_overflow, fx::Overflow::saturate);
  EXPECT_EQ(stimulus_.directed_count(), kDirected);
  // The victim's neighbours have distinct outputs, so hints cannot be confused by equal values.
  EXPECT_NE(Outputs(kK - 1), Outputs(kK));
  EXPECT_NE(Outputs(kK), Outputs(kK + 1));
  EXPECT_NE(Outputs(kK - 1), Outputs(kK + 1));
}

// Before trusting the fake to judge the framework: latency, capacity and holding under a
// stalled sink, driven by hand with the per-cycle protocol of rtl_dut.h.
TEST_F(Cosim, FakeDutIsAWellBehavedPipeline) {
  FakeDut dut(formats_, kLatency, {}, nullptr);
  dut.reset();
  EXPECT_EQ(dut.cycle(), 0u);
  std::vector<std::int64_t> out(3);
  // Sink stalled: accepts exactly L transactions (cycles 0..L-1), first output visible in L.
  for (std::uint64_t c = 0; c < 10; ++c) {
    dut.set_input(Inputs(c < kLatency ? c : kLatency));
    dut.set_in_valid(true);
    dut.set_out_ready(false);
    dut.settle();
    EXPECT_EQ(dut.in_ready(), c < kLatency) << c;
    EXPECT_EQ(dut.out_valid(), c >= kLatency) << c;
    if (dut.out_valid()) {
      dut.output(out);
      EXPECT_EQ(out, Outputs(0)) << c;  // held
    }
    dut.clock();
    EXPECT_EQ(dut.cycle(), c + 1);
  }
  // Sink ready: one output and one input per cycle, in order.
  for (std::uint64_t i = 0; i < 6; ++i) {
    dut.set_input(Inputs(kLatency + i));
    dut.set_in_valid(true);
    dut.set_out_ready(true);
    dut.settle();
    EXPECT_TRUE(dut.in_ready()) << i;
    ASSERT_TRUE(dut.out_valid()) << i;
    dut.output(out);
    EXPECT_EQ(out, Outputs(i)) << i;
    dut.clock();
  }
}

// ---- no fault: passes under every combination of stall patterns ----

const char* const kPatterns[] = {"none", "periodic:1110", "periodic:0001", "random:0.5",
                                 "long:64:100"};

class CosimPatterns : public Cosim,
                      public testing::WithParamInterface<std::tuple<const char*, const char*>> {};

TEST_P(CosimPatterns, NoFaultPasses) {
  const auto [source, sink] = GetParam();
  CosimOptions o = Options(source, sink);
  o.timeout = 0;  // the automatic timeout: long stalls must not count as deadlock
  Probe probe;
  const CosimReport r = Run({}, o, &probe);
  EXPECT_TRUE(r.passed) << r.failure;
  EXPECT_EQ(r.failure_kind, "");
  EXPECT_EQ(r.failure, "");
  EXPECT_EQ(r.mismatches, 0u);
  EXPECT_EQ(r.directed, kDirected);
  EXPECT_EQ(r.random, kRandom);
  EXPECT_EQ(r.vectors, kVectors);
  EXPECT_EQ(r.outputs, kVectors);
  // Stall-free measurement: one output per clock, every latency exactly L.
  EXPECT_EQ(r.throughput, 1.0);
  EXPECT_EQ(r.latency_min, kLatency);
  EXPECT_EQ(r.latency_max, kLatency);
  EXPECT_EQ(probe.instances, 2);  // main run + measurement run, a fresh DUT each
  EXPECT_FALSE(probe.fault_cycle);
  if (std::string(source) == "none" && std::string(sink) == "none") {
    // Last vector accepted in kVectors - 1, taken in kVectors - 1 + L; that ends the run.
    EXPECT_EQ(r.cycles, kVectors + kLatency);
    EXPECT_EQ(r.summary(),
              "PASS lirp/default: 3859 vectors (1859 directed + 2000 random, seed 7), 3859 "
              "outputs, 0 mismatches, 3862 cycles; source none, sink none; throughput "
              "1.000/clock, latency 3 cycles");
  } else {
    EXPECT_GT(r.cycles, kVectors + kLatency);  // stalls cost cycles
  }
}

std::string PatternName(const char* spec) {
  std::string s = spec;
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return s;
}

INSTANTIATE_TEST_SUITE_P(AllStallPatterns, CosimPatterns,
                         testing::Combine(testing::ValuesIn(kPatterns),
                                          testing::ValuesIn(kPatterns)),
                         [](const testing::TestParamInfo<CosimPatterns::ParamType>& info) {
                           return "source_" + PatternName(std::get<0>(info.param)) + "_sink_" +
                                  PatternName(std::get<1>(info.param));
                         });

// ---- each fault is caught, with the right kind and an exact report ----

TEST_F(Cosim, CorruptLsbIsAMismatchMarkingTheField) {
  const CosimOptions o = Options();
  Probe probe;
  const CosimReport r = Run(Inject(Fault::corrupt_lsb, kK), o, &probe);
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.failure_kind, "mismatch");
  auto got = Outputs(kK);
  got[1] ^= 1;
  EXPECT_EQ(r.failure, Mismatch(kK + kLatency, kK, "", got) + Context(o, kK));
  // Only p_y is marked.
  std::size_t marks = 0;
  for (auto at = r.failure.find("<-- differs"); at != std::string::npos;
       at = r.failure.find("<-- differs", at + 1)) {
    ++marks;
  }
  EXPECT_EQ(marks, 1u);
  const auto marked = r.failure.rfind('\n', r.failure.find("<-- differs")) + 1;
  EXPECT_EQ(r.failure.substr(marked, 8), "    p_y ");
  EXPECT_EQ(probe.fault_cycle, kK + kLatency);
  // Vectors accepted through the failing cycle; outputs before the failing one; no measurement.
  EXPECT_EQ(r.vectors, kK + kLatency + 1);
  EXPECT_EQ(r.outputs, kK);
  EXPECT_EQ(r.cycles, kK + kLatency + 1);
  EXPECT_EQ(r.mismatches, 1u);
  EXPECT_EQ(r.throughput, 0.0);
  EXPECT_EQ(r.summary(),
            "FAIL lirp/default: 2504 of 3859 vectors accepted (1859 directed + 2000 random, seed "
            "7), 2500 "
            "outputs, 1 mismatches, 2504 cycles; source none, sink none; first failure: "
            "mismatch");
  EXPECT_EQ(probe.instances, 1);
}

TEST_F(Cosim, CorruptLsbOfEveryFieldIsCaught) {
  for (std::size_t field = 0; field < 3; ++field) {
    SCOPED_TRACE(field);
    const CosimOptions o = Options();
    const CosimReport r = Run(Inject(Fault::corrupt_lsb, kK, field), o);
    auto got = Outputs(kK);
    got[field] ^= 1;
    EXPECT_EQ(r.failure_kind, "mismatch");
    EXPECT_EQ(r.failure, Mismatch(kK + kLatency, kK, "", got) + Context(o, kK));
  }
}

TEST_F(Cosim, SwapIsAMismatchHintingReordered) {
  const CosimOptions o = Options();
  const CosimReport r = Run(Inject(Fault::swap, kK), o);
  EXPECT_EQ(r.failure_kind, "mismatch");
  const std::string hint =
      fmt::format("; it is the expected output of vector {}: reordered or dropped?", kK + 1);
  EXPECT_EQ(r.failure, Mismatch(kK + kLatency, kK, hint, Outputs(kK + 1)) + Context(o, kK));
}

// Dropping #k shows as vector k receiving vector k+1's output: a mismatch with the
// reordered-or-dropped hint, in the cycle #k+1 comes out.
TEST_F(Cosim, DropInTheStreamIsAMismatchHintingDropped) {
  const CosimOptions o = Options();
  Probe probe;
  const CosimReport r = Run(Inject(Fault::drop, kK), o, &probe);
  EXPECT_EQ(r.failure_kind, "mismatch");
  const std::string hint =
      fmt::format("; it is the expected output of vector {}: reordered or dropped?", kK + 1);
  EXPECT_EQ(r.failure, Mismatch(kK + 1 + kLatency, kK, hint, Outputs(kK + 1)) + Context(o, kK));
  EXPECT_EQ(probe.fault_cycle, kK + 1 + kLatency);
}

// Nothing comes after the last vector, so dropping it can only show as the scoreboard waiting
// for it: a deadlock naming the vector that owes its output.
TEST_F(Cosim, DropOfTheLastVectorIsADeadlock) {
  const CosimOptions o = Options();
  const std::uint64_t last = kVectors - 1;
  const CosimReport r = Run(Inject(Fault::drop, static_cast<std::int64_t>(last)), o);
  EXPECT_EQ(r.failure_kind, "deadlock");
  // Last handshake: output of vector last - 1 in cycle last + L - 1 = 3860.
  const std::uint64_t cycle = last + kLatency - 1 + kTimeout + 1;
  EXPECT_EQ(cycle, 4061u);
  EXPECT_EQ(r.failure,
            fmt::format("DEADLOCK: cycle {}: no handshake for {} cycles ({} inputs accepted, {} "
                        "outputs taken)\n  pending: 1 vectors still owe outputs, oldest vector {} "
                        "(accepted at cycle {}, 0 of 1 outputs seen)\n",
                        cycle, kTimeout, kVectors, kVectors - 1, last, last) +
                Context(o, std::nullopt));
  EXPECT_EQ(r.cycles, cycle + 1);
}

// With the next vector already accepted, the repeat is compared against it: a mismatch whose
// hint says duplicated.
TEST_F(Cosim, DuplicateInTheStreamIsAMismatchHintingDuplicated) {
  const CosimOptions o = Options();
  Probe probe;
  const CosimReport r = Run(Inject(Fault::duplicate, kK), o, &probe);
  EXPECT_EQ(r.failure_kind, "mismatch");
  EXPECT_EQ(r.failure, Mismatch(kK + 1 + kLatency, kK + 1,
                                "; it repeats the previous output: duplicated?", Outputs(kK)) +
                           Context(o, kK + 1));
  EXPECT_EQ(probe.fault_cycle, kK + 1 + kLatency);
}

// With a sparse source (one offer every 4 cycles) nothing else is in flight when the repeat
// comes out: an unexpected output, flagged as a duplicate.
TEST_F(Cosim, DuplicateWithNothingInFlightIsAnUnexpectedOutput) {
  const CosimOptions o = Options("periodic:0001");
  const CosimReport r = Run(Inject(Fault::duplicate, kK), o);
  EXPECT_EQ(r.failure_kind, "unexpected output");
  // Vector i is offered and accepted in cycle 4i + 3 and taken in 4i + 3 + L; the repeat
  // follows one cycle later, the same cycle vector k+1 is accepted (after the output check).
  const std::uint64_t cycle = 4 * kK + 3 + kLatency + 1;
  std::string expected = fmt::format(
      "UNEXPECTED OUTPUT at cycle {}: the model expects no output now (all {} checked outputs "
      "matched); duplicated or extra output\n  got:\n",
      cycle, kK + 1);
  const auto got = Outputs(kK);
  for (std::size_t i = 0; i < 3; ++i) {
    expected += "    " + Describe(model_->outputs()[i], got[i]) + "\n";
  }
  expected += "  it repeats the previous output: duplicated\n";
  EXPECT_EQ(r.failure, expected + Context(o, std::nullopt));
}

TEST_F(Cosim, StallForeverIsADeadlock) {
  const CosimOptions o = Options();
  const CosimReport r = Run(Inject(Fault::stall_forever, kK), o);
  EXPECT_EQ(r.failure_kind, "deadlock");
  // Last handshake: #k's output in cycle k + L. (The pending line is checked in
  // BugDeadlockPendingListsOnlyVectorsThatOweOutputs.)
  const std::uint64_t cycle = kK + kLatency + kTimeout + 1;
  EXPECT_TRUE(r.failure.starts_with(
      fmt::format("DEADLOCK: cycle {}: no handshake for {} cycles ({} inputs accepted, {} "
                  "outputs taken, an input is waiting for in_ready)\n  pending: ",
                  cycle, kTimeout, kK + 1, kK + 1)))
      << r.failure;
  EXPECT_TRUE(r.failure.ends_with(Context(o, std::nullopt))) << r.failure;
  EXPECT_EQ(r.cycles, cycle + 1);
}

TEST_F(Cosim, NeverReadyOutputIsADeadlock) {
  const CosimOptions o = Options();
  const CosimReport r = Run(Inject(Fault::never_ready_output, kK), o);
  EXPECT_EQ(r.failure_kind, "deadlock");
  // #k taken in k + L, when #k+L is accepted; then the pipeline is full behind #k+1.
  const std::uint64_t cycle = kK + kLatency + kTimeout + 1;
  EXPECT_EQ(r.failure,
            fmt::format("DEADLOCK: cycle {}: no handshake for {} cycles ({} inputs accepted, {} "
                        "outputs taken, an input is waiting for in_ready)\n  pending: {} vectors "
                        "still owe outputs, oldest vector {} (accepted at cycle {}, 0 of 1 "
                        "outputs seen)\n  waiting for in_ready: vector {}\n",
                        cycle, kTimeout, kK + kLatency + 1, kK + 1, kLatency, kK + 1, kK + 1,
                        kK + kLatency + 1) +
                Context(o, std::nullopt));
}

// Protocol faults need a sink that stalls. periodic:1110 stalls in cycles 3 mod 4, so an output
// can only be held there and the violation is seen in the next cycle, 0 mod 4.
TEST_F(Cosim, WithdrawnValidIsAProtocolViolation) {
  const CosimOptions o = Options("none", "periodic:1110");
  Probe probe;
  const CosimReport r = Run(Inject(Fault::withdraw_valid, kK), o, &probe);
  EXPECT_EQ(r.failure_kind, "protocol");
  ASSERT_TRUE(probe.fault_cycle);
  const std::uint64_t cycle = *probe.fault_cycle;
  EXPECT_EQ(cycle % 4, 0u);
  EXPECT_GT(*probe.fault_ordinal, kK);
  EXPECT_EQ(r.failure, fmt::format("HANDSHAKE VIOLATION: cycle {}: output withdrawn (valid "
                                   "dropped) while the sink was stalling it\n  the offending "
                                   "output is the one due for vector {}\n",
                                   cycle, *probe.fault_ordinal) +
                           Context(o, std::nullopt));
}

TEST_F(Cosim, DataChangedWhileStalledIsAProtocolViolation) {
  const CosimOptions o = Options("none", "periodic:1110");
  Probe probe;
  const CosimReport r = Run(Inject(Fault::change_while_stalled, kK), o, &probe);
  EXPECT_EQ(r.failure_kind, "protocol");
  ASSERT_TRUE(probe.fault_cycle);
  const std::uint64_t cycle = *probe.fault_cycle;
  EXPECT_EQ(cycle % 4, 0u);
  EXPECT_EQ(r.failure,
            fmt::format("HANDSHAKE VIOLATION: cycle {}: output changed while the sink was "
                        "stalling it\n  the offending output is the one due for vector {}\n",
                        cycle, *probe.fault_ordinal) +
                Context(o, std::nullopt));
}

// Every fault is still caught, with the same kind, under random stalls on both sides.
TEST_F(Cosim, EveryFaultIsCaughtUnderRandomStalls) {
  const std::pair<Fault, const char*> cases[] = {
      {Fault::corrupt_lsb, "mismatch"},
      {Fault::drop, "mismatch"},
      {Fault::swap, "mismatch"},
      {Fault::stall_forever, "deadlock"},
      {Fault::withdraw_valid, "protocol"},
      {Fault::change_while_stalled, "protocol"},
      {Fault::never_ready_output, "deadlock"},
  };
  for (const auto& [fault, kind] : cases) {
    SCOPED_TRACE(kind);
    const CosimOptions o = Options("random:0.5", "random:0.5");
    Probe probe;
    const CosimReport r = Run(Inject(fault, kK), o, &probe);
    EXPECT_FALSE(r.passed);
    EXPECT_EQ(r.failure_kind, kind);
    // Mismatches also offer the failing vector alone; it is #k for all three.
    const std::string context =
        Context(o, std::string(kind) == "mismatch" ? std::optional(kK) : std::nullopt);
    EXPECT_TRUE(r.failure.ends_with(context)) << r.failure;
    if (std::string(kind) != "deadlock") {
      ASSERT_TRUE(probe.fault_cycle);
      EXPECT_NE(r.failure.find(fmt::format(" cycle {}", *probe.fault_cycle)), std::string::npos)
          << r.failure;
    }
  }
  // Duplicate: mismatch or unexpected output depending on what else is in flight, always
  // flagged as a duplicate.
  const CosimReport dup = Run(Inject(Fault::duplicate, kK), Options("random:0.5", "random:0.5"));
  EXPECT_TRUE(dup.failure_kind == "mismatch" || dup.failure_kind == "unexpected output")
      << dup.failure_kind;
  EXPECT_NE(dup.failure.find("duplicated"), std::string::npos) << dup.failure;
}

// ---- reproducibility ----

TEST_F(Cosim, SameConfigAndSeedGiveTheSameFailure) {
  const CosimOptions o = Options("random:0.5", "random:0.3");
  Probe pa;
  Probe pb;
  const CosimReport a = Run(Inject(Fault::corrupt_lsb, kK), o, &pa);
  const CosimReport b = Run(Inject(Fault::corrupt_lsb, kK), o, &pb);
  const std::regex head("MISMATCH at cycle (\\d+), vector (\\d+)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(a.failure, m, head)) << a.failure;
  const std::uint64_t cycle = std::stoull(m[1]);
  EXPECT_EQ(std::stoull(m[2]), kK);
  EXPECT_GT(cycle, kK + kLatency);  // the stalls delayed it
  EXPECT_EQ(pa.fault_cycle, cycle);
  EXPECT_EQ(pb.fault_cycle, cycle);
  EXPECT_EQ(a.failure, b.failure);
  EXPECT_EQ(a.cycles, b.cycles);
  EXPECT_EQ(a.cycles, cycle + 1);
  EXPECT_EQ(a.vectors, b.vectors);
  // Another seed stalls differently (and draws other random vectors): another cycle.
  CosimOptions other = o;
  other.seed = kSeed + 1;
  const CosimReport c = Run(Inject(Fault::corrupt_lsb, kK), other);
  EXPECT_EQ(c.failure_kind, "mismatch");
  EXPECT_NE(c.cycles, a.cycles);
}

// A data-dependent fault (as real RTL bugs are) found in a full run is reproduced by the
// "this vector alone" command: only_index runs that one vector and fails on it.
TEST_F(Cosim, VectorIndexReproducesAMismatchAlone) {
  const CosimOptions o = Options("random:0.5", "random:0.5");
  FaultSpec fault = Inject(Fault::corrupt_lsb, 0, 2);
  fault.trigger = Inputs(kK);
  const CosimReport full = Run(fault, o);
  ASSERT_EQ(full.failure_kind, "mismatch");
  EXPECT_NE(full.failure.find(fmt::format(", vector {} (", kK)), std::string::npos);
  const std::string alone_line = fmt::format(
      "  this vector alone: phongsim cosim --pipeline lirp --config {} --seed 7 --vector-index "
      "{} --source-idle random:0.5 --backpressure random:0.5 --timeout {}\n",
      kConfigPath, kK, o.timeout);
  EXPECT_NE(full.failure.find(alone_line), std::string::npos) << full.failure;

  CosimOptions only = o;
  only.only_index = kK;
  Probe probe;
  const CosimReport r = Run(fault, only, &probe);
  EXPECT_EQ(r.failure_kind, "mismatch");
  ASSERT_TRUE(probe.fault_cycle);
  auto got = Outputs(kK);
  got[2] ^= 1;
  EXPECT_EQ(r.failure, Mismatch(*probe.fault_cycle, kK, "", got) + Context(only, std::nullopt));
  EXPECT_EQ(r.vectors, 1u);
  EXPECT_EQ(r.directed, 0u);
  EXPECT_EQ(r.random, 1u);
  EXPECT_EQ(r.outputs, 0u);
  EXPECT_EQ(probe.instances, 1);

  // Without stalls the lone vector goes in at cycle 0 and comes out at L.
  CosimOptions plain = Options();
  plain.only_index = kK;
  const CosimReport p = Run(fault, plain);
  EXPECT_EQ(p.failure, Mismatch(kLatency, kK, "", got) + Context(plain, std::nullopt));
}

TEST_F(Cosim, VectorIndexOfAPassingVectorRunsItAlone) {
  CosimOptions o = Options("periodic:0001", "random:0.5");
  o.only_index = 5;  // a directed vector
  Probe probe;
  const CosimReport r = Run({}, o, &probe);
  EXPECT_TRUE(r.passed) << r.failure;
  EXPECT_EQ(r.vectors, 1u);
  EXPECT_EQ(r.outputs, 1u);
  EXPECT_EQ(r.directed, 1u);
  EXPECT_EQ(r.random, 0u);
  EXPECT_EQ(r.throughput, 0.0);  // no measurement run for a single vector
  EXPECT_EQ(probe.instances, 1);
}

// ---- long stalls ----

// long:64:100 on both sides: cycles 100..163 have no handshake at all, 64 cycles. A timeout of
// 64 tolerates exactly that; 63 reports it, in cycle 163, naming what is in flight.
TEST_F(Cosim, LongStallsAreNotDeadlocksUpToTheTimeout) {
  CosimOptions o = Options("long:64:100", "long:64:100");
  o.timeout = 64;
  const CosimReport ok = Run({}, o);
  EXPECT_TRUE(ok.passed) << ok.failure;
  EXPECT_EQ(ok.outputs, kVectors);

  o.timeout = 63;
  const CosimReport r = Run({}, o);
  EXPECT_EQ(r.failure_kind, "deadlock");
  EXPECT_EQ(r.failure,
            "DEADLOCK: cycle 163: no handshake for 63 cycles (100 inputs accepted, 97 outputs "
            "taken)\n  pending: 3 vectors still owe outputs, oldest vector 97 (accepted at cycle "
            "97, 0 of 1 outputs seen)\n" +
                Context(o, std::nullopt));
}

// ---- regressions: framework bugs these tests found (fixed) ----

// cosim.h: the run "stops at the first ... duplicated ... output". A duplicate of the LAST
// output is never looked for: run_harness returns as soon as finished() says the scoreboard is
// drained, in the very cycle the last expected output is taken, so an extra output in the next
// cycle is never sampled and the run PASSES (harness.cpp, the `inputs_done && !presenting &&
// hooks.finished(cycle)` exit).
TEST_F(Cosim, BugDuplicateOfTheLastOutputIsCaught) {
  CosimOptions o = Options();
  const auto last = static_cast<std::int64_t>(kVectors - 1);
  const CosimReport r = Run(Inject(Fault::duplicate, last), o);
  EXPECT_FALSE(r.passed) << r.summary();
  EXPECT_EQ(r.failure_kind, "unexpected output");
}

// CosimReport::outputs is "outputs compared in the main run". cosim.cpp subtracts one whenever
// the run failed, but only a mismatch / unexpected output is counted by the harness and then
// rejected; a deadlock or protocol violation involves no extra output, so the count comes out
// one short, and wraps to 2^64 - 1 when no output had been taken yet.
TEST_F(Cosim, BugOutputsCountIsExactForDeadlockAndProtocolFailures) {
  const CosimReport deadlock = Run(Inject(Fault::never_ready_output, kK), Options());
  ASSERT_EQ(deadlock.failure_kind, "deadlock");
  EXPECT_EQ(deadlock.outputs, kK + 1);  // #0..#k were taken and matched

  const CosimReport silent = Run(Inject(Fault::never_ready_output, -1), Options());
  ASSERT_EQ(silent.failure_kind, "deadlock");
  EXPECT_EQ(silent.outputs, 0u);

  // #0 is first offered in cycle 3, a stall cycle of periodic:1110, and withdrawn in cycle 4.
  const CosimReport protocol =
      Run(Inject(Fault::withdraw_valid, -1), Options("none", "periodic:1110"));
  ASSERT_EQ(protocol.failure_kind, "protocol");
  EXPECT_NE(protocol.failure.find("HANDSHAKE VIOLATION: cycle 4: output withdrawn"),
            std::string::npos);
  EXPECT_EQ(protocol.outputs, 0u);
}

// harness.cpp: the automatic timeout (options.timeout == 0) is 100000 cycles, "long enough for
// the longest stall a pattern can make", but long:STALL accepts any STALL (and periodic any
// run of zeros). A correct DUT behind a finite sink stall of 100001 cycles is reported as a
// deadlock.
TEST_F(Cosim, BugAutomaticTimeoutCoversEveryStallPattern) {
  CosimOptions o = Options("none", "long:100001:50");
  o.timeout = 0;
  o.directed = false;
  o.random_vectors = 100;
  o.measure_vectors = 0;
  const CosimReport r = Run({}, o);
  EXPECT_TRUE(r.passed) << r.failure;
  EXPECT_EQ(r.outputs, 100u);
}

// cosim.h: every first-failure report names configuration and seed and gives the reproduce
// command. A failure in the stall-free measurement run (e.g. a bug that needs back-to-back
// transactions, which stalls in the main run hide) gets only the scoreboard text plus
// "(in the stall-free measurement run)": no config, no seed, no command (cosim.cpp, the
// `!m.kind.empty()` branch).
TEST_F(Cosim, BugMeasurementRunFailureIsReproducible) {
  CosimOptions o = Options();
  o.directed = false;
  o.random_vectors = 100;  // the main run never reaches transaction #500
  const CosimReport r = Run(Inject(Fault::corrupt_lsb, 500), o);
  ASSERT_EQ(r.failure_kind, "mismatch");
  // What is there: the measurement vectors start after the directed ones.
  EXPECT_EQ(
      r.failure.rfind(
          fmt::format("MISMATCH at cycle {}, vector {} (", 500 + kLatency, kDirected + 500), 0),
      0u)
      << r.failure;
  // What is missing.
  EXPECT_NE(r.failure.find("config default"), std::string::npos) << r.failure;
  EXPECT_NE(r.failure.find("seed 7"), std::string::npos) << r.failure;
  EXPECT_NE(r.failure.find("  reproduce: "), std::string::npos) << r.failure;
}

// Once the DUT stops accepting and every accepted vector has produced its output, nothing is
// pending. The report says "1 vectors still owe outputs, oldest vector 2500 (... 1 of 1 outputs
// seen)": Scoreboard::pending() (cosim.cpp) reads the queue without drop_finished(), and the
// vector completed by the last check() stays at its front because only accept() and drained()
// prune it, and drained() is only consulted once all inputs are in.
TEST_F(Cosim, BugDeadlockPendingListsOnlyVectorsThatOweOutputs) {
  const CosimReport r = Run(Inject(Fault::stall_forever, kK), Options());
  ASSERT_EQ(r.failure_kind, "deadlock");
  EXPECT_NE(r.failure.find("\n  pending: none\n"), std::string::npos) << r.failure;
  EXPECT_EQ(r.failure.find("1 of 1 outputs seen"), std::string::npos) << r.failure;
}

// cosim.h: the report names "configuration, seed, vector index and cycle". Handshake
// violations never name the vector whose output broke the rules (the scoreboard knows it: the
// oldest one in flight), and a deadlock with nothing in flight does not name the vector that
// waits for in_ready ("pending: none").
TEST_F(Cosim, BugProtocolAndDeadlockReportsNameTheVector) {
  Probe probe;
  const CosimReport protocol =
      Run(Inject(Fault::withdraw_valid, kK), Options("none", "periodic:1110"), &probe);
  ASSERT_EQ(protocol.failure_kind, "protocol");
  ASSERT_TRUE(probe.fault_ordinal);
  EXPECT_NE(protocol.failure.find(fmt::format("vector {}", *probe.fault_ordinal)),
            std::string::npos)
      << protocol.failure;

  const CosimReport deadlock = Run(Inject(Fault::stall_forever, kK), Options());
  ASSERT_EQ(deadlock.failure_kind, "deadlock");
  EXPECT_NE(deadlock.failure.find(fmt::format("vector {}", kK + 1)), std::string::npos)
      << deadlock.failure;
}

// ---- parallel co-simulation: --jobs changes nothing but the time ----

// A main run split into 9 shards (400 vectors each, the last 659), run by 1, 2 and 3 workers:
// the same verdict, counts, cycles, first failure and summary. With two faulty vectors in
// different shards (2500 in shard 6, 3600 in shard 8, which a third worker reaches and fails
// first) the report is always the lower one's.
TEST_F(Cosim, JobsDoNotChangeTheResult) {
  constexpr std::uint64_t kShard = 400;
  const auto same = [](const CosimReport& a, const CosimReport& b, unsigned jobs) {
    SCOPED_TRACE(jobs);
    EXPECT_EQ(a.passed, b.passed);
    EXPECT_EQ(a.failure_kind, b.failure_kind);
    EXPECT_EQ(a.failure, b.failure);
    EXPECT_EQ(a.vectors, b.vectors);
    EXPECT_EQ(a.outputs, b.outputs);
    EXPECT_EQ(a.mismatches, b.mismatches);
    EXPECT_EQ(a.cycles, b.cycles);
    EXPECT_EQ(a.latency_min, b.latency_min);
    EXPECT_EQ(a.latency_max, b.latency_max);
    EXPECT_EQ(a.throughput, b.throughput);
    EXPECT_EQ(a.summary(), b.summary());
  };
  CosimOptions o = Options("random:0.3", "random:0.5");
  o.timeout = 0;
  const CosimReport pass1 = Run({}, o, nullptr, kShard);
  EXPECT_TRUE(pass1.passed) << pass1.failure;
  EXPECT_EQ(pass1.vectors, kVectors);
  EXPECT_EQ(pass1.outputs, kVectors);
  // Split: each shard starts on a fresh DUT with its own stalls, so the cycle count differs
  // from the unsplit run's.
  EXPECT_NE(pass1.cycles, Run({}, o, nullptr, 0).cycles);

  FaultSpec two = Inject(Fault::corrupt_lsb, 0);
  two.trigger = Inputs(3600);
  two.trigger2 = Inputs(kK);
  const CosimReport fail1 = Run(two, o, nullptr, kShard);
  ASSERT_EQ(fail1.failure_kind, "mismatch");
  EXPECT_NE(fail1.failure.find(fmt::format(", vector {} (", kK)), std::string::npos)
      << fail1.failure;
  for (const unsigned jobs : {2U, 3U}) {
    o.jobs = jobs;
    same(pass1, Run({}, o, nullptr, kShard), jobs);
    same(fail1, Run(two, o, nullptr, kShard), jobs);
  }
}

}  // namespace
