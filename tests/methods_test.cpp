// The float references of the seeds' other methods: Vlasic's texture coordinates and textures
// (ref/texture_maps.h), Bishop-Weimer's Taylor expansion (ref/fast_phong.h) and Lai-Tai's
// highlight-track point (ref/highlight_track.h). Renders of them: tests/render_test.cpp.
#include <gtest/gtest.h>

#include "tests/error_of.h"

#include <cmath>
#include <random>

#include "ref/fast_phong.h"
#include "ref/highlight_track.h"
#include "ref/texture_maps.h"

namespace phongsim {
namespace {

Vec3 RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return normalized({g(rng), g(rng), g(rng)});
}

// ---- Environment map ----

TEST(SphereMap, Eqs51To53HandComputed) {
  const texmap::Uv centre = texmap::sphere_map_uv({0, 0, 1});  // straight back at the viewer
  EXPECT_DOUBLE_EQ(centre.u, 0.5);
  EXPECT_DOUBLE_EQ(centre.v, 0.5);
  const texmap::Uv right = texmap::sphere_map_uv({1, 0, 0});  // m = sqrt(2)
  EXPECT_DOUBLE_EQ(right.u, 0.5 + 0.5 / std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(right.v, 0.5);
  const texmap::Uv up = texmap::sphere_map_uv({0, 0.6, 0.8});  // m = sqrt(0.36 + 3.24) = 1.897
  EXPECT_NEAR(up.v, 0.5 + 0.3 / std::sqrt(3.6), 1e-15);
  const texmap::Uv behind = texmap::sphere_map_uv({0, 0, -1});  // m = 0: the rim point
  EXPECT_EQ(behind.u, 1);
  EXPECT_EQ(behind.v, 0.5);
}

// The texture built from sphere_map_direction() shows at (u, v) exactly the W that maps there,
// so a lookup at a vertex's coordinates evaluates (W·L)^n of that vertex's own W.
TEST(SphereMap, DirectionInvertsTheCoordinates) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 w = RandomUnit(rng);
    if (w.z < -0.999) continue;  // near the one direction the map cannot place
    Vec3 back;
    ASSERT_TRUE(texmap::sphere_map_direction(texmap::sphere_map_uv(w), back));
    EXPECT_NEAR(back.x, w.x, 1e-9);
    EXPECT_NEAR(back.y, w.y, 1e-9);
    EXPECT_NEAR(back.z, w.z, 1e-9);
  }
  Vec3 untouched{7, 7, 7};
  EXPECT_FALSE(texmap::sphere_map_direction({0.95, 0.95}, untouched));  // outside the disc
  EXPECT_EQ(untouched, (Vec3{7, 7, 7}));
}

// ---- Blinn map ----

// Vlasic §6.4: "by construction, colour values at triangle vertices are exactly the same as in
// Phong shading": the texture at a vertex's coordinates is max(N·P, 0) (diffuse, eq. 5.4) and
// (N·P)^e (specular, eq. 5.5), on both sides of the plane (the far side unfolded to zero).
TEST(BlinnMap, TexturesAtTheCoordinatesAreTheDotProducts) {
  std::mt19937_64 rng(11);
  const Vec3 up{0, 1, 0}, right{1, 0, 0};
  int far_side = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 n = RandomUnit(rng), p = RandomUnit(rng);
    const double np = dot(n, p);
    const texmap::Uv uv = texmap::blinn_uv(n, p, up, right);
    SCOPED_TRACE(i);
    EXPECT_NEAR(texmap::blinn_diffuse(uv.u, uv.v), std::max(np, 0.0), 2e-7);
    EXPECT_NEAR(texmap::blinn_specular(uv.u, uv.v, 80), np > 0 ? std::pow(np, 80) : 0, 1e-12);
    if (np < 0) {
      ++far_side;
      EXPECT_GE(std::hypot(uv.u, uv.v), 1.0);  // unfolded outside the disc
    } else {
      EXPECT_LE(std::hypot(uv.u, uv.v), 1.0 + 1e-15);
    }
  }
  EXPECT_GT(far_side, 5000);
}

// Eqs. 5.6-5.7: u along the projection of the global axis, v along p × û; the antipode of p at
// (2, 0); the axis parallel to p (Figure 5.6's singularity) falls back to the other axis.
TEST(BlinnMap, AxesAndSingularity) {
  const Vec3 p{0, 0, 1};
  const texmap::Uv along_up = texmap::blinn_uv(normalized({0, 0.3, 1}), p, {0, 1, 0}, {1, 0, 0});
  EXPECT_NEAR(along_up.u, 0.3 / std::sqrt(1.09), 1e-15);
  EXPECT_NEAR(along_up.v, 0, 1e-15);
  // p × û = (0, 0, 1) × (0, 1, 0) = (-1, 0, 0).
  const texmap::Uv along_x = texmap::blinn_uv(normalized({0.3, 0, 1}), p, {0, 1, 0}, {1, 0, 0});
  EXPECT_NEAR(along_x.u, 0, 1e-15);
  EXPECT_NEAR(along_x.v, -0.3 / std::sqrt(1.09), 1e-15);
  const texmap::Uv antipode = texmap::blinn_uv({0, 0, -1}, p, {0, 1, 0}, {1, 0, 0});
  EXPECT_EQ(antipode.u, 2);
  EXPECT_EQ(antipode.v, 0);
  const texmap::Uv singular = texmap::blinn_uv(normalized({0.3, 0, 1}), p, p, {1, 0, 0});
  EXPECT_NEAR(singular.u, 0.3 / std::sqrt(1.09), 1e-15);  // û = the fallback's projection
}

// ---- Textures ----

TEST(Texture, NearestBilinearBorderAndExact) {
  // An affine function: nearest gives the texel centre's value, bilinear reproduces it exactly
  // between texel centres; outside the texels both give 0.
  const auto affine = [](double x, double y) { return 0.25 + 0.5 * x - 0.125 * y; };
  const texmap::Texture t(affine, -1, 1, 8);  // texel size 0.25, centres at -0.875 + 0.25 i
  EXPECT_FLOAT_EQ(static_cast<float>(t.sample(0.1, 0.3, texmap::Filter::nearest)),
                  static_cast<float>(affine(0.125, 0.375)));
  for (const double x : {-0.8, -0.3, 0.0, 0.41, 0.87}) {
    for (const double y : {-0.86, 0.2, 0.6}) {
      EXPECT_NEAR(t.sample(x, y, texmap::Filter::bilinear), affine(x, y), 1e-6) << x << " " << y;
    }
  }
  EXPECT_EQ(t.sample(1.01, 0, texmap::Filter::nearest), 0);
  EXPECT_EQ(t.sample(0, -1.5, texmap::Filter::bilinear), 0);
  EXPECT_EQ(t.sample(std::nan(""), 0, texmap::Filter::bilinear), 0);
  // Half a texel inside the edge, bilinear blends with the zero border.
  EXPECT_NEAR(t.sample(-0.9375, 0.125, texmap::Filter::bilinear), 0.75 * affine(-0.875, 0.125),
              1e-6);
  const texmap::Texture exact(affine, -1, 1, 0);
  EXPECT_EQ(exact.sample(0.123, -0.456, texmap::Filter::nearest), affine(0.123, -0.456));
  EXPECT_EQ(exact.sample(1.5, 0, texmap::Filter::nearest), 0);
}

// Bilinear error falls with the square of the texel size, nearest's with the size.
TEST(Texture, SamplingErrorShrinksWithResolution) {
  const auto spec = [](double x, double y) { return texmap::blinn_specular(x, y, 20); };
  const auto max_error = [&](int size, texmap::Filter filter) {
    const texmap::Texture t(spec, -1, 1, size);
    double e = 0;
    for (int i = 0; i < 400; ++i) {
      for (int j = 0; j < 400; ++j) {
        const double x = -0.7 + 1.4 * i / 399, y = -0.7 + 1.4 * j / 399;
        e = std::max(e, std::abs(t.sample(x, y, filter) - spec(x, y)));
      }
    }
    return e;
  };
  const double b64 = max_error(64, texmap::Filter::bilinear);
  const double b256 = max_error(256, texmap::Filter::bilinear);
  const double n64 = max_error(64, texmap::Filter::nearest);
  const double n256 = max_error(256, texmap::Filter::nearest);
  EXPECT_LT(b64, n64 / 4);
  EXPECT_GT(b64 / b256, 12);  // 16 for an exact h² law
  EXPECT_GT(n64 / n256, 3);   // 4 for an exact h law
}

TEST(Texture, Errors) {
  const auto f = [](double, double) { return 0.0; };
  EXPECT_EQ(testing::ErrorOf([&] { (void)texmap::Texture(f, -1, 1, -1); }),
            "texture size -1 is out of range (0..4096; 0: the exact function)");
  EXPECT_EQ(testing::ErrorOf([&] { (void)texmap::Texture(f, -1, 1, 4097); }),
            "texture size 4097 is out of range (0..4096; 0: the exact function)");
  EXPECT_EQ(testing::ErrorOf([&] { (void)texmap::Texture(f, 1, 1, 8); }),
            "texture range [1, 1] is empty");
  EXPECT_EQ(testing::ErrorOf([] { (void)texmap::parse_filter("trilinear"); }),
            "unknown texture filter 'trilinear' (known: nearest, bilinear)");
  EXPECT_EQ(texmap::parse_filter("nearest"), texmap::Filter::nearest);
}

// ---- Fast Phong ----

// The Taylor polynomial has the value, gradient and Hessian of D·N/|N| at the centroid
// (checked against central differences of cosine()).
TEST(FastPhong, TaylorMatchesTheDerivativesAtTheCentroid) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 c = RandomUnit(rng);
    const Vec3 n0 = normalized(c + 0.4 * RandomUnit(rng)),
               n1 = normalized(c + 0.4 * RandomUnit(rng)),
               n2 = normalized(c + 0.4 * RandomUnit(rng)), d = RandomUnit(rng);
    const quad::Coeffs k = fast_phong::taylor(n0, n1, n2, d);
    const auto f = [&](double s, double t) { return fast_phong::cosine(n0, n1, n2, d, {s, t}); };
    const auto p = [&](double s, double t) { return quad::eval_st(k, s, t); };
    const double s0 = 1.0 / 3, t0 = 1.0 / 3, h = 1e-3;
    SCOPED_TRACE(trial);
    EXPECT_NEAR(p(s0, t0), f(s0, t0), 1e-14);
    for (const auto& [ds, dt] : {std::pair{1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {1.0, -1.0}}) {
      const double fd1 = (f(s0 + h * ds, t0 + h * dt) - f(s0 - h * ds, t0 - h * dt)) / (2 * h);
      const double pd1 = (p(s0 + h * ds, t0 + h * dt) - p(s0 - h * ds, t0 - h * dt)) / (2 * h);
      EXPECT_NEAR(pd1, fd1, 1e-5);
      const double fd2 =
          (f(s0 + h * ds, t0 + h * dt) - 2 * f(s0, t0) + f(s0 - h * ds, t0 - h * dt)) / (h * h);
      const double pd2 =
          (p(s0 + h * ds, t0 + h * dt) - 2 * p(s0, t0) + p(s0 - h * ds, t0 - h * dt)) / (h * h);
      EXPECT_NEAR(pd2, fd2, 1e-4);
    }
  }
}

// Second order: the error at the vertices falls with the cube of the normals' spread.
TEST(FastPhong, ErrorIsThirdOrderInTheNormalSpread) {
  const Vec3 c = normalized({0.2, 0.1, 1}), d = normalized({0.5, 0.4, 1});
  const Vec3 dev[3] = {{0.5, -0.2, 0}, {-0.3, 0.6, 0.1}, {-0.1, -0.4, 0.2}};
  const auto vertex_error = [&](double spread) {
    const Vec3 n0 = normalized(c + spread * dev[0]), n1 = normalized(c + spread * dev[1]),
               n2 = normalized(c + spread * dev[2]);
    const quad::Coeffs k = fast_phong::taylor(n0, n1, n2, d);
    double e = 0;
    for (const quad::St st : {quad::St{0, 0}, quad::St{1, 0}, quad::St{0, 1}}) {
      e = std::max(e, std::abs(quad::eval_st(k, st) - fast_phong::cosine(n0, n1, n2, d, st)));
    }
    return e;
  };
  const double ratio = vertex_error(0.2) / vertex_error(0.1);
  EXPECT_GT(ratio, 6.5);
  EXPECT_LT(ratio, 9.5);
  EXPECT_GT(vertex_error(0.2), 1e-4);  // not exact away from the centroid
  EXPECT_EQ(testing::ErrorOf([] {
              (void)fast_phong::taylor({1, 0, 0}, {-1, 0, 0}, {0, 0, 0}, {0, 0, 1});
            }),
            "fast Phong: the interpolated normal vanishes at the centroid");
}

// ---- Highlight track ----

TEST(HighlightTrack, FootOfThePerpendicular) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 n0 = RandomUnit(rng), dn = 0.1 * RandomUnit(rng), h = RandomUnit(rng);
    const double x = highlight_track_offset(n0, dn, h);
    const auto dist = [&](double at) { return length(n0 + at * dn - h); };
    EXPECT_NEAR(dot(n0 + x * dn - h, dn), 0, 1e-12);
    EXPECT_LT(dist(x), dist(x + 0.01));
    EXPECT_LT(dist(x), dist(x - 0.01));
  }
  // Along the x axis through (0, 0, 1), H tilted towards +x: the foot at tan(angle).
  EXPECT_NEAR(highlight_track_offset({0, 0, 1}, {1, 0, 0}, normalized({0.2, 0, 1})),
              0.2 / std::sqrt(1.04), 1e-15);
  EXPECT_TRUE(std::isnan(highlight_track_offset({0, 0, 1}, {0, 0, 0}, {0, 0, 1})));
}

}  // namespace
}  // namespace phongsim
