// Randomized-backpressure tests of the stream primitives in rtl/common, each Verilated on its own
// (as common_cells tests each primitive): stream_skid, pipe_ctrl (tests/stream_tb/pipe_ctrl_tb.sv:
// its stages' data registers load on its enables), pipe_delay (tests/stream_tb/pipe_delay_tb.sv:
// the data travels only in the pipe_delay, under a pipe_ctrl) and fdiff_acc.
//
// The stream benches drive seeded random source-idle and sink-stall patterns (random, bursty,
// long stalls, none) and check against a reference queue in C++: every transaction accepted
// outside reset comes out exactly once, in order, unchanged; a stalled output stays valid with
// its data unchanged; nothing is valid during reset or in the cycle after it (a reset is also
// applied in the middle of each run); without stalls the primitive runs at one transaction per
// clock. fdiff_acc is checked every cycle against the two-accumulator recurrence under random
// load / step / idle patterns of the same kinds. A failure names the bench, seed, patterns and
// cycle; the seed and patterns reproduce it.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "Vfdiff_acc.h"
#include "Vpipe_ctrl_tb.h"
#include "Vpipe_ctrl_tb1.h"
#include "Vpipe_delay_tb.h"
#include "Vpipe_delay_tb1.h"
#include "Vstream_skid.h"
#include "verilated.h"

namespace {

constexpr int kWidth = 16;  // data bits of every stream bench (-GWidth in tests/CMakeLists.txt)

// On/off patterns for "source offers" and "sink ready", one bool per cycle.
enum class Pattern { none, random, bursty, long_stalls };
constexpr Pattern kPatterns[] = {Pattern::none, Pattern::random, Pattern::bursty,
                                 Pattern::long_stalls};

const char* name(Pattern p) {
  switch (p) {
    case Pattern::none:
      return "none";
    case Pattern::random:
      return "random";
    case Pattern::bursty:
      return "bursty";
    case Pattern::long_stalls:
      return "long";
  }
  return "?";
}

class Activity {
 public:
  Activity(Pattern p, std::uint64_t seed) : p_(p), rng_(seed) {}
  // true: active this cycle (the source offers / the sink is ready).
  bool next() {
    switch (p_) {
      case Pattern::none:
        return true;
      case Pattern::random:
        return coin(0.5);
      case Pattern::bursty:  // runs of 1..16 cycles, alternately on and off
        if (run_ == 0) {
          on_ = !on_;
          run_ = 1 + static_cast<int>(rng_() % 16);
        }
        --run_;
        return on_;
      case Pattern::long_stalls:  // mostly on, now and then stalled for 50..300 cycles
        if (run_ > 0) {
          --run_;
          return false;
        }
        if (coin(0.01)) run_ = 50 + static_cast<int>(rng_() % 251);
        return coin(0.9);
    }
    return true;
  }

 private:
  bool coin(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  Pattern p_;
  std::mt19937_64 rng_;
  int run_ = 0;
  bool on_ = false;
};

// Runs one stream bench (ports as stream_skid's) for `cycles` cycles; returns "" or the first
// failure. `depth` is the bench's latency in cycles (stages), for the full-throughput check.
template <typename Top>
std::string run_stream(const char* bench, int depth, std::uint64_t seed, Pattern source,
                       Pattern sink, int cycles) {
  VerilatedContext context;
  Top top(&context);
  std::mt19937_64 rng(seed);
  Activity offer(source, seed * 3 + 1);
  Activity take(sink, seed * 5 + 2);
  std::deque<std::uint32_t> expected;
  std::uint64_t accepted = 0, delivered = 0;
  bool src_valid = false;
  std::uint32_t src_data = 0;
  bool stalled = false;  // the output was valid and not taken in the previous cycle
  std::uint32_t stalled_data = 0;
  bool was_reset = true;
  const int mid_reset = cycles / 2;  // a reset in the middle of the run, for 3 cycles
  std::uint64_t outputs_free_run = 0;

  const auto where = [&](int cycle) {
    std::ostringstream s;
    s << bench << " seed " << seed << " source " << name(source) << " sink " << name(sink)
      << " cycle " << cycle << ": ";
    return s.str();
  };

  top.clk_i = 0;
  for (int cycle = 0; cycle < cycles; ++cycle) {
    const bool in_reset = cycle < 3 || (cycle >= mid_reset && cycle < mid_reset + 3);
    // Drive while the clock is low. During reset the inputs are garbage, valid included.
    top.rst_ni = in_reset ? 0 : 1;
    if (in_reset) {
      src_valid = false;
      top.in_valid_i = rng() & 1U;
      top.in_data_i = static_cast<std::uint32_t>(rng()) & 0xFFFFU;
      top.out_ready_i = rng() & 1U;
    } else {
      if (!src_valid && offer.next()) {
        src_valid = true;
        src_data = static_cast<std::uint32_t>(rng()) & 0xFFFFU;
      }
      top.in_valid_i = src_valid ? 1 : 0;
      // An idle source drives garbage data, which must not be taken.
      top.in_data_i = src_valid ? src_data : static_cast<std::uint32_t>(rng()) & 0xFFFFU;
      top.out_ready_i = take.next() ? 1 : 0;
    }
    top.eval();

    // Sample both handshakes and check the output.
    const bool out_valid = top.out_valid_o != 0;
    const std::uint32_t out_data = top.out_data_o;
    if (in_reset) {
      if (out_valid) return where(cycle) + "output valid during reset";
      expected.clear();  // whatever was in flight is gone
      stalled = false;
    } else {
      if (was_reset && out_valid) return where(cycle) + "output valid right after reset";
      if (stalled && !out_valid) return where(cycle) + "output dropped while stalled";
      if (stalled && out_data != stalled_data) {
        std::ostringstream s;
        s << where(cycle) << "data changed while stalled: 0x" << std::hex << stalled_data
          << " -> 0x" << out_data;
        return s.str();
      }
      if (out_valid && top.out_ready_i) {
        if (expected.empty()) {
          std::ostringstream s;
          s << where(cycle) << "unexpected output 0x" << std::hex << out_data
            << " (nothing accepted is outstanding)";
          return s.str();
        }
        if (out_data != expected.front()) {
          std::ostringstream s;
          s << where(cycle) << "output 0x" << std::hex << out_data << ", expected 0x"
            << expected.front() << std::dec << " (transaction " << delivered << ")";
          return s.str();
        }
        expected.pop_front();
        ++delivered;
        if (cycle >= mid_reset + 3) ++outputs_free_run;
      }
      stalled = out_valid && !top.out_ready_i;
      stalled_data = out_data;
      if (src_valid && top.in_ready_o) {
        expected.push_back(src_data);
        ++accepted;
        src_valid = false;
      }
    }
    was_reset = in_reset;

    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
  }
  // Drain: everything accepted must come out with the sink always ready. A transaction still
  // offered stays offered until taken (the stream rules, which stream_check asserts).
  for (int cycle = cycles; cycle < cycles + 4 * depth + 8; ++cycle) {
    top.in_valid_i = src_valid ? 1 : 0;
    top.in_data_i = src_data;
    top.out_ready_i = 1;
    top.eval();
    if (src_valid && top.in_ready_o) {
      expected.push_back(src_data);
      ++accepted;
      src_valid = false;
    }
    if (top.out_valid_o) {
      std::ostringstream s;
      s << where(cycle) << "while draining: output 0x" << std::hex << top.out_data_o;
      if (expected.empty()) return s.str() + " unexpected";
      if (top.out_data_o != expected.front()) {
        s << ", expected 0x" << expected.front();
        return s.str();
      }
      expected.pop_front();
      ++delivered;
    }
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
  }
  if (!expected.empty()) {
    std::ostringstream s;
    s << where(cycles) << expected.size() << " accepted transactions never came out";
    return s.str();
  }
  if (accepted < static_cast<std::uint64_t>(cycles) / 20) {
    return where(cycles) + "too few transactions accepted to mean anything";
  }
  // Full throughput: with neither source idles nor sink stalls, one transaction per clock after
  // the pipeline has filled (second half of the run, after the mid-run reset).
  if (source == Pattern::none && sink == Pattern::none) {
    const std::uint64_t want = static_cast<std::uint64_t>(cycles - (mid_reset + 3) - depth);
    if (outputs_free_run != want) {
      std::ostringstream s;
      s << where(cycles) << outputs_free_run << " outputs in a stall-free stretch that allows "
        << want << " (not one per clock)";
      return s.str();
    }
  }
  return "";
}

constexpr std::uint64_t kSeeds[] = {1, 2, 3, 4, 5};
constexpr int kCycles = 20000;

template <typename Top>
void every_pattern(const char* bench, int depth) {
  for (const std::uint64_t seed : kSeeds) {
    for (const Pattern source : kPatterns) {
      for (const Pattern sink : kPatterns) {
        const std::string err = run_stream<Top>(bench, depth, seed, source, sink, kCycles);
        ASSERT_EQ(err, "");
      }
    }
  }
}

TEST(StreamSkid, EveryTransactionOnceInOrderUnderBackpressure) {
  every_pattern<Vstream_skid>("stream_skid", 1);
}
TEST(PipeCtrl, FourStagesUnderBackpressure) {
  every_pattern<Vpipe_ctrl_tb>("pipe_ctrl Depth 4", 4);
}
TEST(PipeCtrl, OneStageUnderBackpressure) { every_pattern<Vpipe_ctrl_tb1>("pipe_ctrl Depth 1", 1); }
TEST(PipeDelay, ThreeStagesUnderBackpressure) {
  every_pattern<Vpipe_delay_tb>("pipe_delay Depth 3", 3);
}
TEST(PipeDelay, OneStageUnderBackpressure) {
  every_pattern<Vpipe_delay_tb1>("pipe_delay Depth 1", 1);
}

// fdiff_acc (-GWidth=12: the sums wrap often): random cycles of load, step (with the running d1
// or a reloaded one, and a d2 that changes now and then) or idle, the step/idle choice from the
// same patterns (an idle cycle is a stall). Reference: f <- f + d1, d1 <- d1 + d2 modulo 2^12.
std::string run_fdiff(std::uint64_t seed, Pattern steps, int cycles) {
  constexpr std::uint32_t kMask = (1U << 12) - 1;
  VerilatedContext context;
  Vfdiff_acc top(&context);
  std::mt19937_64 rng(seed);
  Activity active(steps, seed * 7 + 3);
  std::uint32_t f = 0, d1 = 0, d2 = static_cast<std::uint32_t>(rng()) & kMask;
  bool loaded = false;
  std::uint64_t step_count = 0;
  top.clk_i = 0;
  for (int cycle = 0; cycle < cycles; ++cycle) {
    const bool load = !loaded || rng() % 64 == 0;
    const bool step = active.next();
    const bool reload = rng() % 8 == 0;
    if (rng() % 16 == 0) d2 = static_cast<std::uint32_t>(rng()) & kMask;
    top.load_i = load ? 1 : 0;
    top.f_i = static_cast<std::uint32_t>(rng()) & kMask;
    top.d1_i = static_cast<std::uint32_t>(rng()) & kMask;
    top.step_i = step ? 1 : 0;
    const std::uint32_t d1_step = reload ? static_cast<std::uint32_t>(rng()) & kMask : d1;
    top.d1_step_i = loaded ? d1_step : static_cast<std::uint32_t>(rng()) & kMask;
    top.d2_step_i = d2;
    top.eval();
    if (loaded && (top.f_o != f || top.d1_o != d1)) {
      std::ostringstream s;
      s << "fdiff_acc seed " << seed << " steps " << name(steps) << " cycle " << cycle << ": f_o "
        << top.f_o << " d1_o " << top.d1_o << ", expected f " << f << " d1 " << d1 << " (after "
        << step_count << " steps)";
      return s.str();
    }
    // The reference's next state (load has priority over step).
    if (load) {
      f = top.f_i;
      d1 = top.d1_i;
      loaded = true;
    } else if (step) {
      f = (f + top.d1_step_i) & kMask;
      d1 = (top.d1_step_i + d2) & kMask;
      ++step_count;
    }
    top.clk_i = 1;
    top.eval();
    top.clk_i = 0;
    top.eval();
  }
  if (step_count < static_cast<std::uint64_t>(cycles) / 20) {
    return "fdiff_acc: too few steps to mean anything";
  }
  return "";
}

TEST(FdiffAcc, AccumulatesExactlyUnderStalls) {
  for (const std::uint64_t seed : kSeeds) {
    for (const Pattern steps : kPatterns) {
      const std::string err = run_fdiff(seed, steps, kCycles);
      ASSERT_EQ(err, "");
    }
  }
}

}  // namespace
