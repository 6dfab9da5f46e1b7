// Tests for the quadratic-shading reference (ref/quad_float.*): Vlasic, "Fake Phong Shading"
// (seed 000) eqs. 3.5, 3.6-3.11 and 4.1-4.3 with the sample order of SEED-NOTES.md: the
// coefficients, the (s, t) map, the screen polynomial and its forward differencing. The top-left
// coverage rule: quad_float_coverage_test.cpp.
//
// Independent references used here: a 6x6 Gaussian elimination for eq. 4.2; Cramer's rule on
// eq. 3.5 for eq. 4.3.
#include "ref/quad_float.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>

#include "base/error.h"
#include "base/vec3.h"

namespace {

namespace quad = phongsim::quad;
using phongsim::Error;
using phongsim::Vec3;
using quad::Vertex2;

// ---- helpers ----

// Solves A·x = b (6x6) by Gaussian elimination with partial pivoting.
std::array<double, 6> solve6(std::array<std::array<double, 6>, 6> a, std::array<double, 6> b) {
  for (int col = 0; col < 6; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 6; ++r) {
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    }
    std::swap(a[col], a[pivot]);
    std::swap(b[col], b[pivot]);
    for (int r = col + 1; r < 6; ++r) {
      const double f = a[r][col] / a[col][col];
      for (int k = col; k < 6; ++k) a[r][k] -= f * a[col][k];
      b[r] -= f * b[col];
    }
  }
  std::array<double, 6> x{};
  for (int r = 5; r >= 0; --r) {
    double v = b[r];
    for (int k = r + 1; k < 6; ++k) v -= a[r][k] * x[k];
    x[r] = v / a[r][r];
  }
  return x;
}

double max_abs(const quad::Coeffs& c) {
  double m = 0;
  for (double v : c) m = std::max(m, std::abs(v));
  return m;
}

// ---- eqs. 4.1 and 4.2 ----

TEST(QuadCoefficients, ReproduceTheSixSamplesExactly) {
  // Small integers: every product and sum below is exact, so equality is exact.
  const quad::Samples r{3, -7, 11, 2, 5, -13};
  const quad::Coeffs c = quad::coefficients(r);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(quad::eval_st(c, quad::kSampleSt[k]), r[k]) << k;
  // The sample positions, spelled out (SEED-NOTES.md order).
  EXPECT_EQ(quad::kSampleSt[0], (quad::St{0, 0}));
  EXPECT_EQ(quad::kSampleSt[1], (quad::St{0.5, 0}));
  EXPECT_EQ(quad::kSampleSt[2], (quad::St{1, 0}));
  EXPECT_EQ(quad::kSampleSt[3], (quad::St{0.5, 0.5}));
  EXPECT_EQ(quad::kSampleSt[4], (quad::St{0, 1}));
  EXPECT_EQ(quad::kSampleSt[5], (quad::St{0, 0.5}));
  std::mt19937_64 gen(1);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int n = 0; n < 1000; ++n) {
    quad::Samples s;
    for (double& v : s) v = u(gen);
    const quad::Coeffs cs = quad::coefficients(s);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(quad::eval_st(cs, quad::kSampleSt[k]), s[k], 1e-14);
  }
}

TEST(QuadCoefficients, MatchAGeneralSolveOfTheSixEquations) {
  std::array<std::array<double, 6>, 6> a{};
  for (int k = 0; k < 6; ++k) {
    const auto [s, t] = quad::kSampleSt[k];
    a[k] = {1, s, t, s * s, s * t, t * t};
  }
  std::mt19937_64 gen(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int n = 0; n < 200; ++n) {
    quad::Samples r;
    for (double& v : r) v = u(gen);
    const auto expect = solve6(a, r);
    const auto got = quad::coefficients(r);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(got[k], expect[k], 1e-13) << k;
  }
}

TEST(QuadCoefficients, ReproduceAnyQuadraticInST) {
  // Six samples of a quadratic determine it: coefficients() must return its own coefficients.
  const quad::Coeffs q{0.25, -1.5, 2.0, 0.75, -3.0, 1.25};  // dyadic: exact arithmetic
  quad::Samples r;
  for (int k = 0; k < 6; ++k) r[k] = quad::eval_st(q, quad::kSampleSt[k]);
  EXPECT_EQ(quad::coefficients(r), q);
}

TEST(QuadCoefficients, LinearCoefficientsAreThePlaneThroughTheVertices) {
  const quad::Coeffs c = quad::linear_coefficients(0.5, -2, 3.25);
  EXPECT_EQ(c[3], 0.0);
  EXPECT_EQ(c[4], 0.0);
  EXPECT_EQ(c[5], 0.0);
  EXPECT_EQ(quad::eval_st(c, 0, 0), 0.5);
  EXPECT_EQ(quad::eval_st(c, 1, 0), -2.0);
  EXPECT_EQ(quad::eval_st(c, 0, 1), 3.25);
  EXPECT_EQ(quad::eval_st(c, 0.5, 0.5), (-2 + 3.25) / 2);
  // Equal to eq. 4.2 with each midpoint the average of its vertices (a plane is a quadratic).
  const quad::Samples r{0.5, (0.5 - 2) / 2, -2, (-2 + 3.25) / 2, 3.25, (3.25 + 0.5) / 2};
  EXPECT_EQ(quad::coefficients(r), c);
}

TEST(QuadCoefficients, SharedEdgesGetTheSameColour) {
  // §4.3: the three samples on an edge fix r along it, so two triangles sharing the edge and its
  // samples agree along it. Triangles (A, B, C) and (B, A, D) share A-B; their samples come from
  // one smooth "lighting" function at sample_points().
  const auto light = [](Vertex2 p) { return std::sin(0.1 * p.x) * std::cos(0.07 * p.y) + 0.5; };
  const Vertex2 A{10.3, 20.1}, B{40.7, 25.9}, C{22.0, 5.5}, D{31.2, 47.8};
  const auto samples = [&](Vertex2 v0, Vertex2 v1, Vertex2 v2) {
    quad::Samples r;
    const auto pts = quad::sample_points(v0, v1, v2);
    for (int k = 0; k < 6; ++k) r[k] = light(pts[k]);
    return r;
  };
  const auto c1 = quad::coefficients(samples(A, B, C));
  const auto c2 = quad::coefficients(samples(B, A, D));
  for (int n = 0; n <= 100; ++n) {
    const double l = n / 100.0;
    const Vertex2 p{A.x + l * (B.x - A.x), A.y + l * (B.y - A.y)};
    const double r1 = quad::eval_st(c1, quad::st_at(A, B, C, p));
    const double r2 = quad::eval_st(c2, quad::st_at(B, A, D, p));
    EXPECT_NEAR(r1, r2, 1e-13) << l;
  }
  // Away from the edge they differ (the two quadratics are different functions).
  EXPECT_GT(std::abs(c1[5] - c2[5]), 1e-6);
}

TEST(QuadSamples, PointsAndNormalsInEq42Order) {
  const Vertex2 v0{1, 2}, v1{5, 2}, v2{1, 10};
  const auto p = quad::sample_points(v0, v1, v2);
  EXPECT_EQ(p[0], v0);
  EXPECT_EQ(p[1], (Vertex2{3, 2}));
  EXPECT_EQ(p[2], v1);
  EXPECT_EQ(p[3], (Vertex2{3, 6}));
  EXPECT_EQ(p[4], v2);
  EXPECT_EQ(p[5], (Vertex2{1, 6}));
  // Each sample point has the (s, t) of kSampleSt.
  for (int k = 0; k < 6; ++k) {
    const auto st = quad::st_at(v0, v1, v2, p[k]);
    EXPECT_EQ(st, quad::kSampleSt[k]) << k;
  }
  const auto n = quad::sample_normals({0, 0, 2}, {3, 0, 0}, {0, 1, 1});
  const double h = std::sqrt(0.5);
  EXPECT_EQ(n[0], (Vec3{0, 0, 1}));
  EXPECT_EQ(n[2], (Vec3{1, 0, 0}));
  EXPECT_NEAR(n[4].y, h, 1e-15);
  EXPECT_NEAR(n[4].z, h, 1e-15);
  for (const auto& v : n) EXPECT_NEAR(phongsim::dot(v, v), 1.0, 1e-15);
  // Midpoints bisect: equal angles to both neighbours, in their plane.
  EXPECT_NEAR(n[1].x, h, 1e-15);
  EXPECT_NEAR(n[1].z, h, 1e-15);
  for (const auto& [m, a, b] : {std::array{1, 0, 2}, std::array{3, 2, 4}, std::array{5, 4, 0}}) {
    EXPECT_NEAR(phongsim::dot(n[m], n[a]), phongsim::dot(n[m], n[b]), 1e-15);
  }
  EXPECT_THROW((void)quad::sample_normals({0, 0, 1}, {0, 0, -3}, {1, 0, 0}), Error);
  EXPECT_THROW((void)quad::sample_normals({0, 0, 0}, {0, 0, 1}, {1, 0, 0}), Error);
  EXPECT_THROW((void)quad::sample_normals({0, 0, std::numeric_limits<double>::quiet_NaN()},
                                          {0, 0, 1}, {1, 0, 0}),
               Error);
}

// ---- eqs. 3.5 and 4.3 ----

TEST(QuadSt, Eq43MapsTheVerticesAndInvertsEq35) {
  std::mt19937_64 gen(3);
  std::uniform_real_distribution<double> u(0, 300);
  std::uniform_real_distribution<double> w(-0.5, 1.5);
  for (int n = 0; n < 500; ++n) {
    const Vertex2 v0{u(gen), u(gen)}, v1{u(gen), u(gen)}, v2{u(gen), u(gen)};
    const double det = (v1.x - v0.x) * (v2.y - v0.y) - (v2.x - v0.x) * (v1.y - v0.y);
    if (std::abs(det) < 100) continue;  // skip slivers: eq. 4.3's constants lose digits there
    const quad::StMap m = quad::st_affine(v0, v1, v2);
    const auto s0 = m.at(v0), s1 = m.at(v1), s2 = m.at(v2);
    EXPECT_NEAR(s0.s, 0, 1e-11);
    EXPECT_NEAR(s0.t, 0, 1e-11);
    EXPECT_NEAR(s1.s, 1, 1e-11);
    EXPECT_NEAR(s1.t, 0, 1e-11);
    EXPECT_NEAR(s2.s, 0, 1e-11);
    EXPECT_NEAR(s2.t, 1, 1e-11);
    for (int k = 0; k < 10; ++k) {
      const quad::St st{w(gen), w(gen)};
      const Vertex2 p = quad::st_to_xy(v0, v1, v2, st);
      const auto back = m.at(p);
      EXPECT_NEAR(back.s, st.s, 1e-10);
      EXPECT_NEAR(back.t, st.t, 1e-10);
      const auto direct = quad::st_at(v0, v1, v2, p);
      EXPECT_NEAR(direct.s, st.s, 1e-12);
      EXPECT_NEAR(direct.t, st.t, 1e-12);
    }
  }
}

TEST(QuadSt, Eq43SignConventionBySubstitution) {
  // v0 = (1, 2), v1 = (5, 2), v2 = (1, 10): eq. 4.3's denominator is
  // (x2 - x0)(y1 - y0) - (x1 - x0)(y2 - y0) = 0·0 - 4·8 = -32 (minus eq. 3.5's determinant), and
  // s = ((y0 - y2)x + (x2 - x0)y + x0·y2 - x2·y0)/D = (-8x + 0·y + 10 - 2)/(-32) = (x - 1)/4,
  // t = ((y1 - y0)x + (x0 - x1)y + x1·y0 - x0·y1)/D = (0·x - 4y + 10 - 2)/(-32) = (y - 2)/8.
  // Both windings, and all in exact arithmetic.
  const Vertex2 v0{1, 2}, v1{5, 2}, v2{1, 10};
  const quad::StMap m = quad::st_affine(v0, v1, v2);
  EXPECT_EQ(m.s.x_coef, 0.25);
  EXPECT_EQ(m.s.y_coef, 0.0);
  EXPECT_EQ(m.s.c, -0.25);
  EXPECT_EQ(m.t.x_coef, 0.0);
  EXPECT_EQ(m.t.y_coef, 0.125);
  EXPECT_EQ(m.t.c, -0.25);
  // Reversed winding: s and t exchange roles.
  const quad::StMap r = quad::st_affine(v0, v2, v1);
  EXPECT_EQ(r.s.y_coef, 0.125);
  EXPECT_EQ(r.t.x_coef, 0.25);
  EXPECT_EQ(r.at(v2), (quad::St{1, 0}));
  EXPECT_EQ(r.at(v1), (quad::St{0, 1}));
}

TEST(QuadSt, DegenerateTrianglesAreRejected) {
  EXPECT_THROW((void)quad::st_affine({0, 0}, {1, 1}, {2, 2}), Error);
  EXPECT_THROW((void)quad::st_at({0, 0}, {0, 0}, {2, 3}, {1, 1}), Error);
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)quad::st_affine({0, 0}, {inf, 1}, {2, 3}), Error);
  EXPECT_THROW((void)quad::screen_poly({}, {0, 0}, {1, 0}, {2, 0}, 0, 0), Error);
}

// ---- screen polynomial and forward differencing ----

TEST(QuadScreenPoly, EqualsDirectEvaluationAtPixelCentres) {
  // Every pixel of each triangle's bounding box, origin at its top-left pixel (as the walker
  // uses it). Both sides sum terms that can be much larger than the result (slivers: s and t
  // reach hundreds at far corners of the box), so the bound is relative to the sum of the
  // absolute terms of both evaluations (measured worst 4e-16); for well-shaped triangles
  // (|det| >= 1/4 of the box area) it is also 1e-12 relative to max |C| (measured 3e-15).
  std::mt19937_64 gen(4);
  std::uniform_real_distribution<double> pos(0, 400);
  std::uniform_real_distribution<double> size(2, 80);
  std::uniform_real_distribution<double> col(0, 1);
  double worst_terms = 0, worst_shaped = 0;
  int tested = 0, shaped = 0;
  for (int n = 0; n < 300; ++n) {
    const Vertex2 v0{pos(gen), pos(gen)};
    const Vertex2 v1{v0.x + size(gen), v0.y + size(gen) - 40};
    const Vertex2 v2{v0.x + size(gen) - 40, v0.y + size(gen)};
    const double det = (v1.x - v0.x) * (v2.y - v0.y) - (v2.x - v0.x) * (v1.y - v0.y);
    if (std::abs(det) < 10) continue;
    quad::Samples r;
    for (double& v : r) v = col(gen);
    const quad::Coeffs c =
        n % 5 == 0 ? quad::linear_coefficients(r[0], r[2], r[4]) : quad::coefficients(r);
    const int x0 = static_cast<int>(std::floor(std::min({v0.x, v1.x, v2.x})));
    const int y0 = static_cast<int>(std::floor(std::min({v0.y, v1.y, v2.y})));
    const int x1 = static_cast<int>(std::ceil(std::max({v0.x, v1.x, v2.x})));
    const int y1 = static_cast<int>(std::ceil(std::max({v0.y, v1.y, v2.y})));
    const bool well_shaped = std::abs(det) >= 0.25 * (x1 - x0) * (y1 - y0);
    shaped += well_shaped;
    const quad::ScreenPoly p = quad::screen_poly(c, v0, v1, v2, x0, y0);
    const double scale = std::max(1.0, max_abs(c));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const auto [s, t] = quad::st_at(v0, v1, v2, {x + 0.5, y + 0.5});
        const double direct = quad::eval_st(c, s, t);
        const double i = x - x0, j = y - y0;
        const double poly = quad::eval_poly(p, i, j);
        const double terms = std::abs(c[0]) + std::abs(c[1] * s) + std::abs(c[2] * t) +
                             std::abs(c[3] * s * s) + std::abs(c[4] * s * t) +
                             std::abs(c[5] * t * t) + std::abs(p.a * i * i) +
                             std::abs(p.b * i * j) + std::abs(p.c * j * j) + std::abs(p.p10 * i) +
                             std::abs(p.p01 * j) + std::abs(p.p00);
        worst_terms = std::max(worst_terms, std::abs(poly - direct) / terms);
        if (well_shaped) worst_shaped = std::max(worst_shaped, std::abs(poly - direct) / scale);
        ++tested;
      }
    }
  }
  EXPECT_GT(tested, 100000);
  EXPECT_GT(shaped, 50);
  EXPECT_LT(worst_terms, 1e-14);
  EXPECT_LT(worst_shaped, 1e-12);
}

TEST(QuadScreenPoly, OriginPixelAndSTItself) {
  // With C = (0, 1, 0, 0, 0, 0) the polynomial is s itself: eq. 4.3's gradient and s at the
  // origin pixel's centre. v0 = (1, 2), v1 = (5, 2), v2 = (1, 10): s = (x - 1)/4, t = (y - 2)/8.
  const Vertex2 v0{1, 2}, v1{5, 2}, v2{1, 10};
  const auto ps = quad::screen_poly({0, 1, 0, 0, 0, 0}, v0, v1, v2, 3, 7);
  EXPECT_EQ(ps.a, 0.0);
  EXPECT_EQ(ps.b, 0.0);
  EXPECT_EQ(ps.c, 0.0);
  EXPECT_EQ(ps.p10, 0.25);
  EXPECT_EQ(ps.p01, 0.0);
  EXPECT_EQ(ps.p00, (3.5 - 1) / 4);
  const auto pt = quad::screen_poly({0, 0, 1, 0, 0, 0}, v0, v1, v2, 3, 7);
  EXPECT_EQ(pt.p01, 0.125);
  EXPECT_EQ(pt.p00, (7.5 - 2) / 8);
  // s·t = (x - 1)(y - 2)/32: b = 1/32.
  const auto pst = quad::screen_poly({0, 0, 0, 0, 1, 0}, v0, v1, v2, 0, 0);
  EXPECT_EQ(pst.b, 1.0 / 32);
  EXPECT_EQ(quad::eval_poly(pst, 2, 5), (2.5 - 1) * (5.5 - 2) / 32);
}

TEST(QuadForwardDifference, MatchesEvaluation) {
  const Vertex2 v0{12.3, 4.7}, v1{70.1, 20.2}, v2{30.6, 66.9};
  const quad::Coeffs c = quad::coefficients({0.1, 0.9, 0.3, 0.2, 0.7, 0.5});
  const quad::ScreenPoly p = quad::screen_poly(c, v0, v1, v2, 12, 4);
  const int w = 60, h = 64;
  const auto fd = quad::forward_difference(p, w, h);
  ASSERT_EQ(fd.size(), static_cast<std::size_t>(w * h));
  double worst = 0;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      worst = std::max(
          worst, std::abs(fd[static_cast<std::size_t>(j * w + i)] - quad::eval_poly(p, i, j)));
    }
  }
  EXPECT_LT(worst, 1e-11);
  // Exact for integer coefficients (every sum is an integer below 2^53).
  const quad::ScreenPoly q{3, -2, 5, 7, -11, 13};
  const auto fq = quad::forward_difference(q, 17, 9);
  for (int j = 0; j < 9; ++j) {
    for (int i = 0; i < 17; ++i)
      EXPECT_EQ(fq[static_cast<std::size_t>(j * 17 + i)], quad::eval_poly(q, i, j));
  }
  EXPECT_TRUE(quad::forward_difference(q, 0, 5).empty());
  EXPECT_THROW((void)quad::forward_difference(q, -1, 5), Error);
}

}  // namespace
