// Lyon's shading pipeline from triangle to pixels: the quadratic walker interpolating the
// normal, Lyon's unit behind it (docs/shade_lyon.md). The entry composes the walker's and Lyon's
// entries: their cycle models, input contracts, coverpoints and stage values.
#include "sim/pipelines/shade_lyon.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "base/error.h"
#include "ref/lyon_float.h"
#include "ref/quad_float.h"
#include "sim/pipelines/lyon.h"
#include "sim/pipelines/native_walker.h"
#include "sim/pipelines/quad.h"

namespace phongsim {

ShadeLyonTriangle random_shade_lyon_triangle(Rng& rng, const ShadeLyonFormats& f) {
  ShadeLyonTriangle t;
  t.tri = random_triangle(rng, f.walker.sub_bits);
  const LyonPixel p = random_lyon_pixel(rng, f.lyon);
  const Vec3 tilt = random_lyon_pixel(rng, f.lyon).l;  // a random unit vector
  const Vec3 n[3] = {p.n0, p.n1, normalized((p.n0 + p.n1) * 0.5 + tilt * 0.25)};
  for (int v = 0; v < 3; ++v) t.normal[v] = {n[v].x, n[v].y, n[v].z};
  t.v = {p.v.x, p.v.y, p.v.z};
  t.l = {p.l.x, p.l.y, p.l.z};
  t.shin = p.shin;
  return t;
}

namespace {

std::vector<PortBinding> ports() {
  std::vector<PortBinding> p =
      walker_program_ports({"in_nx_i", "in_ny_i", "in_nz_i"}, {"nx", "ny", "nz"});
  p.insert(p.end(), {{"in_v_i", true, {"v_x", "v_y", "v_z"}},
                     {"in_l_i", true, {"l_x", "l_y", "l_z"}},
                     {"in_shin_i", true, {"shin"}},
                     {"in_tri_i", true, {"tri"}},
                     {"out_x_o", false, {"x"}},
                     {"out_y_o", false, {"y"}},
                     {"out_tri_o", false, {"tri"}},
                     {"out_spec_o", false, {"spec"}},
                     {"out_diff_o", false, {"diff"}}});
  return p;
}

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const ShadeLyonFormats formats = ShadeLyonFormats::from_config(cfg);
  cfg.check_all_used();
  return std::make_unique<ShadeLyonModel>(formats);
}

// The walker's contract on the program, then Lyon's on every pixel it feeds the unit.
InputContract contract(const PipelineModel& model, const Config& cfg) {
  const auto m =
      std::shared_ptr<const ShadeLyonModel>(dynamic_cast<ShadeLyonModel*>(model.clone().release()));
  InputContract walker = quad_pipeline().contract(m->walker(), cfg);
  InputContract lyon = lyon_contract(m->formats().lyon);
  std::vector<std::string> clauses = walker.clauses();
  const int first_lyon = static_cast<int>(clauses.size());
  for (const std::string& c : lyon.clauses()) clauses.push_back("every pixel: " + c);
  const std::size_t width = m->lyon().inputs().size();
  return InputContract(std::move(clauses), [m, walker, lyon, first_lyon,
                                            width](std::span<const std::int64_t> in) mutable {
    if (const int w = walker.check(in); w != InputContract::kIn) return w;
    std::vector<std::int64_t> walked, lyon_in;
    const std::size_t n = m->pixels(in, walked, lyon_in);
    for (std::size_t p = 0; p < n; ++p) {
      const int l = lyon.check(std::span<const std::int64_t>(lyon_in).subspan(p * width, width));
      if (l != InputContract::kIn) return first_lyon + l;
    }
    return InputContract::kIn;
  });
}

}  // namespace

ShadeLyonError shade_lyon_error(const ShadeLyonModel& model, std::uint64_t triangles,
                                std::uint64_t seed) {
  const ShadeLyonFormats& f = model.formats();
  const lyon::DatapathParams params{f.lyon.halfway, f.lyon.norm, f.lyon.h_norm, f.lyon.k};
  const double spec_lsb = std::ldexp(1.0, -f.lyon.spec.frac_bits);
  const double diff_lsb = std::ldexp(1.0, -f.lyon.diff.frac_bits);
  // contract() needs a Config only for the walker's entry, which reads none of it.
  InputContract check = contract(model, Config{});
  LyonModel lyon = model.lyon();
  ShadeLyonError e;
  double spec_sum = 0, diff_sum = 0;
  for (std::uint64_t i = 0; i < triangles; ++i) {
    Rng rng(seed, kStimulusStream, i);
    const ShadeLyonTriangle t = random_shade_lyon_triangle(rng, f);
    const std::vector<std::int64_t> words = model.words(t);
    if (check.check(words) != InputContract::kIn) {
      ++e.out_of_contract;
      continue;
    }
    ++e.triangles;
    std::vector<std::int64_t> walked, lyon_in, shaded;
    const std::size_t n = model.pixels(words, walked, lyon_in);
    (void)lyon.eval_batch(lyon_in, shaded);
    const auto v = quad::to_pixels(t.tri);
    const auto vec = [](const std::array<double, 3>& a) { return Vec3{a[0], a[1], a[2]}; };
    const Vec3 n0 = vec(t.normal[0]), n1 = vec(t.normal[1]), n2 = vec(t.normal[2]);
    const double shin = f.lyon.arrangement == 8 ? t.shin * t.shin : t.shin;
    for (std::size_t p = 0; p < n; ++p) {
      const quad::St st = quad::st_at(
          v[0], v[1], v[2],
          {static_cast<double>(walked[5 * p]) + 0.5, static_cast<double>(walked[5 * p + 1]) + 0.5});
      const Vec3 np = n0 + (n1 + n0 * -1.0) * st.s + (n2 + n0 * -1.0) * st.t;  // interpolated
      const lyon::DatapathOut ref = lyon::datapath(np, np, 0, vec(t.v), vec(t.l), shin, params);
      const double ds = std::abs(fx::to_real(shaded[2 * p], f.lyon.spec) - ref.spec) / spec_lsb;
      const double dd = std::abs(fx::to_real(shaded[2 * p + 1], f.lyon.diff) - ref.diff) / diff_lsb;
      e.spec_max = std::max(e.spec_max, ds);
      if (shin <= 256) e.spec_max_low_n = std::max(e.spec_max_low_n, ds);
      e.diff_max = std::max(e.diff_max, dd);
      spec_sum += ds;
      diff_sum += dd;
      ++e.pixels;
    }
  }
  if (e.pixels > 0) {
    e.spec_mean = spec_sum / static_cast<double>(e.pixels);
    e.diff_mean = diff_sum / static_cast<double>(e.pixels);
  }
  return e;
}

namespace {

// The input of `t` with `n` as every vertex normal.
ShadeLyonTriangle flat(const quad::SubpixelTri& tri, Vec3 n, Vec3 v, Vec3 l, double shin) {
  ShadeLyonTriangle t{.tri = tri, .v = {v.x, v.y, v.z}, .l = {l.x, l.y, l.z}, .shin = shin};
  for (auto& vn : t.normal) vn = {n.x, n.y, n.z};
  return t;
}

Stimulus make_stimulus(const PipelineModel& model, const Config& cfg) {
  const auto& m = dynamic_cast<const ShadeLyonModel&>(model);
  const ShadeLyonFormats f = m.formats();
  const int s = f.walker.sub_bits;
  const auto tri = [s](double x0, double y0, double x1, double y1, double x2, double y2) {
    return quad::quantize({x0, y0}, {x1, y1}, {x2, y2}, s);
  };
  const Vec3 z{0, 0, 1}, x{1, 0, 0}, y{0, 1, 0};
  const Vec3 tilted = normalized(Vec3{0.3, -0.2, 1});
  const double shin_max = fx::to_real(f.lyon.shin.max_raw(), f.lyon.shin);
  std::vector<std::vector<std::int64_t>> directed;
  const auto add = [&](ShadeLyonTriangle t) {
    t.id = static_cast<std::int64_t>(directed.size());
    directed.push_back(m.words(t));
  };
  // Normal, V and L all z: the highlight's peak (spec and diff 1) on every pixel.
  add(flat(tri(20.5, 20.5, 30.5, 20.5, 20.5, 30.5), z, z, z, 1));
  // One pixel; the opposite winding; a zero normal (every component encoded 1/2).
  add(flat(tri(10.2, 10.2, 10.9, 10.3, 10.4, 10.9), tilted, z, tilted, 8));
  add(flat(tri(20.5, 20.5, 20.5, 30.5, 30.5, 20.5), Vec3{0, 0, 0}, z, z, 1));
  // Normals a quarter turn apart across the triangle, the highlight inside it; the largest
  // shininess; components of -1 and +1 (the walker's clamp corners).
  ShadeLyonTriangle fan = flat(tri(40, 40, 104, 44, 60, 100), z, z, tilted, 16);
  fan.normal[1] = {x.x, x.y, x.z};
  fan.normal[2] = {y.x, y.y, y.z};
  add(fan);
  fan.shin = shin_max;
  add(fan);
  ShadeLyonTriangle corners = flat(tri(300, 300, 340, 310, 310, 350), x * -1.0, z, x, 4);
  corners.normal[1] = {0, -1, 0};
  corners.normal[2] = {0, 0, -1};
  add(corners);
  // A 256-pixel right triangle, a sliver, a degenerate triangle, the screen's far corner.
  add(flat(tri(0, 0, 256, 0, 0, 256), tilted, z, z, 32));
  add(flat(tri(100, 100, 900, 103, 100, 101), z, tilted, z, 64));
  add(flat(tri(5, 5, 10, 10, 15, 15), z, z, z, 1));
  add(flat(tri(2040, 2040, 2048, 2047, 2043, 2048), tilted, tilted, z, 2));

  // g2 lengthens N' = (0.95, 0, 0) just past 1, and V = L = (-2, 0, 0), the format's corner:
  // halfway's projection (H·N)N falls below -2 (r.low).
  const Vec3 corner{fx::to_real(f.lyon.vec.min_raw(), f.lyon.vec), 0, 0};
  add(flat(tri(500, 500, 504, 500, 500, 504), Vec3{0.95, 0, 0}, corner, corner, 1));
  // Lyon's directed pixels (comparator ties, saturations), each as a flat triangle whose normal
  // is the N' the LIRP gave it, where the walker's [-1, 1] holds it.
  const Stimulus lyon = lyon_pipeline().make_stimulus(m.lyon(), cfg);
  std::vector<std::int64_t> px(m.lyon().inputs().size());
  const auto vec_real = [&](std::size_t at) {
    return Vec3{fx::to_real(px[at], f.lyon.vec), fx::to_real(px[at + 1], f.lyon.vec),
                fx::to_real(px[at + 2], f.lyon.vec)};
  };
  for (std::uint64_t i = 0; i < lyon.directed_count(); ++i) {
    lyon.vector(0, i, px);
    const LyonStages st = m.lyon().stages({px[0], px[1], px[2]}, {px[3], px[4], px[5]}, px[6],
                                          {px[7], px[8], px[9]}, {px[10], px[11], px[12]}, px[13]);
    const auto real = [](const fx::Fixed& x) { return fx::to_real(x.raw, x.fmt); };
    const Vec3 np{real(st.np[0]), real(st.np[1]), real(st.np[2])};
    if (std::max({std::abs(np.x), std::abs(np.y), std::abs(np.z)}) > 1) continue;
    const double at = 4.0 * static_cast<double>(i % 400);
    add(flat(tri(at, 600, at + 3, 600, at, 603), np, vec_real(7), vec_real(10),
             fx::to_real(px[13], f.lyon.shin)));
  }

  // Random: three quarters through the setup, one quarter arbitrary words over a small box.
  const FieldRandom bits(model.inputs());
  auto random = [m = std::shared_ptr<const ShadeLyonModel>(
                     dynamic_cast<ShadeLyonModel*>(model.clone().release())),
                 bits](std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) {
    Rng rng(seed, kStimulusStream, index);
    if (rng.below(4) == 0) {
      bits(rng, in);
      in[0] = static_cast<std::int64_t>(rng.below(2016));  // box up to 32 x 32 pixels
      in[1] = static_cast<std::int64_t>(rng.below(2016));
      in[2] = in[0] + static_cast<std::int64_t>(rng.below(32));
      in[3] = in[1] + static_cast<std::int64_t>(rng.below(32));
      return;
    }
    ShadeLyonTriangle t = random_shade_lyon_triangle(rng, m->formats());
    t.id = static_cast<std::int64_t>(index & 0xffff);  // consecutive programs differ
    const auto w = m->words(t);
    std::copy(w.begin(), w.end(), in.begin());
  };
  return Stimulus(model, std::move(directed), random);
}

int lyon_latency(const Config& cfg) { return LyonModel(LyonFormats::from_config(cfg)).latency(); }
// The walker's 4 cycles to a first pixel, then Lyon's unit.
int latency(const Config& cfg) { return 4 + lyon_latency(cfg); }

// The walker's cycles: Lyon's unit takes a pixel every clock, so it delays the walker's pixels
// by its latency and adds nothing else.
FrameCycles cycles(const Config& cfg, std::span<const std::int64_t> in,
                   std::span<const std::int64_t> out, std::span<const std::uint32_t> counts,
                   std::vector<FrameCycles>* per_vector) {
  FrameCycles c = walker_cycles(in, out, 5, counts, per_vector);
  if (c.outputs == 0) return c;
  const auto lyon = static_cast<std::uint64_t>(lyon_latency(cfg));
  c.cycles += lyon;
  c.fill_cycles += lyon;
  return c;
}

// Per pixel: the walker's encoded components (c_x, c_y, c_z) and Lyon's stage values.
std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  const auto& m = dynamic_cast<const ShadeLyonModel&>(model);
  std::vector<std::int64_t> walked, lyon_in;
  const std::size_t n = m.pixels(in, walked, lyon_in);
  LyonModel lyon = m.lyon();
  const std::size_t width = lyon.inputs().size();
  std::vector<StageValue> s;
  for (std::size_t p = 0; p < n; ++p) {
    const std::string at = fmt::format("pixel({},{}).", walked[5 * p], walked[5 * p + 1]);
    for (std::size_t c = 0; c < 3; ++c) {
      s.push_back(
          {at + "c_" + "xyz" [c], fx::Fixed { walked[5 * p + 2 + c], m.formats().walker.out }});
    }
    for (StageValue& v : lyon_pipeline().stages(
             lyon, std::span<const std::int64_t>(lyon_in).subspan(p * width, width))) {
      s.push_back({at + v.name, v.value});
    }
  }
  return s;
}

// The walker's coverpoints on the program ("walker." + quad's) and Lyon's on every pixel it
// feeds the unit ("lyon." + Lyon's), with both entries' waivers, and the outcomes the composition
// rules out waived: with a = 0 and N0 = N1, N' is N0 requantized.
CoverpointSampler coverpoints(const PipelineModel& model, const Config& cfg) {
  const auto& m = dynamic_cast<const ShadeLyonModel&>(model);
  CoverpointSampler walker = quad_pipeline().coverpoints(m.walker(), cfg);
  CoverpointSampler lyon = lyon_pipeline().coverpoints(m.lyon(), cfg);
  for (const char* side : {"np.low", "np.high"}) {
    waive_lyon_outcome(lyon, side, "a = 0 and N0 = N1 = N' in [-1, 1]: the LIRP passes N'");
  }
  CoverpointSampler c;
  c.points = walker.points.prefixed("walker.");
  c.points.merge(lyon.points.prefixed("lyon."));
  c.line_waivers = walker.line_waivers;
  c.line_waivers.insert(c.line_waivers.end(), lyon.line_waivers.begin(), lyon.line_waivers.end());
  const std::size_t offset = walker.points.names().size();
  c.sample = [walker, lyon, offset](PipelineModel& model, std::span<const std::int64_t> in,
                                    Coverpoints& cp) {
    auto& m = dynamic_cast<ShadeLyonModel&>(model);
    QuadModel w = m.walker();
    LyonModel l = m.lyon();
    Coverpoints wp = walker.points, lp = lyon.points;  // counts 0: copies of the declarations
    walker.sample(w, in.first(ShadeLyonModel::kProgramFields), wp);
    std::vector<std::int64_t> walked, lyon_in;
    const std::size_t n = m.pixels(in, walked, lyon_in);
    const std::size_t width = l.inputs().size();
    for (std::size_t p = 0; p < n; ++p) {
      lyon.sample(l, std::span<const std::int64_t>(lyon_in).subspan(p * width, width), lp);
    }
    for (std::size_t i = 0; i < wp.counts().size(); ++i) {
      if (wp.counts()[i] != 0) cp.hit(i, wp.counts()[i]);
    }
    for (std::size_t i = 0; i < lp.counts().size(); ++i) {
      if (lp.counts()[i] != 0) cp.hit(offset + i, lp.counts()[i]);
    }
  };
  return c;
}

ModelError float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  const ShadeLyonModel model(ShadeLyonFormats::from_config(cfg));
  // About 64 pixels a triangle: `samples` pixels or so.
  const ShadeLyonError s = shade_lyon_error(model, std::max<std::uint64_t>(1, samples / 64), seed);
  ModelError e;
  e.max_lsb = s.spec_max;
  e.mean_lsb = s.spec_mean;
  e.max_abs = s.spec_max * std::ldexp(1.0, -model.formats().lyon.spec.frac_bits);
  e.samples = s.pixels;
  return e;
}

// configs/shade_lyon/default.toml by hand: the walker of its normal components (acc S2.35, out
// U1.11), each pixel's N' = 2c - 1 (c's raw value less 2^10, read as S1.10) into lyon/default's
// native kernel (the same Lyon formats) with the program's V, L and shininess. Laid out as the
// model's eval_batch: programs walked until they have 512 pixels, then Lyon's kernel on them all.
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  constexpr std::size_t kProgram = ShadeLyonModel::kProgramFields, kStride = kProgram + 8;
  constexpr std::int64_t kOne = std::int64_t{1} << 10;
  constexpr std::size_t kGroup = 512;
  const std::size_t programs = in.size() / kStride;
  std::vector<std::int64_t> walked, lyon_in, shaded;
  std::vector<std::size_t> sizes;
  std::size_t pixels = 0;
  for (std::size_t first = 0; first < programs;) {
    walked.clear();
    sizes.clear();
    std::size_t end = first;
    for (; end < programs && walked.size() < 5 * kGroup; ++end) {
      const auto program = in.subspan(end * kStride, kProgram);
      fx::on_kernel_isa([&] {
        sizes.push_back(native_walker<38, 35, 12, 11, kProgram, false>(program, walked));
      });
    }
    const std::size_t n = walked.size() / 5;
    lyon_in.resize(14 * n);
    for (std::size_t k = first, p = 0; k < end; ++k) {
      const std::int64_t* w = in.data() + k * kStride;
      for (std::size_t i = 0; i < sizes[k - first]; ++i, ++p) {
        std::int64_t* v = lyon_in.data() + 14 * p;
        for (int c = 0; c < 3; ++c) v[c] = v[3 + c] = walked[5 * p + 2 + c] - kOne;
        v[6] = 0;                             // a
        std::copy_n(w + kProgram, 7, v + 7);  // v, l, shin
      }
    }
    shaded.clear();
    (void)lyon_pipeline().native(lyon_in, shaded);
    const std::size_t base = out.size();
    out.resize(base + 5 * n);
    for (std::size_t k = first, p = 0; k < end; ++k) {
      for (std::size_t i = 0; i < sizes[k - first]; ++i, ++p) {
        std::int64_t* o = out.data() + base + 5 * p;
        o[0] = walked[5 * p];
        o[1] = walked[5 * p + 1];
        o[2] = in[k * kStride + kStride - 1];
        o[3] = shaded[2 * p];
        o[4] = shaded[2 * p + 1];
      }
    }
    pixels += n;
    first = end;
  }
  return pixels;
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  const std::uint64_t triangles = std::max<std::uint64_t>(1, samples / 64);
  out.print(
      "The composed pipeline against the float datapath (ref/lyon_float.h) on the normal\n"
      "interpolated exactly at each pixel centre: {} random triangles, errors in LSBs\n",
      triangles);
  out.table("Composed pipeline against the float datapath",
            {"config", "triangles", "pixels", "out_of_contract", "spec_max_lsb",
             "spec_max_lsb_n_le_256", "spec_mean_lsb", "diff_max_lsb", "diff_mean_lsb"});
  out.print("  {:<14} {:>9} {:>9} {:>8} {:>9} {:>11} {:>9} {:>9} {:>9}\n", "config", "triangles",
            "pixels", "outside", "spec max", "max n<=256", "spec mean", "diff max", "diff mean");
  for (const Config& cfg : configs) {
    const ShadeLyonModel model(ShadeLyonFormats::from_config(cfg));
    const ShadeLyonError e = shade_lyon_error(model, triangles, seed);
    out.print("  {:<14} {:>9} {:>9} {:>8} {:>9.2f} {:>11.2f} {:>9.3f} {:>9.2f} {:>9.3f}\n",
              cfg.name(), e.triangles, e.pixels, e.out_of_contract, e.spec_max, e.spec_max_low_n,
              e.spec_mean, e.diff_max, e.diff_mean);
    out.row({cfg.name(), static_cast<std::int64_t>(e.triangles),
             static_cast<std::int64_t>(e.pixels), static_cast<std::int64_t>(e.out_of_contract),
             e.spec_max, e.spec_max_low_n, e.spec_mean, e.diff_max, e.diff_mean});
  }
}

}  // namespace

const PipelineInfo& shade_lyon_pipeline() {
  static const PipelineInfo info{
      .name = "shade_lyon",
      .summary = "Triangle to pixels: walker interpolating the normal, Lyon's unit behind it",
      .top = "shade_lyon",
      .rtl_files = {"rtl/common", "rtl/lirp/lirp_core.sv", "rtl/lyon/lyon_norm.sv",
                    "rtl/lyon/lyon_x.sv", "rtl/lyon/lyon_shape.sv", "rtl/lyon/lyon_core.sv",
                    "rtl/quad/quad_channel.sv", "rtl/quad/quad_walker_core.sv",
                    "rtl/shade_lyon/shade_lyon.sv"},
      .ports = ports(),
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = true,
      // Vectors are triangle programs, about a hundred pixels each on average.
      .default_vectors = 10000,
      .latency = latency,
      // The walker's row set-up: below one pixel per clock by design.
      .one_per_clock = false,
      .cycles = cycles,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract = contract,
      .float_error = float_error,
      .analyze = analyze,
      .mutants = {{"shade-lyon-decode", "default", "rtl/shade_lyon/shade_lyon.sv",
                   "assign centred = px_c[c*CW+:CW] - CW'(1 << F);",
                   "assign centred = px_c[c*CW+:CW] - CW'((1 << F) - 1);",
                   "the decoded normal one LSB high"},
                  {"shade-lyon-tag", "default", "rtl/quad/quad_walker_core.sv",
                   ".in_data_i  ({tag_q, rgb, y_q, x_q}),",
                   ".in_data_i  ({head[ProgW-1-:TagW], rgb, y_q, x_q}),",
                   "pixels take the waiting program's V, L and shininess"},
                  {"shade-lyon-side", "default", "rtl/lyon/lyon_core.sv",
                   ".in_data_i  ({side_last, spec, diff_last}),",
                   ".in_data_i  ({in_side_i, spec, diff_last}),",
                   "a pixel leaves with the position of the pixel entering the unit"}},
  };
  return info;
}

}  // namespace phongsim
