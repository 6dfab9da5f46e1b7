// The Lyon model (model/lyon.h): exact outputs on hand-computed pixels, configuration refusals,
// stage formats, and the accuracy figures docs/lyon.md states (as regression bounds).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "base/error.h"
#include "model/config.h"
#include "model/lyon.h"
#include "model/plan.h"
#include "sim/pipelines/lyon.h"
#include "sim/pipelines/lyon_geometry.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

std::string ConfigPath(const std::string& name) {
  return std::string(PHONGSIM_SOURCE_DIR) + "/configs/lyon/" + name + ".toml";
}

std::unique_ptr<PipelineModel> Load(const std::string& name) {
  return make_model(find_pipeline("lyon"), Config::load(ConfigPath(name)));
}

const LyonModel& AsLyon(const std::unique_ptr<PipelineModel>& m) {
  return dynamic_cast<const LyonModel&>(*m);
}

// Spec and diff of one pixel given as reals (quantized like the stimulus does).
std::pair<std::int64_t, std::int64_t> Shade(const LyonModel& m, Vec3 n, Vec3 v, Vec3 l,
                                            double shin) {
  const auto raw = quantize_lyon_pixel(LyonPixel{n, n, 0, v, l, shin}, m.formats());
  const LyonStages s = m.stages({raw[0], raw[1], raw[2]}, {raw[3], raw[4], raw[5]}, raw[6],
                                {raw[7], raw[8], raw[9]}, {raw[10], raw[11], raw[12]}, raw[13]);
  return {s.spec.raw, s.diff.raw};
}

std::string ErrorOf(const std::string& toml) {
  try {
    (void)make_model(find_pipeline("lyon"), Config::parse(toml, "mine.toml"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kConfigs[] = {"default", "fig7_g1", "fig7_k0", "fig7_k1",      "fig7_k3", "fig7_nonorm",
                          "fig8_k1", "fig8_k2", "halfway", "halfway_fig8", "narrow",  "wide"};

// R exactly on L (N = V = L = +z): D = 0, x = 0, f_k(0) = 1; N·L = 1. Every configuration gives
// exactly 1.0, or its largest value where 1.0 is not representable (narrow: 0.8 -> 255).
TEST(LyonModel, MirrorDirectionGivesExactlyOne) {
  for (const char* name : kConfigs) {
    SCOPED_TRACE(name);
    const auto m = Load(name);
    const LyonFormats& f = AsLyon(m).formats();
    const std::int64_t one_spec = std::min(std::int64_t{1} << f.spec.frac_bits, f.spec.max_raw());
    const std::int64_t one_diff = std::min(std::int64_t{1} << f.diff.frac_bits, f.diff.max_raw());
    const Vec3 up{0, 0, 1};
    const auto [spec, diff] = Shade(AsLyon(m), up, up, up, 64);
    EXPECT_EQ(spec, one_spec);
    EXPECT_EQ(diff, one_diff);
  }
}

// L opposite N: N·L = -1 saturates to 0 in the unsigned diffuse format.
TEST(LyonModel, BacklightClampsDiffuseToZero) {
  const auto m = Load("default");
  const auto [spec, diff] = Shade(AsLyon(m), {0, 0, 1}, {0, 0, 1}, {0, 0, -1}, 1);
  EXPECT_EQ(diff, 0);
  // D = R - L = (0,0,2) saturates to 2047/1024 in S1.10; D·D = 2047²/2^20 rounds to 2095104 in
  // 3.19 (a tie, to even); x/4 = 32736 in 0.16; sq_0 = 32800/65536; sq_0² = 16416.016 -> 16416;
  // sq_0^4 = 4112.016 -> 4112 in 1.16 = 257 in 1.12 (without the saturation it would be 256).
  EXPECT_EQ(spec, 257);
}

// N = V = +z makes R = +z exactly; L = (-1/2, 0, 1) makes D = (1/2, 0, 0): x = n/8.
TEST(LyonModel, ShapeFunctionAtHandComputedPoints) {
  const Vec3 up{0, 0, 1};
  const Vec3 l{-0.5, 0, 1};
  {
    const auto m = Load("default");  // k = 2
    // n = 16: x = 2, x/4 = 1/2, sq_0 = 1/2, sq_0^4 = 1/16 -> 256.
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 16).first, 256);
    // n = 32: x = 4 = 2^k exactly: the comparator zeroes the output.
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 32).first, 0);
    // n = 1: x = 1/8, x/4 = 1/32, sq_0 = 31/32, sq_0² = 961/1024 exactly; sq_0^4 = 923521/2^20 is
    // 57720.0625 in 1.16 -> 57720, which is 3607.5 in 1.12: a tie, to even -> 3608. (Rounding
    // sq_0^4 directly would give 3607: the squarer's rounding is part of the specification.)
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 1).first, 3608);
  }
  {
    const auto m = Load("fig7_k1");  // k = 1: n = 8: x = 1, x/2 = 1/2, sq_0² = 1/4 -> 1024.
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 8).first, 1024);
  }
  {
    const auto m = Load("fig8_k1");  // m = 4: (m|D|)² = 4 = 2x, x = 2, x/2 = 1: zero.
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 4).first, 0);
    // m = 2: x = 1/2, x/2 = 1/4, sq_0 = 3/4, sq_0² = 9/16 -> 2304.
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 2).first, 2304);
  }
  {
    const auto m = Load("fig8_k2");  // even k: m = 4: x = 2, x/4 = 1/2, sq_0^4 = 1/16 -> 256.
    EXPECT_EQ(Shade(AsLyon(m), up, up, l, 4).first, 256);
  }
}

TEST(LyonModel, StageFormatsOfTheDefault) {
  const auto m = Load("default");
  const LyonStages s = AsLyon(m).stages({0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, {0, 0, 0}, 0);
  EXPECT_EQ(s.dd.fmt.str(), "3.19");
  EXPECT_EQ(s.xk.fmt.str(), "13.22");  // 13.0 × 3.19 = 16.19, shifted right by k + 1 = 3
  EXPECT_EQ(s.xf.fmt.str(), "0.16");
  EXPECT_EQ(s.sq[2].fmt.str(), "1.16");
  EXPECT_EQ(AsLyon(m).latency(), 15);
  const auto fig8 = Load("fig8_k2");
  const LyonStages s8 = AsLyon(fig8).stages({0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, {0, 0, 0}, 0);
  EXPECT_EQ(s8.w[0].fmt.str(), "0.9");
  EXPECT_EQ(s8.xk.fmt.str(), "3.17");  // 2 · (0.18 + 0.18 + 0.18) = 2.18 scaled by 2^1
}

constexpr const char* kHead =
    "pipeline = \"lyon\"\n[param]\narrangement = 7\nhalfway = 0\nnorm = 0\nk = 2\n"
    "[mode]\nround = \"half_even\"\n[format]\nvec = \"S1.10\"\na = \"1.10\"\nshin = \"13.0\"\n"
    "np = \"S1.10\"\nn = \"S1.10\"\ndot = \"S1.12\"\nr = \"S1.10\"\nd = \"S1.10\"\n"
    "xf = \"0.16\"\nsq = \"1.16\"\ndiff = \"1.12\"\n";

TEST(LyonConfig, RefusesWhatTheStructureCannotUse) {
  // The minimal head plus what it lacks: a valid configuration.
  EXPECT_EQ(ErrorOf(std::string(kHead) + "dd = \"3.19\"\nspec = \"1.12\"\n"), "");
  EXPECT_EQ(ErrorOf(std::string(kHead) + "dd = \"3.19\"\nspec = \"S1.12\"\n"),
            "mine.toml: [format] spec must be unsigned (got S1.12)");
  EXPECT_EQ(ErrorOf(std::string(kHead) + "spec = \"1.12\"\n"),
            "mine.toml: [format] is missing 'dd' (required by pipeline lyon)");
  EXPECT_EQ(ErrorOf(std::string(kHead) + "dd = \"3.19\"\nspec = \"1.12\"\nw = \"0.9\"\n"),
            "mine.toml:23: [format] w: unknown key for pipeline lyon");
  // 13.0 × 3.50 needs 66 bits.
  EXPECT_NE(ErrorOf(std::string(kHead) + "dd = \"3.50\"\nspec = \"1.12\"\n")
                .find("13.0 * 3.50: the exact result needs 66 bits"),
            std::string::npos);
  std::string bad_k = std::string(kHead) + "dd = \"3.19\"\nspec = \"1.12\"\n";
  bad_k.replace(bad_k.find("k = 2"), 5, "k = 4");
  EXPECT_EQ(ErrorOf(bad_k), "mine.toml:6: [param] k = 4 must be an integer in [0, 3]");
}

// docs/lyon.md, "Normalization": g2 within 0.5 % for lengths 0.80..1.00, float and fixed.
TEST(LyonAnalysis, NormalizationWithinHalfAPercent) {
  const auto m = Load("default");
  for (const LyonNormRow& r : lyon_norm_table(AsLyon(m))) {
    if (r.length < 0.8 - 1e-9) continue;
    EXPECT_LT(std::abs(r.g2 - 1), 0.005) << r.length;
    EXPECT_LT(std::abs(r.fixed - 1), 0.005) << r.length;
  }
}

// docs/lyon.md, "Fixed point against the same datapath in float": the table's figures, from
// the same samples and seed (deterministic), to the printed precision.
TEST(LyonAnalysis, OutputErrorsAreTheDocumentedOnes) {
  struct Row {
    const char* name;
    double spec_max, spec_max_low_n, spec_mean, diff_max;
  };
  const Row rows[] = {
      {"default", 675.47, 113.11, 16.936, 5.69},  {"fig7_g1", 568.16, 122.47, 14.429, 5.54},
      {"fig7_k0", 1192.26, 225.86, 16.857, 5.69}, {"fig7_k1", 779.24, 132.36, 16.938, 5.69},
      {"fig7_k3", 634.81, 105.42, 16.887, 5.69},  {"fig7_nonorm", 382.84, 95.48, 7.345, 3.69},
      {"fig8_k1", 529.16, 125.38, 12.993, 5.69},  {"fig8_k2", 489.05, 122.45, 13.531, 5.69},
      {"halfway", 1141.12, 190.00, 27.980, 5.69}, {"halfway_fig8", 621.29, 142.46, 20.069, 5.69},
      {"narrow", 234.10, 140.90, 9.766, 6.78},    {"wide", 415.54, 113.63, 13.156, 6.23},
  };
  for (const Row& row : rows) {
    SCOPED_TRACE(row.name);
    const auto m = Load(row.name);
    const LyonOutputError e = lyon_output_error(AsLyon(m), 100000, 1);
    EXPECT_NEAR(e.spec_max, row.spec_max, 0.005);
    EXPECT_NEAR(e.spec_max_low_n, row.spec_max_low_n, 0.005);
    EXPECT_NEAR(e.spec_mean, row.spec_mean, 0.0005);
    EXPECT_NEAR(e.diff_max, row.diff_max, 0.005);
  }
}

// The stimulus' block path (vectors(): FieldRandom's fill, then the geometry) makes the vectors
// of its one-at-a-time path (vector()), across the directed vectors' end and in blocks that end
// anywhere, for both arrangements.
TEST(LyonStimulus, VectorsAreOneVectorAtATime) {
  for (const char* name : {"default", "fig8_k2"}) {
    const Config cfg = Config::load(ConfigPath(name));
    const PipelineInfo& lyon = find_pipeline("lyon");
    const auto model = make_model(lyon, cfg);
    const Stimulus stimulus = lyon.make_stimulus(*model, cfg);
    const std::size_t n = model->inputs().size();
    const std::uint64_t d = stimulus.directed_count();
    for (const auto& [first, count] : {std::pair<std::uint64_t, std::size_t>{d - 3, 70},
                                       {d, 1},
                                       {d + 1000, 64},
                                       {d + 77, 1500}}) {
      std::vector<std::int64_t> got(count * n), want(n);
      stimulus.vectors(9, first, count, got);
      for (std::size_t v = 0; v < count; ++v) {
        stimulus.vector(9, first + v, want);
        for (std::size_t i = 0; i < n; ++i) {
          ASSERT_EQ(got[v * n + i], want[i]) << name << " vector " << first + v << " field " << i;
        }
      }
    }
  }
}

// Every configuration's formats, and vector formats at and beyond the block path's widest (22
// fraction bits: a rounding tolerance of 1/16 LSB; 26: the pixel-at-a-time path throughout).
std::vector<LyonFormats> GeometryFormats() {
  std::vector<LyonFormats> all;
  for (const auto& path : pipeline_configs(find_pipeline("lyon"))) {
    all.push_back(AsLyon(Load(path.stem().string())).formats());
  }
  for (const int frac : {22, 26}) {
    LyonFormats f = all.front();
    f.vec = fx::Format{true, 1, frac};
    all.push_back(f);
  }
  return all;
}

// The generators of `count` stimulus vectors after their coin's draw, as the stimulus passes them.
std::vector<std::uint64_t> GeometryStates(std::uint64_t seed, std::size_t count) {
  std::vector<std::uint64_t> states;
  for (std::size_t i = 0; i < count; ++i) {
    Rng rng(seed, kStimulusStream, 1000 + i);
    (void)rng.next();
    states.push_back(rng.state());
  }
  return states;
}

// random_lyon_pixels is quantize_lyon_pixel(random_lyon_pixel(...)) bit for bit, on every
// instruction set, for every configuration's formats and wider ones; it writes the rows it is
// given and no others.
TEST(LyonGeometry, BlockIsPixelAtATime) {
  const fx::Isa chosen = fx::kernel_isa();
  const std::vector<std::uint64_t> states = GeometryStates(3, 40000);
  std::vector<std::uint32_t> rows(states.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<std::uint32_t>(2 * i + 1);
  for (const fx::Isa isa : fx::supported_isas()) {
    fx::set_kernel_isa(isa);
    for (const LyonFormats& f : GeometryFormats()) {
      SCOPED_TRACE(fmt::format("{} vec {}", fx::isa_name(isa), f.vec.str()));
      std::vector<std::int64_t> out(14 * 2 * states.size(), -7);
      random_lyon_pixels(states, rows, f, out);
      for (std::size_t i = 0; i < states.size(); ++i) {
        Rng rng = Rng::from_state(states[i]);
        const auto want = quantize_lyon_pixel(random_lyon_pixel(rng, f), f);
        for (std::size_t k = 0; k < 14; ++k) {
          ASSERT_EQ(out[14 * (2 * i + 1) + k], want[k]) << "pixel " << i << " field " << k;
          ASSERT_EQ(out[14 * 2 * i + k], -7) << "row " << 2 * i << " written";
        }
      }
    }
  }
  fx::set_kernel_isa(chosen);
}

// The block path's sine and cosine within their bound of the library's, on 2^20 + 1 points
// spread over [0, 2π] and at the quadrants' ends.
TEST(LyonGeometry, SinCosWithinBound) {
  using lyon_geometry_detail::kSinCosError;
  const double bound = kSinCosError + 0x1p-53;
  std::vector<double> xs;
  for (int i = 0; i <= (1 << 20); ++i) xs.push_back(2 * std::numbers::pi * i / (1 << 20));
  for (int q = 0; q <= 8; ++q) {
    const double x = q * std::numbers::pi / 4;
    xs.insert(xs.end(), {std::nextafter(x, 0.0), x, std::nextafter(x, 7.0)});
  }
  double worst = 0;
  for (const double x : xs) {
    double s = 0, c = 0;
    lyon_geometry_detail::sincos(x, s, c);
    worst = std::max({worst, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
  }
  EXPECT_LE(worst, bound);
}

// The block path's unrounded geometry against random_lyon_pixel's, on every instruction set
// (FMA contraction included): the largest difference over 200,000 pixels stays 2^10 below the
// bound the rounding check assumes, and few pixels are fragile.
TEST(LyonGeometry, ApproximationWithinBound) {
  using namespace lyon_geometry_detail;
  const fx::Isa chosen = fx::kernel_isa();
  const std::vector<std::uint64_t> states = GeometryStates(5, 200000);
  for (const fx::Isa isa : fx::supported_isas()) {
    fx::set_kernel_isa(isa);
    for (const char* name : {"default", "fig8_k2"}) {
      const LyonFormats f = AsLyon(Load(name)).formats();
      SCOPED_TRACE(fmt::format("{} {}", fx::isa_name(isa), name));
      double worst = 0;
      std::size_t fragile = 0;
      auto chunk = std::make_unique<Chunk>();
      for (std::size_t first = 0; first < states.size(); first += kChunk) {
        const std::size_t count = std::min(kChunk, states.size() - first);
        std::vector<LyonPixel> want;
        std::vector<double> shin;
        for (std::size_t i = 0; i < count; ++i) {
          Rng rng = Rng::from_state(states[first + i]);
          want.push_back(random_lyon_pixel(rng, f));
          shin.push_back(want.back().shin);
        }
        approximate_geometry(&states[first], shin.data(), count, f.arrangement == 8, *chunk);
        for (std::size_t i = 0; i < count; ++i) {
          if (chunk->fragile[i]) {
            ++fragile;
            continue;
          }
          const Vec3 got[4] = {{chunk->n0[0][i], chunk->n0[1][i], chunk->n0[2][i]},
                               {chunk->n1[0][i], chunk->n1[1][i], chunk->n1[2][i]},
                               {chunk->v[0][i], chunk->v[1][i], chunk->v[2][i]},
                               {chunk->l[0][i], chunk->l[1][i], chunk->l[2][i]}};
          const Vec3 exact[4] = {want[i].n0, want[i].n1, want[i].v, want[i].l};
          for (int w = 0; w < 4; ++w) {
            const Vec3 d = got[w] - exact[w];
            worst = std::max({worst, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
          }
        }
      }
      EXPECT_LE(worst, kGeometryError * 0x1p-10);
      EXPECT_LT(fragile, states.size() / 100);
      std::printf("%s %s: largest difference 2^%.1f, %zu fragile of %zu\n", fx::isa_name(isa), name,
                  std::log2(worst), fragile, states.size());
    }
  }
  fx::set_kernel_isa(chosen);
}

// quantize_far against fx::quantize: for values x and every x' within the tolerance of x, either
// `near` is set or x' quantizes to quantize_far(x); and x exactly on a rounding boundary, or
// within the tolerance of one, is near. Formats with and without saturation in reach.
TEST(LyonGeometry, QuantizeFarIsQuantizeAwayFromBoundaries) {
  using lyon_geometry_detail::quantize_far;
  Rng rng(1, 2, 3);
  for (const fx::Format fmt : {fx::Format{true, 1, 10}, fx::Format{true, 0, 7},
                               fx::Format{false, 1, 14}, fx::Format{true, 1, 22}}) {
    SCOPED_TRACE(fmt.str());
    const double scale = std::ldexp(1.0, fmt.frac_bits);
    const double tol = 0x1p-8;
    const auto lo = static_cast<double>(fmt.min_raw()), hi = static_cast<double>(fmt.max_raw());
    const auto q = [fmt](double x) {
      return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
    };
    std::size_t checked = 0;
    for (int k = 0; k < 200000; ++k) {
      // Near half-integers often: a boundary plus a few tolerances either way.
      const double boundary = (std::floor(rng.symmetric() * 2.5 * scale) + 0.5) / scale;
      const double x =
          k % 2 == 0 ? rng.symmetric() * 2.5 : boundary + (rng.symmetric() * 4 * tol) / scale;
      bool near = false;
      const std::int64_t got = quantize_far(x, scale, tol, lo, hi, near);
      if (std::abs(x * scale - std::round(x * scale - 0.5) - 0.5) < tol) {
        ASSERT_TRUE(near) << x;
      }
      if (near) continue;
      ++checked;
      for (const double e : {-tol, -tol / 2, 0.0, tol / 2, tol}) {
        ASSERT_EQ(got, q(x + e / scale)) << x << " + " << e << " LSB";
      }
    }
    EXPECT_GT(checked, 100000U);
  }
}

}  // namespace
}  // namespace phongsim
