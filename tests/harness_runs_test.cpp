// The co-simulation framework (sim/harness.*, sim/cosim.*) with the fake DUT of
// tests/fake_dut.h, beyond catching each fault (harness_faults_test.cpp): the same seed gives the
// same failure, --vector-index reproduces a vector alone, long stalls are not deadlocks up to the
// timeout, --jobs changes nothing but the time, and regressions for framework bugs these tests
// found.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <regex>
#include <string>

#include "base/error.h"
#include "tests/fake_dut.h"

namespace {

using namespace phongsim::testing;  // tests/fake_dut.h

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
  EXPECT_EQ(r.outputs, 1u);  // its output, compared and wrong
  EXPECT_EQ(r.mismatches, 1u);
  EXPECT_EQ(
      r.summary().rfind(
          fmt::format("FAIL lirp/default: vector {} alone (random, seed {}), ", kK, o.seed), 0),
      0u)
      << r.summary();
  EXPECT_NE(r.summary().find(", 1 output compared, 1 mismatch, "), std::string::npos)
      << r.summary();
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

// The scoreboard compares outputs in runs across vectors, a run ending with each batch the
// harness hands over: the run's last output, and the very last output of all, are compared too.
TEST_F(Cosim, AWrongLastOutputIsCaught) {
  const auto last = static_cast<std::int64_t>(kVectors - 1);
  const CosimReport r = Run(Inject(Fault::corrupt_lsb, last), Options());
  EXPECT_FALSE(r.passed) << r.summary();
  EXPECT_EQ(r.failure_kind, "mismatch");
  EXPECT_EQ(r.failure_detail->vector, kVectors - 1);
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

// ---- DUTs and resets: one DUT sees the whole stream unless asked otherwise ----

// A DUT that goes wrong at its 3001st transaction since reset (a counter that wraps): the default
// run (one worker) gives the whole stream to one DUT and fails there; --jobs 2 gives each of two
// DUTs a contiguous half (1930 and 1929 vectors), and --reset-every 1000 a fresh DUT every 1000
// vectors: both pass, and say so (the longest sequence since reset is part of the verdict).
TEST_F(Cosim, OneDutSeesTheWholeStreamByDefault) {
  const FaultSpec wrap = Inject(Fault::corrupt_lsb, 3000);
  const CosimReport one = Run(wrap, Options());
  ASSERT_EQ(one.failure_kind, "mismatch");
  EXPECT_NE(one.failure.find(", vector 3000 ("), std::string::npos) << one.failure;
  EXPECT_EQ(one.duts, 1U);

  // A pass that states `duts` DUTs, the longest of which took `n` vectors and outputs.
  const auto passes_stating = [](const CosimReport& r, std::uint64_t duts, std::uint64_t n) {
    ASSERT_TRUE(r.passed) << r.failure;
    EXPECT_EQ(r.duts, duts);
    EXPECT_EQ(r.longest_vectors, n);
    EXPECT_EQ(r.longest_outputs, n);
    EXPECT_NE(r.summary().find(fmt::format("longest since reset {} vectors, {} outputs ({} DUT{})",
                                           n, n, duts, duts == 1 ? "" : "s")),
              std::string::npos)
        << r.summary();
  };
  passes_stating(Run({}, Options()), 1, kVectors);
  CosimOptions two = Options();
  two.jobs = 2;
  passes_stating(Run(wrap, two), 2, kVectors - kVectors / 2);

  CosimOptions every = Options();
  every.reset_every = 1000;
  const CosimReport resets = Run(wrap, every);
  ASSERT_TRUE(resets.passed) << resets.failure;
  EXPECT_EQ(resets.duts, 4U);
  EXPECT_EQ(resets.longest_vectors, 1000U);
}

// With --reset-every the runs are fixed by the stream, so 1, 2 and 3 workers give the same
// verdict, counts, cycles, first failure and summary. With two faulty vectors in different runs
// (2500 in run 6, 3600 in run 8, which a third worker reaches and fails first) the report is
// always the lower one's, and its reproduce line carries --reset-every.
TEST_F(Cosim, WithResetEveryJobsDoNotChangeTheResult) {
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
  o.reset_every = 400;
  const CosimReport pass1 = Run({}, o);
  EXPECT_TRUE(pass1.passed) << pass1.failure;
  EXPECT_EQ(pass1.vectors, kVectors);
  EXPECT_EQ(pass1.outputs, kVectors);
  EXPECT_EQ(pass1.duts, 10U);
  EXPECT_EQ(pass1.longest_vectors, 400U);
  // Split: each run starts on a fresh DUT with its own stalls, so the cycle count differs from
  // the unsplit run's.
  CosimOptions whole = o;
  whole.reset_every = 0;
  EXPECT_NE(pass1.cycles, Run({}, whole).cycles);

  FaultSpec two = Inject(Fault::corrupt_lsb, 0);
  two.trigger = Inputs(3600);
  two.trigger2 = Inputs(kK);
  const CosimReport fail1 = Run(two, o);
  ASSERT_EQ(fail1.failure_kind, "mismatch");
  EXPECT_NE(fail1.failure.find(fmt::format(", vector {} (", kK)), std::string::npos)
      << fail1.failure;
  EXPECT_NE(fail1.failure.find(" --reset-every 400"), std::string::npos) << fail1.failure;
  for (const unsigned jobs : {2U, 3U}) {
    o.jobs = jobs;
    same(pass1, Run({}, o), jobs);
    same(fail1, Run(two, o), jobs);
  }
}

// A run that checks nothing cannot pass: no vectors is an error, not a PASS.
TEST_F(Cosim, NoVectorsIsRefused) {
  CosimOptions o = Options();
  o.directed = false;
  o.random_vectors = 0;
  EXPECT_THROW((void)Run({}, o), phongsim::Error);
}

// After the last expected output the sink stays ready with no input for the drain window (at
// least kTailCycles plus the patterns' longest stalls); an output in it fails the run.
TEST_F(Cosim, DrainWindowIsStated) {
  const CosimReport r = Run({}, Options("none", "long:100:300"));
  ASSERT_TRUE(r.passed) << r.failure;
  EXPECT_GE(r.drain_cycles, phongsim::kTailCycles + 100);
  EXPECT_NE(r.summary().find(fmt::format("; drain {} cycles", r.drain_cycles)), std::string::npos)
      << r.summary();
}

// ---- the scoreboard's rule ----

// A combinational DUT: each vector's output, correct, in the very cycle the vector is accepted.
// An output is due to a vector accepted before its cycle (docs/cosim.md), so this one is
// unexpected, however right its value: the scoreboard must not match outputs to vectors by
// order and value alone.
class PassthroughDut final : public phongsim::RtlDut {
 public:
  explicit PassthroughDut(const LirpFormats& formats) : model_(formats) {}
  void reset() override { cycle_ = 0; }
  void set_input(std::span<const std::int64_t> fields) override {
    in_.assign(fields.begin(), fields.end());
  }
  void set_in_valid(bool valid) override { in_valid_ = valid; }
  void set_out_ready(bool ready) override { out_ready_ = ready; }
  void settle() override {
    if (in_valid_) (void)model_.eval(in_, out_);
  }
  [[nodiscard]] bool in_ready() const override { return out_ready_; }
  [[nodiscard]] bool out_valid() const override { return in_valid_; }
  void output(std::span<std::int64_t> fields) const override {
    std::copy(out_.begin(), out_.end(), fields.begin());
  }
  void clock() override {
    out_.clear();
    ++cycle_;
  }
  [[nodiscard]] std::uint64_t cycle() const override { return cycle_; }
  [[nodiscard]] bool assertion_failed() const override { return false; }
  void open_trace(const std::string&) override {}
  void close_trace() override {}

 private:
  LirpModel model_;
  std::vector<std::int64_t> in_, out_;
  bool in_valid_ = false, out_ready_ = false;
  std::uint64_t cycle_ = 0;
};

TEST_F(Cosim, AnOutputInTheCycleItsVectorIsAcceptedIsUnexpected) {
  const phongsim::CosimSubject subject{
      .pipeline = "lirp",
      .cfg = cfg_,
      .model = *model_,
      .stimulus = stimulus_,
      .independent_vectors = true,
      .make_dut = [&] { return DutPtr(new PassthroughDut(formats_), DutDeleter{}); },
      .rtl_label = {},
      .rtl_options = {},
      .contract = {}};
  const CosimReport r = phongsim::cosim(subject, Options());
  EXPECT_FALSE(r.passed);
  EXPECT_EQ(r.failure_kind, "unexpected output");
  EXPECT_EQ(r.failure.find("UNEXPECTED OUTPUT at cycle 0:"), 0U) << r.failure;
}

// ---- input contract ----

// Every accepted vector is counted once against the input contract, inside or outside, split or
// not, however many workers; the counts are the contract's own on the same vectors; a failing
// run counts the vectors the RTL accepted.
TEST_F(Cosim, ContractCountsEveryAcceptedVector) {
  CosimOptions o = Options("random:0.3", "random:0.5");
  o.timeout = 0;
  const CosimReport whole = Run({}, o, nullptr, true);
  ASSERT_TRUE(whole.passed) << whole.failure;
  ASSERT_TRUE(whole.contract.has_value());
  EXPECT_EQ(whole.contract->in + whole.contract->out(), whole.vectors);
  EXPECT_GT(whole.contract->in, 0U);
  EXPECT_GT(whole.contract->out(), 0U);  // the corners include a = 1 + 1 LSB, p = -2
  phongsim::InputContract c = lirp_.contract(*model_, cfg_);
  phongsim::ContractCounts direct;
  std::vector<std::int64_t> v(model_->inputs().size());
  for (std::uint64_t i = 0; i < whole.vectors; ++i) {
    stimulus_.vector(kSeed, i, v);
    c.count(v, v.size(), direct);
  }
  EXPECT_EQ(whole.contract->in, direct.in);
  EXPECT_EQ(whole.contract->by_clause, direct.by_clause);
  EXPECT_NE(whole.summary().find(
                fmt::format("{} in contract, {} out of contract (", direct.in, direct.out())),
            std::string::npos)
      << whole.summary();
  o.jobs = 2;
  o.reset_every = 400;
  const CosimReport split = Run({}, o, nullptr, true);
  EXPECT_EQ(split.contract->in, direct.in);
  EXPECT_EQ(split.contract->by_clause, direct.by_clause);
  // Without a contract nothing is counted and the summary says nothing about it.
  const CosimReport none = Run({}, Options(), nullptr, false);
  EXPECT_FALSE(none.contract.has_value());
  EXPECT_EQ(none.summary().find("contract"), std::string::npos);

  const CosimReport failed = Run(Inject(Fault::corrupt_lsb, kK), Options(), nullptr, true);
  ASSERT_FALSE(failed.passed);
  EXPECT_EQ(failed.contract->in + failed.contract->out(), failed.vectors);
  EXPECT_LT(failed.vectors, whole.vectors);
}

}  // namespace
