// The LIRP unit: the model (model/lirp.h) against an independent exact-rational reference,
// exhaustively on narrow formats; its float reference (ref/lirp_float.h); the float-error bound
// docs/lirp.md states; and its registry entry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "model/config.h"
#include "model/lirp.h"
#include "ref/lirp_float.h"
#include "sim/pipelines/lirp.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

Config Parse(const std::string& p, const std::string& a, const std::string& out,
             const std::string& round, const std::string& overflow) {
  return Config::parse("pipeline = \"lirp\"\n[format]\np = \"" + p + "\"\na = \"" + a +
                           "\"\nout = \"" + out + "\"\n[mode]\nout_round = \"" + round +
                           "\"\nout_overflow = \"" + overflow + "\"\n",
                       "test.toml");
}

// floor(n / 2^s) for any sign.
std::int64_t FloorShift(std::int64_t n, int s) { return n >> s; }

// The exact value p0 + a (p1 - p0) as an integer numerator over 2^(pf + af), then rounded to
// `of` fraction bits and overflowed into `out`, written from the definitions in
// docs/fixed-point.md (not from model/fixed.cpp).
std::int64_t Reference(std::int64_t p0, std::int64_t p1, std::int64_t a, int pf, int af,
                       fx::Format out, const std::string& round, const std::string& overflow) {
  const std::int64_t exact = (p0 << af) + a * (p1 - p0);  // over 2^(pf + af)
  const int drop = pf + af - out.frac_bits;
  std::int64_t v = 0;
  if (drop <= 0) {
    v = exact << -drop;
  } else if (round == "truncate") {
    v = FloorShift(exact, drop);
  } else {
    const std::int64_t lo = FloorShift(exact, drop);
    const std::int64_t rem = exact - (lo << drop);  // 0 <= rem < 2^drop
    const std::int64_t half = std::int64_t{1} << (drop - 1);
    if (rem > half || (rem == half && (round == "half_up" || (lo & 1) != 0))) {
      v = lo + 1;
    } else {
      v = lo;
    }
  }
  if (overflow == "saturate") return std::clamp(v, out.min_raw(), out.max_raw());
  const int w = out.width();
  std::int64_t m = v & ((std::int64_t{1} << w) - 1);
  if (out.is_signed && m >= (std::int64_t{1} << (w - 1))) m -= std::int64_t{1} << w;
  return m;
}

struct Case {
  std::string p, a, out, round, overflow;
};

class LirpExhaustive : public ::testing::TestWithParam<Case> {};

// Every (p0, p1, a) of small formats, one component: 2^(5+5+4) = 16384 cases per format set.
TEST_P(LirpExhaustive, MatchesExactRationalReference) {
  const Case& c = GetParam();
  const Config cfg = Parse(c.p, c.a, c.out, c.round, c.overflow);
  const LirpFormats f = LirpFormats::from_config(cfg);
  const LirpModel model(f);
  int checked = 0;
  for (std::int64_t p0 = f.p.min_raw(); p0 <= f.p.max_raw(); ++p0) {
    for (std::int64_t p1 = f.p.min_raw(); p1 <= f.p.max_raw(); ++p1) {
      for (std::int64_t a = f.a.min_raw(); a <= f.a.max_raw(); ++a) {
        const std::int64_t want =
            Reference(p0, p1, a, f.p.frac_bits, f.a.frac_bits, f.out, c.round, c.overflow);
        ASSERT_EQ(model.component(p0, p1, a).p.raw, want)
            << "p0 " << p0 << " p1 " << p1 << " a " << a << " (" << c.p << ", " << c.a << " -> "
            << c.out << ", " << c.round << ", " << c.overflow << ")";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

INSTANTIATE_TEST_SUITE_P(Formats, LirpExhaustive,
                         ::testing::Values(Case{"S1.3", "1.3", "S1.3", "half_even", "saturate"},
                                           Case{"S1.3", "1.3", "S1.2", "half_up", "saturate"},
                                           Case{"S1.3", "1.3", "S0.3", "truncate", "wrap"},
                                           Case{"S1.3", "0.4", "S1.5", "half_even", "wrap"},
                                           Case{"S1.3", "1.3", "S0.2", "half_even", "saturate"}));

TEST(LirpFloat, InterpolatesAndExtrapolates) {
  EXPECT_EQ(lirp::lirp(0.5, -0.25, 0.0), 0.5);
  EXPECT_EQ(lirp::lirp(0.5, -0.25, 1.0), -0.25);
  EXPECT_EQ(lirp::lirp(0.5, -0.25, 0.5), 0.125);
  EXPECT_EQ(lirp::lirp(Vec3{1, 0, 0}, Vec3{0, 1, 0}, 0.25), (Vec3{0.75, 0.25, 0}));
}

// docs/lirp.md: against the float reference on exact reals, the error is at most half an output
// LSB (rounding) + half a p LSB (p0, p1 quantized, weights 1 - a and a) + one a LSB (a quantized,
// weight |p1 - p0| <= 2), plus their product; for the default S1.10/1.10/S1.10 that is 2 LSBs
// and a hair.
TEST(LirpFloat, DefaultErrorWithinDocumentedBound) {
  const Config cfg = Config::load(std::string(PHONGSIM_SOURCE_DIR) + "/configs/lirp/default.toml");
  const ModelError e = lirp_float_error(cfg, 200000, 1);
  EXPECT_EQ(e.samples, 600000U);
  EXPECT_LE(e.max_lsb, 0.5 + 0.5 + 1.0 + 1.0 / 1024);
  EXPECT_GT(e.max_lsb, 1.0);  // the input quantization really shows up
  EXPECT_LT(e.mean_lsb, e.max_lsb);
}

TEST(LirpRegistry, LatencyIsThreeStages) {
  const Config cfg = Config::load(std::string(PHONGSIM_SOURCE_DIR) + "/configs/lirp/default.toml");
  EXPECT_EQ(find_pipeline("lirp").latency(cfg), 3);  // diff, prod, out
}

}  // namespace
}  // namespace phongsim
