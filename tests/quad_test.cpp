// The quadratic colour interpolator: the walker model's coverage against the exact reference
// rasterizer (ref/quad_float.h) on meshes and random triangles, the setup against the exact
// polynomial, the guard-bit bound, the RTL's cycle cost, and configuration refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "base/error.h"
#include "model/config.h"
#include "model/quad.h"
#include "model/quad_setup.h"
#include "sim/cosim/harness.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/pipelines/quad.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

QuadFormats Formats(int guard_bits, int sub_bits = 4) {
  QuadFormats f;
  f.acc = fx::Format{true, 2, 8 + guard_bits};
  f.out = fx::Format{false, 0, 8};
  f.sub_bits = sub_bits;
  return f;
}

const std::array<quad::Coeffs, 3> kColour{quad::coefficients({0.1, 0.9, 0.3, 0.7, 0.5, 0.2}),
                                          quad::linear_coefficients(0, 1, 0.5),
                                          quad::coefficients({1, 0, 1, 0, 1, 0})};

// Covered pixels (x, y) of the walker for one triangle, in emission order.
std::vector<std::pair<int, int>> Walk(const QuadModel& m, const quad::SubpixelTri& tri) {
  std::vector<std::int64_t> out;
  (void)m.walk(quad_program(tri, kColour, m.formats()), out);
  std::vector<std::pair<int, int>> pixels;
  for (std::size_t i = 0; i < out.size(); i += 5) {
    pixels.emplace_back(static_cast<int>(out[i]), static_cast<int>(out[i + 1]));
  }
  return pixels;
}

// The walker covers exactly the reference's pixels, in the same (row-major) order, on meshes
// whose pixel centres lie on shared edges and vertices: so a mesh has no holes and no doubles.
TEST(QuadCoverage, WalkerEqualsReferenceOnMeshes) {
  for (const int s : {1, 2, 4, 8}) {
    const QuadModel m(Formats(24, s));
    const std::vector<std::vector<quad::SubpixelTri>> meshes{
        quad::grid_mesh(12, 9, 3.5, 7.5, 9, 7, 0, 1, s, false),
        quad::grid_mesh(10, 10, 100.25, 50.75, 13.5, 11.25, 2.5, 7, s, true),
        quad::fan_mesh(600.5, 400.5, 90, 17, 0.3, 0, 3, s)};
    for (const auto& mesh : meshes) {
      std::map<std::pair<int, int>, int> count;
      for (const auto& tri : mesh) {
        const auto got = Walk(m, tri);
        ASSERT_EQ(got, quad::raster(tri, 2048, 2048)) << "S=" << s;
        for (const auto& p : got) ++count[p];
      }
      for (const auto& [p, n] : count) ASSERT_EQ(n, 1) << "pixel " << p.first << "," << p.second;
    }
  }
}

TEST(QuadCoverage, WalkerEqualsReferenceOnRandomTriangles) {
  const QuadModel m(Formats(24));
  for (std::uint64_t i = 0; i < 3000; ++i) {
    Rng rng(5, kStimulusStream, i);
    const quad::SubpixelTri tri = random_triangle(rng, 4);
    ASSERT_EQ(Walk(m, tri), quad::raster(tri, 2048, 2048)) << "triangle " << i;
  }
  // Slivers sharing an apex.
  for (const auto& tri : quad::sliver_fan(300.5, 10.5, 100, 700, 900.5, 40, 9, 4)) {
    ASSERT_EQ(Walk(m, tri), quad::raster(tri, 2048, 2048));
  }
}

// With 40 guard bits the accumulators follow the exact polynomial to far below an LSB.
TEST(QuadSetup, ChannelsFollowTheExactQuadratic) {
  const QuadFormats f = Formats(40);
  const QuadModel m(f);
  const quad::SubpixelTri tri = quad::quantize({10.3, 20.7}, {500.1, 60.2}, {200.9, 700.4}, 4);
  const QuadProgram p = quad_program(tri, kColour, f);
  std::vector<std::int64_t> out;
  std::vector<std::int64_t> acc;
  (void)m.walk(p, out, &acc);
  const auto v = quad::to_pixels(tri);
  for (std::size_t n = 0; n < out.size() / 5; n += 97) {
    const int x = static_cast<int>(out[5 * n]);
    const int y = static_cast<int>(out[5 * n + 1]);
    for (int ch = 0; ch < 3; ++ch) {
      const quad::ScreenPoly poly = quad::screen_poly(kColour[ch], v[0], v[1], v[2], p.x0, p.y0);
      EXPECT_NEAR(fx::to_real(acc[3 * n + ch], f.acc), quad::eval_poly(poly, x - p.x0, y - p.y0),
                  1e-6 / 256);
    }
  }
}

// A sliver's polynomial has terms far outside the accumulator's range (its (s, t) change by
// hundreds per pixel); the setup's words wrap and the walker's modular sums still give the
// right values at the covered pixels.
TEST(QuadSetup, SliversWrapBackIntoRange) {
  const QuadFormats f = Formats(40, 8);
  const QuadModel m(f);
  // 0.2 pixels across, 900 long at slope 1/2: coefficients up to 79 (S2.x holds +-4), with
  // about two covered pixels per row, so the x terms matter as well as the y terms.
  const quad::SubpixelTri tri = quad::quantize({100.2, 100.3}, {900.7, 500.4}, {100.11, 100.48}, 8);
  const QuadProgram p = quad_program(tri, kColour, f);
  std::vector<std::int64_t> out;
  std::vector<std::int64_t> acc;
  ASSERT_EQ(m.walk(p, out, &acc), 187u);
  const auto v = quad::to_pixels(tri);
  for (std::size_t n = 0; n < out.size() / 5; ++n) {
    const double x = static_cast<double>(out[5 * n]) + 0.5;
    const double y = static_cast<double>(out[5 * n + 1]) + 0.5;
    const quad::St st = quad::st_at(v[0], v[1], v[2], {x, y});
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(fx::to_real(acc[3 * n + ch], f.acc), quad::eval_st(kColour[ch], st), 1e-6);
    }
  }
}

// docs/quad.md: the guard bits the bound asks for keep every pixel of a 1024 x 1024 box within
// half an output LSB of the exact quadratic.
TEST(QuadSetup, GuardBitBound) {
  EXPECT_EQ(quad_guard_bits_needed(1024, 1024), 22);
  EXPECT_EQ(quad_guard_bits_needed(2048, 2048), 24);
  EXPECT_EQ(quad_guard_bits_needed(1, 1), 0);
  const QuadFormats f = Formats(22);
  const QuadModel m(f);
  const quad::SubpixelTri tri = quad::quantize({0, 0}, {1024, 0}, {0, 1024}, 4);
  const QuadProgram p = quad_program(tri, kColour, f);
  std::vector<std::int64_t> out;
  std::vector<std::int64_t> acc;
  (void)m.walk(p, out, &acc);
  const auto v = quad::to_pixels(tri);
  double worst = 0;
  for (int ch = 0; ch < 3; ++ch) {
    const quad::ScreenPoly poly = quad::screen_poly(kColour[ch], v[0], v[1], v[2], p.x0, p.y0);
    for (std::size_t n = 0; n < out.size() / 5; ++n) {
      const double exact = quad::eval_poly(poly, static_cast<double>(out[5 * n] - p.x0),
                                           static_cast<double>(out[5 * n + 1] - p.y0));
      worst = std::max(worst, std::abs(fx::to_real(acc[3 * n + ch], f.acc) - exact) * 256);
    }
  }
  EXPECT_LE(worst, 0.5);
}

// `phongsim analyze quad`'s figures: random triangles drift by at most half an output LSB with
// the analytic guard bits, and by more with three fewer (the bound is within a bit or two of
// tight); the default configuration's output is then within the rounding's half LSB plus the
// drift bound for its 24 guard bits over 1024-pixel boxes (1/8 LSB) of direct evaluation.
TEST(QuadAnalysis, DriftBoundAndOutputError) {
  const fx::Format out{false, 0, 8};
  for (const int size : {16, 64, 256}) {
    const int g = quad_guard_bits_needed(size, size);
    EXPECT_LE(quad_drift(size, g, out, 20, 1), 0.5) << "size " << size;
    EXPECT_GT(quad_drift(size, g - 3, out, 20, 1), 0.5) << "size " << size;
  }
  const auto formats = [](const char* name) {
    return QuadFormats::from_config(
        Config::load(std::string(PHONGSIM_SOURCE_DIR) + "/configs/quad/" + name + ".toml"));
  };
  const QuadOutputError fine = quad_output_error(formats("default"), QuadMode::quadratic, 100, 1);
  EXPECT_GT(fine.pixels, 5000u);
  EXPECT_LE(fine.max, 0.5 + 0.125);
  const QuadOutputError narrow =
      quad_output_error(formats("narrow_quad"), QuadMode::quadratic, 100, 1);
  EXPECT_GT(narrow.max, 1.0);  // 8 guard bits are too few for the larger triangles
}

// The RTL needs exactly one cycle per row of a program's row range plus one per covered pixel:
// stream triangles without stalls and count the cycles from the first output to the last.
TEST(QuadRtl, CycleCostIsOnePerRowPlusOnePerPixel) {
  const Config cfg = Config::load(std::string(PHONGSIM_SOURCE_DIR) + "/configs/quad/default.toml");
  const auto model = make_model(find_pipeline("quad"), cfg);
  const auto& qm = dynamic_cast<const QuadModel&>(*model);
  const RtlPlugin plugin =
      locate_rtl(rtl_design(find_pipeline("quad"), cfg), *model, RtlBuild::never, stderr);
  auto dut = RtlLibrary::open(plugin)->create(*model);
  std::vector<std::int64_t> words;
  std::uint64_t rows = 0;
  std::uint64_t pixels = 0;
  std::int64_t first_lead = -1;  // empty rows before the first pixel of the first triangle
  std::int64_t last_trail = 0;   // empty rows after the last pixel of the last triangle
  for (std::uint64_t i = 0; i < 300; ++i) {
    Rng rng(11, kStimulusStream, i);
    const QuadProgram p = quad_program(random_triangle(rng, 4), kColour, qm.formats());
    std::vector<std::int64_t> out;
    const std::size_t n = qm.walk(p, out);
    if (n == 0) continue;  // a program without pixels costs its rows too; keep the count simple
    const auto w = QuadModel::words(p);
    words.insert(words.end(), w.begin(), w.end());
    pixels += n;
    rows += static_cast<std::uint64_t>(p.y1 - p.y0 + 1);
    if (first_lead < 0) first_lead = out[1] - p.y0;
    last_trail = p.y1 - out[out.size() - 4];
  }
  const HarnessResult r = stream_vectors(*dut, qm.inputs().size(), qm.outputs().size(), words,
                                         [](std::span<const std::int64_t>) {});
  ASSERT_EQ(r.outputs, pixels);
  // One cycle per covered pixel and one per row (its span set-up), back to back across
  // triangles. Outside the first-to-last output window: the first triangle's rows up to and
  // including its first non-empty one, and the last triangle's empty rows after its last pixel.
  EXPECT_EQ(r.last_output_cycle - r.first_output_cycle + 1,
            pixels + rows - static_cast<std::uint64_t>(first_lead + 1 + last_trail));
}

std::string ErrorOf(const std::string& toml) {
  try {
    (void)make_model(find_pipeline("quad"), Config::parse(toml, "mine.toml"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(QuadConfig, RefusesBadValues) {
  const std::string ok =
      "pipeline = \"quad\"\n[param]\nsub_bits = 4\n[mode]\nout_round = \"half_even\"\n"
      "[format]\nacc = \"S2.32\"\nout = \"0.8\"\n[setup]\nmode = \"linear\"\n";
  EXPECT_EQ(ErrorOf(ok), "");
  std::string bad = ok;
  bad.replace(bad.find("S2.32"), 5, "2.32");
  EXPECT_EQ(ErrorOf(bad), "mine.toml: [format] acc must be signed (got 2.32)");
  bad = ok;
  bad.replace(bad.find("sub_bits = 4"), 12, "sub_bits = 9");
  EXPECT_EQ(ErrorOf(bad), "mine.toml:3: [param] sub_bits = 9 must be an integer in [1, 8]");
  bad = ok;
  bad.replace(bad.find("linear"), 6, "cubic");
  EXPECT_EQ(ErrorOf(bad),
            "mine.toml:10: [setup] mode = 'cubic' (expected one of: quadratic, linear)");
  EXPECT_THROW(
      (void)quad_program(quad::quantize({0, 0}, {3000, 0}, {0, 10}, 4), kColour, Formats(24)),
      Error);
}

}  // namespace
}  // namespace phongsim
