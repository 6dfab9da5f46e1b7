// Tests for the double-precision Kuijk–Blake reference (ref/kb_float.*), seed 001 with the
// errata of SEED-NOTES.md: angular interpolation along a scanline (section 1.2). Equation numbers
// are the report's: (1) exact angle along a scanline, (2) decomposition method, (4) one-vector
// method. The quadratic f and its parameters: kb_float_quad_test.cpp.
//
// Expected values are derived in the comments or computed here by independent means (eq. (1)'s
// trigonometric form); measured bounds say where they were measured and how much margin they
// keep.
#include "ref/kb_float.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

#include "base/error.h"
#include "base/vec3.h"

namespace {

using phongsim::Vec3;
namespace kb = phongsim::kb;

constexpr double kPi = std::numbers::pi;

// ---- angular interpolation (section 1.2) ----

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return phongsim::normalized(Vec3{g(rng), g(rng), g(rng)});
}

// The unit vector at angle w from unit p in the direction of (unit) q's component normal to p.
Vec3 towards(Vec3 p, Vec3 q, double w) {
  const Vec3 tangent = phongsim::normalized(cross(cross(p, q), p));
  return p * std::cos(w) + tangent * std::sin(w);
}

struct Couple {
  Vec3 n1, n2, l1, l2;
};

// The paper's test scene (Photographs 1-6): a unit sphere, a point light four radii from its
// centre. A span joins two surface points omega apart (N_i = P_i), both facing the viewer on +z
// (N·O >= 0, so the one-vector rotations stay away from their singular N = -O);
// L_i = normalize(light - P_i).
Couple sphere_span(std::mt19937_64& rng, double omega) {
  for (;;) {
    const Vec3 p1 = random_unit(rng);
    const Vec3 p2 = towards(p1, random_unit(rng), omega);
    if (p1.z < 0 || p2.z < 0) continue;
    const Vec3 light = random_unit(rng) * 4.0;
    return {p1, p2, phongsim::normalized(light - p1), phongsim::normalized(light - p2)};
  }
}

TEST(KbAngular, SlerpRotatesAtAConstantRate) {
  std::mt19937_64 rng(7);
  for (int k = 0; k < 200; ++k) {
    const Vec3 u = random_unit(rng);
    const Vec3 v = random_unit(rng) * 3.0;  // length does not matter
    const double w = kb::angle(u, v);
    for (const double t : {0.0, 0.25, 0.5, 0.9, 1.0}) {
      const Vec3 s = kb::slerp(u, v, t);
      EXPECT_NEAR(phongsim::length(s), 1.0, 1e-15);
      EXPECT_NEAR(kb::angle(u, s), t * w, 1e-14);
      EXPECT_NEAR(kb::angle(s, v), (1 - t) * w, 1e-14);
      EXPECT_NEAR(phongsim::dot(s, cross(u, v)), 0.0, 1e-14);  // stays on the great circle
    }
  }
  EXPECT_EQ(kb::slerp({0, 0, 2}, {0, 0, 5}, 0.5), (Vec3{0, 0, 1}));
  EXPECT_NEAR(kb::angle({1, 0, 0}, {1, 1e-9, 0}), 1e-9, 1e-24);  // small angles stay accurate
  EXPECT_THROW((void)kb::slerp({0, 0, 1}, {0, 0, -1}, 0.5), phongsim::Error);
  EXPECT_THROW((void)kb::slerp({0, 0, 0}, {0, 0, 1}, 0.5), phongsim::Error);
  EXPECT_THROW((void)kb::cos_exact({1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                   {std::numeric_limits<double>::quiet_NaN(), 0, 0}, 0.5),
               phongsim::Error);
}

TEST(KbAngular, CosExactMatchesEq1) {
  // Eq. (1): S = the intersection of the two great circles, γ the angle between them, n and l
  // the angles from S to N1 and L1. With the poles K_N = N1 × N2, K_L = L1 × L2 (normalized,
  // oriented by the direction of travel), S = K_N × K_L normalized, n and l are signed angles
  // about K_N and K_L, and cos γ = K_N·K_L: then N = S cos φ + (K_N × S) sin φ, likewise L, and
  // N·L = cos φ cos ψ + sin φ sin ψ (K_N × S)·(K_L × S) = cos φ cos ψ + sin φ sin ψ cos γ.
  std::mt19937_64 rng(11);
  for (int k = 0; k < 500; ++k) {
    const Couple c{random_unit(rng), random_unit(rng), random_unit(rng), random_unit(rng)};
    const Vec3 kn = phongsim::normalized(cross(c.n1, c.n2));
    const Vec3 kl = phongsim::normalized(cross(c.l1, c.l2));
    const Vec3 s = phongsim::normalized(cross(kn, kl));
    const double n = std::atan2(phongsim::dot(c.n1, cross(kn, s)), phongsim::dot(c.n1, s));
    const double l = std::atan2(phongsim::dot(c.l1, cross(kl, s)), phongsim::dot(c.l1, s));
    const double cos_gamma = phongsim::dot(kn, kl);
    for (const double t : {0.0, 0.3, 0.5, 1.0}) {
      const double nt = t * kb::angle(c.n1, c.n2);
      const double lt = t * kb::angle(c.l1, c.l2);
      const double eq1 =
          std::cos(n + nt) * std::cos(l + lt) + std::sin(n + nt) * std::sin(l + lt) * cos_gamma;
      EXPECT_NEAR(kb::cos_exact(c.n1, c.n2, c.l1, c.l2, t), eq1, 1e-12) << k << " t=" << t;
    }
  }
}

TEST(KbAngular, BothMethodsAreExactAtTheEnds) {
  // Eq. (2): at t = 0 the frame puts N1 and L1 themselves in it; at t = 1, N2' and L2' are N2
  // and L2 turned by the same rotation about P (kb_float.cpp). Eq. (4): V_i·O = R_i L_i·R_i N_i
  // = L_i·N_i. Both hold for any vectors, not only sphere spans.
  std::mt19937_64 rng(13);
  for (int k = 0; k < 2000; ++k) {
    const Couple c =
        k % 2 ? Couple{random_unit(rng), random_unit(rng), random_unit(rng), random_unit(rng)}
              : sphere_span(rng, 1.0);
    const kb::Decomposition d = kb::decompose(c.n1, c.n2, c.l1, c.l2);
    const kb::ScanlineAngles o = kb::one_vector(c.n1, c.n2, c.l1, c.l2);
    for (const double t : {0.0, 1.0}) {
      const double exact = kb::cos_exact(c.n1, c.n2, c.l1, c.l2, t);
      EXPECT_NEAR(d.cos_at(t), exact, 1e-12) << k << " t=" << t;
      EXPECT_NEAR(o.cos_at(t), exact, 1e-12) << k << " t=" << t;
    }
  }
}

struct SpanErrors {
  double max_decomposition = 0;
  double max_one_vector = 0;
  double lit_decomposition = 0;  // max where the exact cos α >= 0.2 (away from the terminator)
  double lit_one_vector = 0;
  double rms_decomposition = 0;
  double rms_one_vector = 0;
};

// Errors of eqs. (2) and (4) against eq. (1) over `spans` sphere spans omega apart, 65 samples
// of t each. Deterministic (fixed seed per omega).
SpanErrors measure(double omega, int spans) {
  std::mt19937_64 rng(1000 + static_cast<int>(std::lround(omega * 1000)));
  SpanErrors e;
  double sum_d = 0;
  double sum_o = 0;
  int count = 0;
  for (int k = 0; k < spans; ++k) {
    const Couple c = sphere_span(rng, omega);
    const kb::Decomposition d = kb::decompose(c.n1, c.n2, c.l1, c.l2);
    const kb::ScanlineAngles o = kb::one_vector(c.n1, c.n2, c.l1, c.l2);
    for (int i = 0; i <= 64; ++i) {
      const double t = i / 64.0;
      const double exact = kb::cos_exact(c.n1, c.n2, c.l1, c.l2, t);
      const double ed = std::abs(d.cos_at(t) - exact);
      const double eo = std::abs(o.cos_at(t) - exact);
      e.max_decomposition = std::max(e.max_decomposition, ed);
      e.max_one_vector = std::max(e.max_one_vector, eo);
      if (exact >= 0.2) {
        e.lit_decomposition = std::max(e.lit_decomposition, ed);
        e.lit_one_vector = std::max(e.lit_one_vector, eo);
      }
      sum_d += ed * ed;
      sum_o += eo * eo;
      ++count;
    }
  }
  e.rms_decomposition = std::sqrt(sum_d / count);
  e.rms_one_vector = std::sqrt(sum_o / count);
  return e;
}

TEST(KbAngular, SphereSpanErrorsAreSmall) {
  // Both methods are exact at the ends, so their error grows from 0 with the span's rotation ω.
  // One vector (4): V's true path R(N_t)L_t leaves the great circle V1V2 by O(ω²) (the rotations
  // R(N_t) do not compose along a geodesic), so the error is ~c·ω²; measured c = 0.16 (N·O >= 0).
  // Decomposition (2): away from the terminator also O(ω²) (c = 0.04 where cos α >= 0.2). Near
  // it, i.e. when L is close to the pole P of N's plane (then cos α ~ 0), L's longitude about P
  // changes fast and non-linearly, and the error there is O(ω_L) = O(ω) (measured 0.12·ω): the
  // paper's "extreme situations". Bounds: the measured constants plus ~25%.
  for (const double degrees : {10.0, 30.0, 45.0, 60.0}) {
    const double w = degrees * kPi / 180;
    const SpanErrors e = measure(w, 3000);
    std::printf(
        "span %2.0f deg: decomposition max %.2e (cos>=0.2: %.2e) rms %.2e | one vector max %.2e "
        "(cos>=0.2: %.2e) rms %.2e\n",
        degrees, e.max_decomposition, e.lit_decomposition, e.rms_decomposition, e.max_one_vector,
        e.lit_one_vector, e.rms_one_vector);
    EXPECT_LT(e.max_one_vector, 0.20 * w * w) << degrees;
    EXPECT_LT(e.lit_decomposition, 0.05 * w * w) << degrees;
    EXPECT_LT(e.max_decomposition, 0.15 * w) << degrees;
    EXPECT_LT(e.rms_decomposition, e.rms_one_vector) << degrees;
  }
}

TEST(KbAngular, MethodsPartWaysAtLargeRotations) {
  // The paper: differences between the methods "became visible when vector rotations on the
  // polygon were about 90°". Typical (rms) errors agree: at 10° both are below 1e-3, a quarter
  // of an 8-bit step; at 90° the one-vector method's rms error is over 4 times the
  // decomposition's and its worst case passes 0.25. Worst cases are stricter than the paper's
  // impression: 0.16·ω² reaches 1/255 already at ω ≈ 9° (SphereSpanErrorsAreSmall).
  const SpanErrors small = measure(10 * kPi / 180, 3000);
  EXPECT_LT(small.rms_decomposition, 1e-3);
  EXPECT_LT(small.rms_one_vector, 1e-3);
  const SpanErrors big = measure(kPi / 2, 3000);
  std::printf("span 90 deg: decomposition max %.2e rms %.2e | one vector max %.2e rms %.2e\n",
              big.max_decomposition, big.rms_decomposition, big.max_one_vector, big.rms_one_vector);
  EXPECT_GT(big.rms_one_vector, 4 * big.rms_decomposition);
  EXPECT_GT(big.max_one_vector, 0.25);
}

TEST(KbAngular, ExactWhenTheNormalDoesNotMove) {
  // N1 = N2: the decomposition puts P on L's great circle, so L moves along a meridian and (2)
  // is exact for all t; the one-vector method rotates both L_i by the same R, so V = R·L_t and
  // (4) is exact too. Includes a path of L over the pole P (L1, L2 on either side of it).
  std::mt19937_64 rng(17);
  for (int k = 0; k < 300; ++k) {
    const Vec3 n = k == 0 ? Vec3{1, 0, 0} : random_unit(rng);
    const Vec3 l1 = k == 0 ? Vec3{0.6, 0.8, 0} : random_unit(rng);
    const Vec3 l2 = k == 0 ? Vec3{-0.6, 0.8, 0} : random_unit(rng);  // k = 0: over the pole
    const kb::Decomposition d = kb::decompose(n, n, l1, l2);
    const kb::ScanlineAngles o = kb::one_vector(n, n, l1, l2);
    EXPECT_NEAR(d.n.dtheta, 0.0, 1e-13);  // Δ = 0 (or ±π over the pole) up to rounding
    for (int i = 0; i <= 8; ++i) {
      const double t = i / 8.0;
      const double exact = kb::cos_exact(n, n, l1, l2, t);
      EXPECT_NEAR(d.cos_at(t), exact, 1e-12) << k << " t=" << t;
      EXPECT_NEAR(o.cos_at(t), exact, 1e-12) << k << " t=" << t;
    }
  }
}

TEST(KbAngular, DecompositionExactWhenTheGreatCirclesArePerpendicular) {
  // cos γ = 0 reduces (1) to a product of cosines (the paper's motivation for (2)): when L's
  // great circle passes through the pole of N's, L's rotation has no component about that pole.
  const Vec3 n1{1, 0, 0};
  const Vec3 n2{std::cos(0.7), std::sin(0.7), 0};  // N turns about z
  const Vec3 l1 = towards(Vec3{std::cos(0.2), std::sin(0.2), 0}, {0, 0, 1}, 0.3);
  const Vec3 l2 = towards(Vec3{std::cos(0.2), std::sin(0.2), 0}, {0, 0, 1}, 1.1);  // same meridian
  const kb::Decomposition d = kb::decompose(n1, n2, l1, l2);
  for (int i = 0; i <= 10; ++i) {
    const double t = i / 10.0;
    EXPECT_NEAR(d.cos_at(t), kb::cos_exact(n1, n2, l1, l2, t), 1e-14) << t;
  }
  EXPECT_NEAR(d.n.theta0, -0.2, 1e-15);  // S' at longitude 0.2: n1 = -0.2, n2 = 0.5
  EXPECT_NEAR(d.n.dtheta, 0.7, 1e-15);
  EXPECT_NEAR(d.l.theta0, 0.3, 1e-15);
  EXPECT_NEAR(d.l.dtheta, 0.8, 1e-15);
}

bool finite(const kb::ScanlineAngles& s) {
  return std::isfinite(s.theta0) && std::isfinite(s.dtheta) && std::isfinite(s.scale);
}

TEST(KbAngular, DecompositionDegenerateCases) {
  const Vec3 n1{1, 0, 0};
  const Vec3 n2{0, 1, 0};  // pole P = z
  struct Case {
    const char* what;
    Vec3 n1, n2, l1, l2;
  };
  const Case cases[] = {
      {"L fixed (light at infinity)", n1, n2, {0.3, 0.4, 0.866}, {0.3, 0.4, 0.866}},
      {"L1 on the pole", n1, n2, {0, 0, 1}, {0.5, 0.5, 0.7}},
      {"L2 on the pole", n1, n2, {0.5, -0.5, 0.7}, {0, 0, 1}},
      {"L1 = L2 on the pole", n1, n2, {0, 0, 1}, {0, 0, 1}},
      {"L passes near the pole", n1, n2, {0.01, -0.2, 1}, {0.01, 0.2, 1}},
      {"N and L fixed", n1, n1, {0.2, 0.3, 0.9}, {0.2, 0.3, 0.9}},
      {"N fixed, L turns about N", n1, n1, {0, 1, 0}, {0, 0, 1}},
      {"L along N's equator", n1, n2, {0, -1, 0}, {-1, 0.1, 0}},
  };
  for (const Case& c : cases) {
    const kb::Decomposition d = kb::decompose(c.n1, c.n2, c.l1, c.l2);
    EXPECT_TRUE(finite(d.n) && finite(d.l)) << c.what;
    for (const double t : {0.0, 1.0}) {
      EXPECT_NEAR(d.cos_at(t), kb::cos_exact(c.n1, c.n2, c.l1, c.l2, t), 1e-12) << c.what;
    }
    for (int i = 1; i < 10; ++i) {
      EXPECT_TRUE(std::isfinite(d.cos_at(i / 10.0))) << c.what;
    }
  }
  // L fixed on N's equator plane: exact for all t (L stays on the meridian of longitude λ1).
  {
    const Vec3 l{0.6, 0.8, 0};
    const kb::Decomposition d = kb::decompose(n1, n2, l, l);
    for (int i = 0; i <= 10; ++i) {
      EXPECT_NEAR(d.cos_at(i / 10.0), kb::cos_exact(n1, n2, l, l, i / 10.0), 1e-14);
    }
  }
  // Near the pole the path crosses ~174° of longitude; carrying L over the pole (option B,
  // kb_float.cpp) keeps (2) within 0.01 of (1) (measured 0.0078), where the plain longitude
  // change (option A: N turns by 90° - 174°) was measured 0.13 off.
  {
    const Case& c = cases[4];
    const kb::Decomposition d = kb::decompose(c.n1, c.n2, c.l1, c.l2);
    for (int i = 0; i <= 10; ++i) {
      const double t = i / 10.0;
      EXPECT_NEAR(d.cos_at(t), kb::cos_exact(c.n1, c.n2, c.l1, c.l2, t), 0.01) << t;
    }
  }
  EXPECT_THROW((void)kb::decompose(n1, -n1, n2, n2), phongsim::Error);
  EXPECT_THROW((void)kb::decompose(n1, n2, {}, n2), phongsim::Error);
}

TEST(KbAngular, OneVectorDegenerateCases) {
  // V1 = V2 (N and L turn together): V stands still; s = 0 on the great circle through V1 and O.
  {
    const Vec3 v{0.6, 0, 0.8};
    const kb::ScanlineAngles o = kb::one_vector_from_v(v, v);
    EXPECT_TRUE(finite(o));
    EXPECT_EQ(o.dtheta, 0.0);
    EXPECT_NEAR(o.scale, 1.0, 1e-15);
    EXPECT_NEAR(std::abs(o.theta0), std::acos(0.8), 1e-15);
    EXPECT_NEAR(o.cos_at(0.5), 0.8, 1e-15);
    // V1 = V2 = O and = -O.
    EXPECT_NEAR(kb::one_vector_from_v(kb::kO, kb::kO).cos_at(0.3), 1.0, 1e-15);
    EXPECT_NEAR(kb::one_vector_from_v(-kb::kO, -kb::kO).cos_at(0.3), -1.0, 1e-15);
  }
  // O on the great circle: s = 0, S = O, and (4) is cos of the angle from O.
  {
    const Vec3 v1{std::sin(-0.3), 0, std::cos(-0.3)};
    const Vec3 v2{std::sin(0.9), 0, std::cos(0.9)};
    const kb::ScanlineAngles o = kb::one_vector_from_v(v1, v2);
    EXPECT_NEAR(o.scale, 1.0, 1e-15);
    EXPECT_NEAR(o.theta0, -0.3, 1e-15);
    EXPECT_NEAR(o.dtheta, 1.2, 1e-15);
  }
  // O the pole of the great circle (V on the equator z = 0): cos α = 0 all along.
  {
    const kb::ScanlineAngles o = kb::one_vector_from_v({1, 0, 0}, {0.6, 0.8, 0});
    EXPECT_TRUE(finite(o));
    EXPECT_EQ(o.scale, 0.0);
    EXPECT_EQ(o.cos_at(0.4), 0.0);
  }
  // s as defined: V on the circle z = sin s... here the great circle through (1, 0, 0) and
  // (0, cos 0.4, sin 0.4) has pole (0, -sin 0.4, cos 0.4); O·pole = cos 0.4 = sin s, so
  // cos s = sin 0.4, S = (0, cos 0.4, sin 0.4) = V2 and ν = -π/2 (V1 is a quarter turn before).
  {
    const kb::ScanlineAngles o =
        kb::one_vector_from_v({1, 0, 0}, {0, std::cos(0.4), std::sin(0.4)});
    EXPECT_NEAR(o.scale, std::sin(0.4), 1e-15);
    EXPECT_NEAR(o.theta0, -kPi / 2, 1e-15);
    EXPECT_NEAR(o.dtheta, kPi / 2, 1e-15);
  }
  // align_to_o: N = O is the identity, N = -O the half turn about x, otherwise N goes to O.
  EXPECT_EQ(kb::align_to_o(kb::kO, {0.6, 0.8, 0}), (Vec3{0.6, 0.8, 0}));
  EXPECT_EQ(kb::align_to_o(-kb::kO, {0.6, 0.8, 0}), (Vec3{0.6, -0.8, 0}));
  std::mt19937_64 rng(19);
  for (int k = 0; k < 100; ++k) {
    const Vec3 n = random_unit(rng);
    const Vec3 l = random_unit(rng);
    const Vec3 rn = kb::align_to_o(n, n);
    EXPECT_NEAR(rn.x, 0.0, 1e-15);
    EXPECT_NEAR(rn.y, 0.0, 1e-15);
    EXPECT_NEAR(rn.z, 1.0, 1e-15);
    EXPECT_NEAR(kb::align_to_o(n, l).z, phongsim::dot(n, l), 1e-15);
    // The rotation is about N × O: that axis is unchanged.
    const Vec3 axis = cross(n, kb::kO);
    const Vec3 ra = kb::align_to_o(n, axis);
    EXPECT_NEAR(kb::angle(ra, axis), 0.0, 1e-7);
  }
  EXPECT_THROW((void)kb::one_vector_from_v({1, 0, 0}, {-1, 0, 0}), phongsim::Error);
}

}  // namespace
