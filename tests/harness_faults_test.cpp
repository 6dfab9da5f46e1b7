// Does the co-simulation framework (sim/harness.*, sim/cosim.*) really catch broken RTL? With
// the fake DUT of tests/fake_dut.h (a correct lirp pipeline with one injectable fault): the fake
// itself is a well-behaved pipeline, the fault-free DUT passes under every stall pattern, and
// every fault fails with the right kind and a report that pins it down. Reproducibility, long
// stalls, --jobs and regressions: harness_runs_test.cpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tests/fake_dut.h"

namespace {

using namespace phongsim::testing;  // tests/fake_dut.h

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
              "outputs compared, 0 mismatches, 3862 cycles; source none, sink none; longest since "
              "reset 3859 vectors, 3859 outputs (1 DUT); drain 1024 cycles; throughput "
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
  // Vectors accepted through the failing cycle; outputs compared up to the failing one (the DUT
  // vouches for those before it); no measurement.
  EXPECT_EQ(r.vectors, kK + kLatency + 1);
  EXPECT_EQ(r.outputs, kK + 1);
  EXPECT_EQ(r.cycles, kK + kLatency + 1);
  EXPECT_EQ(r.mismatches, 1u);
  EXPECT_EQ(r.throughput, 0.0);
  EXPECT_EQ(
      r.summary(),
      "FAIL lirp/default: 2504 of 3859 vectors accepted (1859 directed + 2000 random, seed "
      "7), 2501 "
      "outputs compared, 1 mismatch, 2504 cycles; source none, sink none; longest since reset "
      "2504 vectors, 2500 outputs (1 DUT); first failure: "
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
// An output 300 idle cycles after the last expected one (a wrapped counter firing late) falls in
// the drain window and fails the run, under every stall pattern the cosim tests use.
TEST_F(Cosim, LateExtraOutputIsAnUnexpectedOutput) {
  for (const auto& [source, sink] :
       std::vector<std::pair<std::string, std::string>>{{"none", "none"},
                                                        {"periodic:1110", "random:0.5"},
                                                        {"random:0.3", "periodic:0001"},
                                                        {"long:64:200", "long:100:300"}}) {
    SCOPED_TRACE(source + " " + sink);
    CosimOptions o = Options(source, sink);
    o.timeout = 0;
    Probe probe;
    const CosimReport r = Run(Inject(Fault::late_extra, 300), o, &probe);
    EXPECT_EQ(r.failure_kind, "unexpected output") << r.summary();
    ASSERT_TRUE(probe.fault_cycle);
    EXPECT_NE(r.failure.find(fmt::format("UNEXPECTED OUTPUT at cycle {}", *probe.fault_cycle)),
              std::string::npos)
        << r.failure;
  }
}

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

}  // namespace
