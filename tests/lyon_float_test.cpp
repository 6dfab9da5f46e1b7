// Tests for the double-precision Lyon TR #43 reference (ref/lyon_float.*).
//
// Expected values are derived by hand in the comments from the report (seed 002) and
// specfuns.m, never copied from the implementation's output. Tolerances: unless a test says
// otherwise, kTol = 1e-12. Every checked quantity is O(1) and comes from at most ~30 roundings
// of O(1) operands amplified by at most the exponent 4n = 16 of the Blinn row (or 2^k = 8 of
// f_3), i.e. below 30 * 16 * 2^-53 = 5e-14; 1e-12 leaves a factor 20 of margin and is still far
// below any modelling difference we want to detect.
#include "ref/lyon_float.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "base/vec3.h"

namespace {

using phongsim::Vec3;
using phongsim::lyon::index;
using phongsim::lyon::Spec;
namespace lyon = phongsim::lyon;

constexpr double kTol = 1e-12;
constexpr double kPi = std::numbers::pi;

double row(const std::array<double, lyon::kNumSpecs>& rows, Spec s) { return rows[index(s)]; }

// Unit vector in the x-z plane at angle theta from +z.
Vec3 at_angle(double theta) { return {std::sin(theta), 0, std::cos(theta)}; }

// Uniform on the unit sphere (z uniform in [-1, 1], azimuth uniform).
Vec3 random_unit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 2 * u(rng) - 1;
  const double phi = 2 * kPi * u(rng);
  const double r = std::sqrt(1 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// ---- shape functions ("Phong Specularity Reformulation") ----

TEST(LyonShape, EndPointsAndZeroBeyond) {
  for (int k = 0; k <= lyon::kMaxK; ++k) {
    const double big_k = std::ldexp(1.0, k);  // 2^k
    EXPECT_EQ(lyon::shape(0, k), 1.0) << "k=" << k;
    EXPECT_EQ(lyon::shape(big_k, k), 0.0) << "k=" << k;  // (1 - 1)^(2^k)
    EXPECT_EQ(lyon::shape(std::nextafter(big_k, 2 * big_k), k), 0.0) << "k=" << k;
    EXPECT_EQ(lyon::shape(big_k + 1, k), 0.0) << "k=" << k;
    EXPECT_EQ(lyon::shape(1e300, k), 0.0) << "k=" << k;
    EXPECT_EQ(lyon::shape(std::numeric_limits<double>::infinity(), k), 0.0) << "k=" << k;
    // Just inside: (1 - (1 - 2^-10))^(2^k) = 2^(-10 * 2^k), exact in binary.
    EXPECT_EQ(lyon::shape(big_k * (1 - 0x1p-10), k), std::ldexp(1.0, -10 * (1 << k))) << k;
  }
}

TEST(LyonShape, LyonsValues) {
  // All exact in binary: f_0(1/2) = 1/2, f_1(1) = (1/2)^2, f_2(2) = (1/2)^4, f_3(4) = (1/2)^8.
  EXPECT_EQ(lyon::shape(0.5, 0), 0.5);
  EXPECT_EQ(lyon::shape(1, 1), 0.25);
  EXPECT_EQ(lyon::shape(2, 2), 0.0625);
  EXPECT_EQ(lyon::shape(4, 3), 0.00390625);
}

TEST(LyonShape, MatchesTaylorQuadraticTerm) {
  // f_k(x) = (1 - x/K)^K = 1 - x + (K - 1)/(2K) x^2 - ..., so (1 - f_k(x))/x = 1 - c x with
  // 0 <= c < 1/2: within x/2 of 1 (Lyon: every f_k "still matches the Taylor series quadratic
  // term"). Rounding: 1 - f_k carries at most ~9 ulp(1) = 2e-15, divided by x.
  for (int k = 0; k <= lyon::kMaxK; ++k) {
    for (const double x : {1e-2, 1e-3, 1e-4, 1e-6}) {
      const double slope = (1 - lyon::shape(x, k)) / x;
      EXPECT_NEAR(slope, 1.0, x / 2 + 2e-15 / x) << "k=" << k << " x=" << x;
    }
  }
}

TEST(LyonShape, IncreasesWithKTowardTheGaussian) {
  // (1 - x/K)^K increases with K toward exp(-x) ("Gaussian and Exponential Relationships"),
  // the property the shape-error bounds below rest on.
  for (const double x : {0.01, 0.1, 0.5, 1.0}) {
    for (int k = 0; k < lyon::kMaxK; ++k) {
      EXPECT_LT(lyon::shape(x, k), lyon::shape(x, k + 1)) << "k=" << k << " x=" << x;
    }
    EXPECT_LT(lyon::shape(x, lyon::kMaxK), std::exp(-x)) << "x=" << x;
  }
}

TEST(LyonShape, RejectsOrdersOutside0To3) {
  EXPECT_THROW((void)lyon::shape(0, -1), phongsim::Error);
  EXPECT_THROW((void)lyon::shape(0, 4), phongsim::Error);
  EXPECT_THROW((void)lyon::max_shape_error(10, 4), phongsim::Error);
  EXPECT_THROW((void)lyon::max_shape_error(0, 2), phongsim::Error);
  EXPECT_THROW((void)lyon::rms_shape_error(-1, 2), phongsim::Error);
}

// ---- approximate normalization ("Approximate Normalization", Figure 4) ----

TEST(LyonNormalization, LyonsNumbers) {
  // y = 1 - 0.5 = 0.5: g1 = 1 + 0.25, g2 = 1 + (0.5 + 0.25)/2; exact in binary.
  EXPECT_EQ(lyon::g1(0.5), 1.25);
  EXPECT_EQ(lyon::g2(0.5), 1.375);
  EXPECT_EQ(lyon::g1(1), 1.0);
  EXPECT_EQ(lyon::g2(1), 1.0);
  // "errors of just under 12% and 3%" against 1/sqrt(0.5) = 1.414.
  const double exact = 1 / std::sqrt(0.5);
  EXPECT_GT((exact - 1.25) / exact, 0.11);
  EXPECT_LT((exact - 1.25) / exact, 0.12);
  EXPECT_GT((exact - 1.375) / exact, 0.02);
  EXPECT_LT((exact - 1.375) / exact, 0.03);
  EXPECT_EQ(lyon::normalized_length(0.7, 0), 0.7);
  EXPECT_THROW((void)lyon::normalized_length(1, 3), phongsim::Error);
  EXPECT_THROW((void)lyon::normalized_length(1, -1), phongsim::Error);
}

TEST(LyonNormalization, SecondOrderWithinHalfPercentDownTo0Point8) {
  // Lyon: g2 is "good to better than 0.5% for input lengths as low as 0.8" and "over-corrects
  // vectors of length near 0.9 to a final length of about 1.002". With u = len^2 the corrected
  // length is sqrt(u) (4 - 3u + u^2)/2; its derivative vanishes where 5u^2 - 9u + 4 = 0, i.e.
  // u = 1 (a double root of the error: flat at length 1) and u = 0.8. So the maximum on
  // [0.8, 1] is at len = 2/sqrt(5) = 0.894: 1.12 * 2/sqrt(5) = 1.0017585; the minimum is at the
  // end, 0.8 * (1 + (0.36 + 0.1296)/2) = 0.99584.
  double max_len = 0;
  double argmax = 0;
  for (int i = 0; i <= 20000; ++i) {
    const double len = 0.8 + 0.2 * i / 20000;
    const double out = lyon::normalized_length(len, 2);
    EXPECT_LT(std::abs(out - 1), 0.005) << "len=" << len;
    if (out > max_len) {
      max_len = out;
      argmax = len;
    }
  }
  EXPECT_GE(max_len, 1.001);
  EXPECT_LE(max_len, 1.003);
  // Grid spacing 1e-5 around a smooth maximum: value within f''/2 h^2 ~ 1e-10 of the peak.
  EXPECT_NEAR(max_len, 2.24 / std::sqrt(5.0), 1e-9);
  EXPECT_NEAR(argmax, 2 / std::sqrt(5.0), 1e-4);
  EXPECT_NEAR(lyon::normalized_length(0.8, 2), 0.99584, kTol);
  // First order "reasonable only over a more limited range": 0.8 * 1.18 = 0.944, 5.6% short.
  EXPECT_NEAR(lyon::normalized_length(0.8, 1), 0.944, kTol);
}

// ---- the twelve specfuns.m rows (Figure 9) ----

TEST(LyonSpecfuns, NamesFollowFigure9) {
  const auto names = lyon::specfun_names();
  ASSERT_EQ(names.size(), lyon::kNumSpecs);
  const std::array<std::string_view, lyon::kNumSpecs> expected = {
      "Phong (R.L)^n",
      "Lyon k=0",
      "Lyon k=1",
      "Lyon k=2",
      "Blinn D1 (H*.N)^4n",
      "D = H* - N, k=2",
      "D = H - proj, k=2",
      "D = Hg2 - proj, k=2",
      "D = Hg2 - proj, k=1",
      "D = Hg2 - N, k=2",
      "Torrance-Sparrow (Blinn D2)",
      "Trowbridge-Reitz (Blinn D3)",
  };
  for (std::size_t i = 0; i < lyon::kNumSpecs; ++i) {
    EXPECT_EQ(names[i], expected[i]) << "row " << i + 1;
  }
  EXPECT_EQ(index(Spec::phong), 0U);
  EXPECT_EQ(index(Spec::trowbridge_reitz), 11U);
}

TEST(LyonSpecfuns, EveryRowIsOneAtThePerfectMirror) {
  // N = L = V = z: R = 2(1)z - z = z, R.L = 1, D = L - R = 0; H = (z + z)/2 = z, |H| = 1 so
  // Hg2 = H* = H; every halfway D is 0; acos(1) = 0; 1/(1 + 0 n) = 1. All exact.
  const Vec3 z{0, 0, 1};
  for (const double n : {0.5, 1.0, 4.0, 16.0, 64.0, 256.0, 1000.0}) {
    const auto rows = lyon::specfuns(z, z, z, n);
    for (std::size_t i = 0; i < lyon::kNumSpecs; ++i) {
      EXPECT_EQ(rows[i], 1.0) << "row " << i + 1 << " n=" << n;
    }
  }
}

// L = V = z and N = (sin t, 0, cos t), t the angle between N and the light/view:
//   V.N = cos t, R = 2 cos t N - V, R.L = 2cos^2 t - 1 = cos 2t, |L - R|^2 = 2 - 2 cos 2t
//   = 4 sin^2 t, so rows 2-4 see x = (n/2) 4 sin^2 t = 2n sin^2 t.
//   H = (z + z)/2 = z (unit), so H* = Hg2 = H: row 5 = cos^(4n) t;
//   rows 6 and 10: |H - N|^2 = 2 - 2cos t = 4 sin^2(t/2), x = (4n/2) 4 sin^2(t/2) = 8n sin^2(t/2);
//   rows 7-9: |H - (H.N)N|^2 = 1 - cos^2 t = sin^2 t, x = (4n/2) sin^2 t = 2n sin^2 t, the same x
//   as rows 2-4 (so row 7 = row 8 = row 4 and row 9 = row 3 here);
//   row 11: alpha = t, exp(-2n t^2); row 12: 1/(1 + n sin^2 t)^2 when cos t > 0.
TEST(LyonSpecfuns, LightAtViewpointHandValues) {
  const Vec3 z{0, 0, 1};
  {
    // n = 4, t = 30 degrees: cos 2t = 1/2, sin^2 t = 1/4, x = 2; 8n sin^2(t/2) = 16(1 - cos t)
    // = 16 - 8 sqrt(3) = 2.1436 <= 4, f_2 = (1 - 4 + 2 sqrt(3))^4 = (2 sqrt(3) - 3)^4
    // = 873 - 504 sqrt(3) = 0.046393; 2n t^2 = 8 pi^2/36 = 2 pi^2/9.
    const auto r = lyon::specfuns(at_angle(kPi / 6), z, z, 4);
    const double row6 = std::pow(2 * std::sqrt(3.0) - 3, 4);
    EXPECT_NEAR(row(r, Spec::phong), 0.0625, kTol);             // (1/2)^4
    EXPECT_EQ(row(r, Spec::lyon_k0), 0.0);                      // x = 2 > 1
    EXPECT_NEAR(row(r, Spec::lyon_k1), 0.0, kTol);              // x = 2: f_1's zero
    EXPECT_NEAR(row(r, Spec::lyon_k2), 0.0625, kTol);           // (1 - 2/4)^4, equals Phong here
    EXPECT_NEAR(row(r, Spec::blinn_d1), 6561.0 / 65536, kTol);  // (sqrt(3)/2)^16 = (3/4)^8
    EXPECT_NEAR(row(r, Spec::halfway_unit_k2), row6, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_proj_k2), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_proj_k2), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_proj_k1), 0.0, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_k2), row6, kTol);
    EXPECT_NEAR(row(r, Spec::torrance_sparrow), std::exp(-2 * kPi * kPi / 9), kTol);
    EXPECT_NEAR(row(r, Spec::trowbridge_reitz), 0.25, kTol);  // 1/(1 + 4/4)^2
  }
  {
    // n = 1, t = 60 degrees: cos 2t = -1/2 so Phong is 0 (Lyon: "goes abruptly to zero for
    // n=1"); x = 2 * 3/4 = 1.5: f_0 = 0, f_1 = (1/4)^2, f_2 = (5/8)^4 = 0.152587890625;
    // row 5 = (1/2)^4; rows 6, 10: x = 8 sin^2(30 deg) = 2, f_2 = (1/2)^4; 2n t^2 = 2 pi^2/9;
    // row 12: 1/(1 + 3/4)^2 = 16/49.
    const auto r = lyon::specfuns(at_angle(kPi / 3), z, z, 1);
    EXPECT_EQ(row(r, Spec::phong), 0.0);
    EXPECT_EQ(row(r, Spec::lyon_k0), 0.0);
    EXPECT_NEAR(row(r, Spec::lyon_k1), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::lyon_k2), 0.152587890625, kTol);
    EXPECT_NEAR(row(r, Spec::blinn_d1), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_unit_k2), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_proj_k2), 0.152587890625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_proj_k2), 0.152587890625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_proj_k1), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_k2), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::torrance_sparrow), std::exp(-2 * kPi * kPi / 9), kTol);
    EXPECT_NEAR(row(r, Spec::trowbridge_reitz), 16.0 / 49, kTol);
  }
  {
    // n = 1, t = 120 degrees (N faces away from light and viewer). Rows 1-4, 7-9 depend on
    // cos^2 t and sin^2 t only, so they equal the t = 60 degree values (MATLAB quirk: no
    // backside test). H*.N = -1/2: row 5 = 0; rows 6, 10: x = 8 sin^2(60 deg) = 6 > 4, so 0;
    // row 11 has no dot > 0 test: alpha = 2pi/3, exp(-2 (2pi/3)^2) = exp(-8pi^2/9) = 1.5e-4;
    // row 12 takes its floor (1/(1 + n))^2 = 1/4.
    const auto r = lyon::specfuns(at_angle(2 * kPi / 3), z, z, 1);
    EXPECT_EQ(row(r, Spec::phong), 0.0);
    EXPECT_EQ(row(r, Spec::lyon_k0), 0.0);
    EXPECT_NEAR(row(r, Spec::lyon_k1), 0.0625, kTol);
    EXPECT_NEAR(row(r, Spec::lyon_k2), 0.152587890625, kTol);
    EXPECT_EQ(row(r, Spec::blinn_d1), 0.0);
    EXPECT_EQ(row(r, Spec::halfway_unit_k2), 0.0);
    EXPECT_NEAR(row(r, Spec::halfway_proj_k2), 0.152587890625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_proj_k2), 0.152587890625, kTol);
    EXPECT_NEAR(row(r, Spec::halfway_g2_proj_k1), 0.0625, kTol);
    EXPECT_EQ(row(r, Spec::halfway_g2_k2), 0.0);
    EXPECT_NEAR(row(r, Spec::torrance_sparrow), std::exp(-8 * kPi * kPi / 9), kTol);
    EXPECT_EQ(row(r, Spec::trowbridge_reitz), 0.25);
  }
}

TEST(LyonSpecfuns, ReflectRowsAreShapeOfChordAndRowsUseTheNamedFunctions) {
  // Rows 2-4 are f_k((n/2)|L - R|^2) with R = 2(V.N)N - V (recomputed here), row 1 is
  // (R.L)^n; and specfuns() is built from phong/lyon_reflect/blinn/lyon_halfway (bit-equal).
  std::mt19937_64 rng(43);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 nv = random_unit(rng);
    const Vec3 lv = random_unit(rng);
    const Vec3 vv = random_unit(rng);
    for (const double n : {1.0, 4.0, 16.0, 64.0, 256.0}) {
      const auto r = lyon::specfuns(nv, lv, vv, n);
      const Vec3 rv = 2 * phongsim::dot(vv, nv) * nv - vv;
      const Vec3 d = lv - rv;
      const double x = n / 2 * phongsim::dot(d, d);
      const double rl = phongsim::dot(rv, lv);
      // Different operation order than the model: a few ulps, times the exponent n for row 1.
      EXPECT_NEAR(row(r, Spec::phong), rl > 0 ? std::pow(rl, n) : 0.0, kTol);
      EXPECT_NEAR(row(r, Spec::lyon_k0), lyon::shape(x, 0), kTol);
      EXPECT_NEAR(row(r, Spec::lyon_k1), lyon::shape(x, 1), kTol);
      EXPECT_NEAR(row(r, Spec::lyon_k2), lyon::shape(x, 2), kTol);

      EXPECT_EQ(row(r, Spec::phong), lyon::phong(nv, lv, vv, n));
      EXPECT_EQ(row(r, Spec::lyon_k0), lyon::lyon_reflect(nv, lv, vv, n, 0));
      EXPECT_EQ(row(r, Spec::lyon_k1), lyon::lyon_reflect(nv, lv, vv, n, 1));
      EXPECT_EQ(row(r, Spec::lyon_k2), lyon::lyon_reflect(nv, lv, vv, n, 2));
      EXPECT_EQ(row(r, Spec::blinn_d1), lyon::blinn(nv, lv, vv, n));
      EXPECT_EQ(row(r, Spec::halfway_proj_k2), lyon::lyon_halfway(nv, lv, vv, n, 2, 0));
      EXPECT_EQ(row(r, Spec::halfway_g2_proj_k2), lyon::lyon_halfway(nv, lv, vv, n, 2, 2));
      EXPECT_EQ(row(r, Spec::halfway_g2_proj_k1), lyon::lyon_halfway(nv, lv, vv, n, 1, 2));
    }
  }
  EXPECT_THROW((void)lyon::lyon_halfway({0, 0, 1}, {0, 0, 1}, {0, 0, 1}, 1, 2, 3), phongsim::Error);
  EXPECT_THROW((void)lyon::lyon_reflect({0, 0, 1}, {0, 0, 1}, {0, 0, 1}, 1, 4), phongsim::Error);
}

TEST(LyonSpecfuns, ReflectAndProjectionRowsIgnoreTheSignOfN) {
  // MATLAB quirk documented in lyon_float.cpp: rows 1-4 and 7-9 see N only as (.N)N, and
  // (V.(-N))(-N) = (V.N)N bit for bit, so flipping N changes nothing; rows 5, 6, 10-12 differ.
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 nv = random_unit(rng);
    const Vec3 lv = random_unit(rng);
    const Vec3 vv = random_unit(rng);
    const auto a = lyon::specfuns(nv, lv, vv, 16);
    const auto b = lyon::specfuns(-nv, lv, vv, 16);
    for (const Spec s :
         {Spec::phong, Spec::lyon_k0, Spec::lyon_k1, Spec::lyon_k2, Spec::halfway_proj_k2,
          Spec::halfway_g2_proj_k2, Spec::halfway_g2_proj_k1}) {
      EXPECT_EQ(row(a, s), row(b, s)) << "row " << index(s) + 1;
    }
  }
}

TEST(LyonSpecfuns, SmallNZerosWhereLyonSaysTheyAre) {
  // "For n=1, f_1(x) doesn't go to zero until alpha = pi, and f_2(x) never goes to zero. For
  // n=4, f_1(x) goes to zero at alpha = pi/3, and f_2(x) goes to zero at alpha = pi/2."
  // N = V = z gives R = z; L at angle alpha from R: x = (n/2)(2 - 2cos alpha) = n(1 - cos a),
  // zero of f_k where x = 2^k: cos alpha = 1 - 2^k/n.
  const Vec3 z{0, 0, 1};
  struct Case {
    double n;
    int k;
    double alpha_zero;
  };
  for (const Case c : {Case{4, 1, kPi / 3}, Case{4, 2, kPi / 2}, Case{1, 1, kPi}}) {
    EXPECT_GT(lyon::lyon_reflect(z, at_angle(c.alpha_zero * (1 - 1e-6)), z, c.n, c.k), 0)
        << "n=" << c.n << " k=" << c.k;
    if (c.alpha_zero < kPi) {
      EXPECT_EQ(lyon::lyon_reflect(z, at_angle(c.alpha_zero * (1 + 1e-6)), z, c.n, c.k), 0)
          << "n=" << c.n << " k=" << c.k;
    }
  }
  // n = 1, k = 2 at alpha = pi: x = 2, f_2 = (1/2)^4 > 0.
  EXPECT_NEAR(lyon::lyon_reflect(z, at_angle(kPi), z, 1, 2), 0.0625, kTol);
}

TEST(LyonSpecfuns, Row10LosesTheGlancingHighlight) {
  // "Simulation Results": row 10 "loses the glancing hilite" because D = Hg2 - N never gets
  // short when H starts out short. Mirror configuration at glancing incidence:
  // N = z, L = (sin t, 0, cos t), V = (-sin t, 0, cos t). Then V.N = cos t and
  // R = 2 cos t z - V = L: rows 1-4 see D = 0 and give 1. H = (L + V)/2 = (0, 0, cos t), so
  // H* = z (rows 5, 6, 11, 12 give 1) and H is parallel to N: H - (H.N)N = 0 for H and Hg2
  // (rows 7-9 give 1). Row 10: Hg2 = g2(cos^2 t) cos t z with g2 = 1 + (y + y^2)/2,
  // y = sin^2 t, so |D| = 1 - g2 cos t and x = (4n/2)(1 - g2 cos t)^2.
  //   t = 60 deg: c = 1/2, y = 3/4, g2 = 1.65625, 1 - g2 c = 0.171875, x = 2n * 0.0295410...
  //     n = 16: x = 0.9453125, f_2 = (1 - x/4)^4 = 0.763671875^4 = 0.340.
  //   t = 70 deg: c = 0.34202, g2 = 1.83138, 1 - g2 c = 0.37364, x = 32 * 0.13960 = 4.47 > 4: 0.
  //   t = 80 deg: c = 0.17365, g2 = 1.95522, 1 - g2 c = 0.66048, x = 32 * 0.43623 = 13.96: 0.
  const Vec3 z{0, 0, 1};
  const double n = 16;
  for (const double degrees : {60.0, 70.0, 80.0, 85.0}) {
    const double t = degrees * kPi / 180;
    const Vec3 lv{std::sin(t), 0, std::cos(t)};
    const Vec3 vv{-std::sin(t), 0, std::cos(t)};
    const auto r = lyon::specfuns(z, lv, vv, n);
    for (std::size_t i = 0; i < lyon::kNumSpecs; ++i) {
      if (i != index(Spec::halfway_g2_k2)) {
        EXPECT_NEAR(r[i], 1.0, kTol) << "row " << i + 1 << " t=" << degrees;
      }
    }
    const double c = std::cos(t);
    const double y = 1 - c * c;
    const double g2 = 1 + (y + y * y) / 2;
    const double x = 2 * n * (1 - g2 * c) * (1 - g2 * c);
    const double expected = x > 4 ? 0.0 : std::pow(1 - x / 4, 4);
    EXPECT_NEAR(row(r, Spec::halfway_g2_k2), expected, kTol) << "t=" << degrees;
    if (degrees == 60) {  // the hand value; c = cos(pi/3) is 1/2 only to 1 ulp
      EXPECT_NEAR(expected, std::pow(0.763671875, 4), 1e-12);
      EXPECT_LT(expected, 0.35);
    }
    if (degrees >= 70) {
      EXPECT_EQ(row(r, Spec::halfway_g2_k2), 0.0) << "t=" << degrees;
    }
  }
}

TEST(LyonSpecfuns, OppositeLightAndViewStayFinite) {
  // L = -V exactly, so H = 0. N = z, L = x, V = -x: R = 2(0)z + x = L, rows 1-4 give 1.
  // Deviation from MATLAB (NaN there): H* = 0, so H*.N = 0. Row 5: 0. Row 6: D = -N,
  // x = (4n/2) * 1 = 8 > 4: 0. Rows 7-9: H = Hg2 = 0 so D = 0: 1 (Lyon: "a short H would tend
  // to produce a short D, for an increased reflection; this effect could be a feature or a
  // bug"). Row 10: D = -N: 0. Row 11: alpha = pi/2, exp(-(16/2) pi^2/4) = exp(-2 pi^2).
  // Row 12: (1/(1 + 4))^2 = 0.04.
  const auto r = lyon::specfuns({0, 0, 1}, {1, 0, 0}, {-1, 0, 0}, 4);
  const std::array<double, lyon::kNumSpecs> expected = {
      1, 1, 1, 1, 0, 0, 1, 1, 1, 0, std::exp(-2 * kPi * kPi), 0.04};
  for (std::size_t i = 0; i < lyon::kNumSpecs; ++i) {
    EXPECT_NEAR(r[i], expected[i], kTol) << "row " << i + 1;
  }
}

TEST(LyonSpecfuns, EveryRowFiniteAndInUnitIntervalOnRandomVectors) {
  std::mt19937_64 rng(1993);
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 nv = random_unit(rng);
    const Vec3 lv = random_unit(rng);
    const Vec3 vv = random_unit(rng);
    for (const double n : {1.0, 4.0, 16.0, 64.0, 256.0}) {
      const auto r = lyon::specfuns(nv, lv, vv, n);
      for (std::size_t i = 0; i < lyon::kNumSpecs; ++i) {
        EXPECT_TRUE(std::isfinite(r[i])) << "row " << i + 1 << " trial " << trial;
        EXPECT_GE(r[i], 0.0) << "row " << i + 1 << " trial " << trial;
        EXPECT_LE(r[i], 1.0) << "row " << i + 1 << " trial " << trial;
      }
    }
  }
}

TEST(LyonSpecfuns, TorranceSparrowSurvivesRoundingPastOne) {
  // N = H* computed in floating point: H*.N = |H*|^2 can round to 1 + 2^-52, where a bare acos
  // is NaN. Row 11 must stay finite and essentially 1 (alpha ~ 0).
  std::mt19937_64 rng(11);
  int past_one = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 lv = random_unit(rng);
    const Vec3 vv = random_unit(rng);
    const Vec3 nv = phongsim::normalized((lv + vv) * 0.5);
    past_one += phongsim::dot(nv, nv) > 1 ? 1 : 0;
    const double d2 = lyon::specfuns(nv, lv, vv, 64)[index(Spec::torrance_sparrow)];
    // alpha from a dot product 1 - O(eps) is at most ~sqrt(2 * 4 eps) = 3e-8 rad; 128 alpha^2
    // is then ~1e-13.
    EXPECT_NEAR(d2, 1.0, 1e-12) << "trial " << trial;
  }
  EXPECT_GT(past_one, 0);  // the clamp was exercised
}

// ---- shape-function accuracy ----
//
// In terms of x = n(1 - cos alpha) (the chord |D| = 2 sin(alpha/2) gives (n/2)|D|^2 exactly
// that), Phong is c(x) = (1 - x/n)^n for x <= n and the shape f_k(x) = (1 - x/K)^K for x <= K,
// K = 2^k. Since m -> (1 - x/m)^m increases toward exp(-x):
//  (a) n = K: c = f_k on [0, 2n], error 0.
//  (b) n >= K: 0 <= c - f_k <= exp(-x) - f_k, so max_shape_error(n, k) <= E_k, the supremum of
//      exp(-x) - f_k(x), and grows with n (c grows pointwise) and falls with k (f_k grows).
//  (c) 0 <= exp(-x) - (1 - x/n)^n <= x^2 exp(-x)/n <= (4/e^2)/n < 0.55/n for x <= n (classical),
//      and exp(-x) < exp(-n) beyond, so max_shape_error(n, k) >= E_k - 0.55/n.
// E_0 = 1/e: exp(-x) - (1 - x) rises (slope 1 - exp(-x)) up to x = 1, then exp(-x) falls. In the
// same way max_shape_error(n, 0) = c(1) = (1 - 1/n)^n exactly for n >= 1 (the k = 0 kink).
// For K >= 2 the gap's slope (1 - x/K)^(K-1) - exp(-x) has one root in (1, K) (its log ratio
// (K-1) ln(1 - x/K) + x rises to x = 1 and then falls to -infinity), found by bisection;
// E_k = max(gap there, exp(-K)).
double limit_error(int k) {
  const double big_k = std::ldexp(1.0, k);
  if (k == 0) {
    return std::exp(-1.0);
  }
  auto slope = [&](double x) { return std::pow(1 - x / big_k, big_k - 1) - std::exp(-x); };
  double lo = 1;
  double hi = big_k;
  for (int i = 0; i < 200; ++i) {
    const double mid = (lo + hi) / 2;
    if (slope(mid) > 0) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  const double gap = std::exp(-lo) - std::pow(1 - lo / big_k, big_k);
  return std::max(gap, std::exp(-big_k));
}

TEST(LyonShapeError, ZeroWhenNIsTwoToTheK) {
  // (a): Lyon's k = 0 at n = 1 "approximates it excellently"; likewise k = 2 at n = 4.
  // Rounding only: 1 - 2 sin^2(alpha/2) versus cos(alpha), to the power K <= 8.
  for (int k = 0; k <= lyon::kMaxK; ++k) {
    const double n = std::ldexp(1.0, k);
    EXPECT_LT(lyon::max_shape_error(n, k), 1e-14) << "k=" << k;
    EXPECT_LT(lyon::rms_shape_error(n, k), 1e-14) << "k=" << k;
  }
}

TEST(LyonShapeError, KZeroMaximumIsAtTheKink) {
  // max_shape_error(n, 0) = (1 - 1/n)^n for n >= 1 (derivation above); checks the kink handling
  // (a plain grid would be off by up to |slope| * spacing ~ 5e-4 at n = 1000).
  for (const double n : {1.0, 2.0, 3.0, 4.0, 16.0, 100.0, 1000.0, 8000.0}) {
    EXPECT_NEAR(lyon::max_shape_error(n, 0), std::pow(1 - 1 / n, n), 1e-12) << "n=" << n;
  }
}

TEST(LyonShapeError, SmoothMaximumAndRmsClosedForms) {
  // n = 3, k = 1 (n >= K, so the error is c - f_1 >= 0): d/dx [(1 - x/3)^3 - (1 - x/2)^2] =
  // -(1 - x/3)^2 + (1 - x/2) = 0 gives x^2/9 = x/6, x = 3/2 (alpha = pi/3, between grid points),
  // error (1/2)^3 - (1/4)^2 = 1/16. A grid alone would miss it by ~1.5e-11; refinement leaves
  // rounding only.
  EXPECT_NEAR(lyon::max_shape_error(3, 1), 0.0625, 1e-14);
  // n = 1, k = 1, c = cos(alpha): x = 1 - c and f_1 = ((1 + c)/2)^2, so the error is (1 - c)^2/4
  // up to pi/2 and (1 + c)^2/4 beyond, the mirror image. Integral of error^2 over [0, pi]
  // = (2/16) * integral over [0, pi/2] of (1 - cos)^4 = (1/8)(35 pi/16 - 20/3); RMS =
  // sqrt(that / pi) = 0.0904393. Trapezoid error for this smooth-but-for-one-kink integrand is
  // O(h^2) ~ 1e-10 relative to the integral.
  const double integral = (35 * kPi / 16 - 20.0 / 3) / 8;
  EXPECT_NEAR(lyon::rms_shape_error(1, 1), std::sqrt(integral / kPi), 1e-10);
}

TEST(LyonShapeError, LargeNApproachesTheGaussianLimitAndImprovesWithK) {
  // E_k = 0.3679, 0.1619, 0.0738, 0.0353 (k = 0..3): the k = 2 shape Lyon calls "visually
  // indistinguishable" is within 7.4% of the peak everywhere, k = 0 ("drops too abruptly")
  // misses by 37%. Bounds (b) and (c); 1e-9 is the stated accuracy of max_shape_error.
  const std::array<double, 4> expected_limits = {0.36788, 0.16190, 0.07380, 0.03530};
  for (int k = 0; k <= lyon::kMaxK; ++k) {
    EXPECT_NEAR(limit_error(k), expected_limits[k], 1e-5) << "k=" << k;  // the hand estimate
  }
  for (const double n : {100.0, 1000.0}) {
    for (int k = 0; k <= lyon::kMaxK; ++k) {
      const double e = lyon::max_shape_error(n, k);
      EXPECT_LE(e, limit_error(k) + 1e-9) << "n=" << n << " k=" << k;
      EXPECT_GE(e, limit_error(k) - 0.55 / n) << "n=" << n << " k=" << k;
      if (k > 0) {
        EXPECT_LT(e, lyon::max_shape_error(n, k - 1)) << "n=" << n << " k=" << k;
      }
    }
  }
  EXPECT_GT(lyon::max_shape_error(1000, 0), 4 * lyon::max_shape_error(1000, 2));
}

TEST(LyonShapeError, GrowsWithNOnceNReachesTwoToTheK) {
  // (b): for n >= 2^k the error grows with n toward E_k.
  const std::vector<double> ns = {8, 16, 64, 100, 256, 1000};
  for (int k = 0; k <= lyon::kMaxK; ++k) {
    for (std::size_t i = 1; i < ns.size(); ++i) {
      EXPECT_GE(lyon::max_shape_error(ns[i], k), lyon::max_shape_error(ns[i - 1], k))
          << "k=" << k << " n=" << ns[i];
    }
  }
}

TEST(LyonShapeError, FiniteAndBounded) {
  // Both f_k and c lie in [0, 1], so does |f_k - c|; the RMS cannot exceed the maximum.
  for (const double n : {0.5, 1.0, 4.0, 16.0, 64.0, 100.0, 256.0, 1000.0}) {
    for (int k = 0; k <= lyon::kMaxK; ++k) {
      const double mx = lyon::max_shape_error(n, k);
      const double rms = lyon::rms_shape_error(n, k);
      EXPECT_TRUE(std::isfinite(mx) && std::isfinite(rms)) << "n=" << n << " k=" << k;
      EXPECT_GE(mx, 0.0);
      EXPECT_LE(mx, 1.0);
      EXPECT_GE(rms, 0.0);
      EXPECT_LE(rms, mx) << "n=" << n << " k=" << k;
    }
  }
  // Hand values at n = 1 (Phong = 1 - x up to x = 1, then 0): k = 1 peaks at x = 1 with
  // (1/2)^2, k = 2 with (3/4)^4 = 0.31640625 (both past 90 degrees stay below that).
  EXPECT_NEAR(lyon::max_shape_error(1, 1), 0.25, 1e-12);
  EXPECT_NEAR(lyon::max_shape_error(1, 2), 0.31640625, 1e-12);
}

}  // namespace
