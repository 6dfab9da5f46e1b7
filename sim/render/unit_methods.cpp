#include "sim/render/unit_methods.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "base/error.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "model/lyon.h"
#include "model/quad.h"
#include "model/quad_setup.h"
#include "model/shade_lyon.h"
#include "model/shade_quad.h"
#include "sim/cosim/harness.h"
#include "sim/pipelines/registry.h"
#include "sim/pipelines/shade_kb.h"

namespace phongsim::shading {

namespace {

// The design of a unit of `cfg`: phongsim's, or the user's `rtl` with top `top`.
RtlDesign unit_design(const Config& cfg, const RtlSources* rtl, const std::string& top) {
  const PipelineInfo& pipeline = find_pipeline(cfg.pipeline());
  return rtl != nullptr ? rtl_design(pipeline, cfg, *rtl, top) : rtl_design(pipeline, cfg);
}

}  // namespace

void build_unit_plugins(std::span<const RtlUnit> units) {
  std::vector<Config> cfgs;
  std::vector<std::unique_ptr<PipelineModel>> owned;
  std::vector<RtlDesign> designs;
  std::vector<const PipelineModel*> models;
  cfgs.reserve(units.size());
  for (const RtlUnit& u : units) {
    cfgs.push_back(Config::load(u.config));
    owned.push_back(make_model(find_pipeline(cfgs.back().pipeline()), cfgs.back()));
    designs.push_back(unit_design(cfgs.back(), u.rtl, u.top));
    models.push_back(owned.back().get());
  }
  (void)build_rtl(designs, models, stderr);
}

Unit::Unit(const std::filesystem::path& config, Backend backend, bool no_build,
           const RtlSources* rtl, const std::string& top)
    : cfg_(Config::load(config)),
      model_(make_model(find_pipeline(cfg_.pipeline()), cfg_)),
      backend_(backend),
      rtl_name_("the RTL of " + cfg_.origin()),
      user_rtl_(rtl != nullptr) {
  if (backend == Backend::rtl) {
    const RtlDesign design = unit_design(cfg_, rtl, top);
    if (rtl != nullptr) rtl_name_ = fmt::format("your RTL ({}) with {}", design.top, cfg_.origin());
    const RtlPlugin plugin =
        locate_rtl(design, *model_, no_build ? RtlBuild::never : RtlBuild::if_missing, stderr);
    library_ = RtlLibrary::open(plugin);
  }
}

std::vector<std::int64_t> Unit::run(const std::vector<std::int64_t>& vectors,
                                    const RenderProgress& progress, std::string_view what) {
  model_->reset();  // the kb engine keeps span state between words
  const std::size_t n_in = model_->inputs().size();
  const std::size_t n_out = model_->outputs().size();
  const std::uint64_t count = vectors.size() / n_in;
  std::vector<std::int64_t> out;
  std::vector<std::uint32_t> counts;
  constexpr std::uint64_t kStep = 4096;
  for (std::uint64_t i = 0; i < count; i += kStep) {
    const std::uint64_t n = std::min(kStep, count - i);
    std::vector<std::uint32_t> step;
    (void)model_->eval_batch(std::span(vectors).subspan(i * n_in, n * n_in), out, &step);
    counts.insert(counts.end(), step.begin(), step.end());
    if (backend_ == Backend::model) progress(what, i, count);
  }
  frame_ = find_pipeline(cfg_.pipeline()).cycles(cfg_, vectors, out, counts, &own_);
  if (backend_ == Backend::model) return out;
  auto dut = library_->create(*model_);
  std::vector<std::int64_t> rtl;
  std::uint64_t outputs = 0;
  const HarnessResult r =
      stream_vectors(*dut, n_in, n_out, vectors, [&](std::span<const std::int64_t> o) {
        rtl.insert(rtl.end(), o.begin(), o.end());
        if (++outputs % 4096 == 0) progress(what, outputs, 0);
      });
  if (r.reason != StopReason::finished || r.inputs != count) {
    const std::string problem =
        fmt::format("{}: {} stopped: {}", what, rtl_name_,
                    r.message.empty() ? "not every input was accepted" : r.message);
    if (user_rtl_) throw DesignFailure(problem);
    throw Error(problem);
  }
  const std::uint64_t measured = r.outputs == 0 ? 0 : r.last_output_cycle + 1;
  if (user_rtl_ && r.outputs == frame_.outputs) {
    frame_.cycles = measured;  // the user's design keeps its own clocks
  } else if (measured != frame_.cycles || r.outputs != frame_.outputs) {
    throw Error(fmt::format(
        "{}: the RTL of {} took {} cycles for {} outputs, the cycle model says {} for {} (a "
        "phongsim bug: please report it)",
        what, cfg_.origin(), measured, r.outputs, frame_.cycles, frame_.outputs));
  }
  if (rtl != out) {  // the frame is a co-simulation too
    std::size_t i = 0;
    while (i < rtl.size() && i < out.size() && rtl[i] == out[i]) ++i;
    throw DesignFailure(
        fmt::format("{}: {} differs from its model at output {} of {} (phongsim cosim "
                    "gives the first mismatch with its stages)",
                    what, rtl_name_, i / n_out, out.size() / n_out));
  }
  return rtl;
}

UnitImage pixel_unit(const Frame& f, Unit& unit, const RenderProgress& progress,
                     std::string_view what) {
  const LyonFormats lf = LyonFormats::from_config(unit.config());
  const auto q = [](double x, fx::Format fmt) {
    return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
  };
  std::vector<std::int64_t> words;
  const std::size_t nl = f.lighting.lights.size();
  words.reserve(f.fragments.size() * nl * 14);
  for (const Fragment& fr : f.fragments) {
    const Vec3 v = f.lighting.v_at(fr.p);
    const double shin =
        lf.arrangement == 8 ? root_shininess(fr.shininess) : std::round(fr.shininess);
    for (const Light& l : f.lighting.lights) {
      const Vec3 ld = Lighting::l_at(l, fr.p);
      for (int rep = 0; rep < 2; ++rep) {
        words.insert(words.end(), {q(fr.n.x, lf.vec), q(fr.n.y, lf.vec), q(fr.n.z, lf.vec)});
      }
      words.push_back(0);
      words.insert(words.end(), {q(v.x, lf.vec), q(v.y, lf.vec), q(v.z, lf.vec)});
      words.insert(words.end(), {q(ld.x, lf.vec), q(ld.y, lf.vec), q(ld.z, lf.vec)});
      words.push_back(q(shin, lf.shin));
    }
  }
  const std::vector<std::int64_t> out = unit.run(words, progress, what);
  if (out.size() != f.fragments.size() * nl * 2) {
    throw Error(fmt::format("{}: the unit returned {} outputs for {} pixels", what, out.size() / 2,
                            f.fragments.size() * nl));
  }
  Image img = blank(f);
  std::vector<Amounts> a(nl);
  for (std::size_t i = 0; i < f.fragments.size(); ++i) {
    for (std::size_t k = 0; k < nl; ++k) {
      a[k] = {fx::to_real(out[2 * (i * nl + k) + 1], lf.diff),
              fx::to_real(out[2 * (i * nl + k)], lf.spec)};
    }
    const Fragment& fr = f.fragments[i];
    img.at(fr.x, fr.y) = to_rgb8(combine(fr, f.lighting.lights, a));
  }
  return {std::move(img), {unit.frame(), f.fragments.size(), {}, {}}};
}

namespace {

// A walker unit's programs, one per triangle (and pass), with the pixels the frame's coverage
// says each emits: the unit must emit exactly those (its pixels come back program by program).
struct TrianglePrograms {
  // The triangle pipelines' `tri` field.
  static constexpr int kTriMask = (1 << ShadeLyonModel::kTriBits) - 1;
  static_assert(ShadeLyonModel::kTriBits == ShadeQuadModel::kTriBits);
  std::vector<std::int64_t> words;
  std::vector<int> tris;
  std::vector<std::size_t> counts;
  std::size_t pixels = 0;

  void add(const std::vector<std::int64_t>& program, const Frame& f, std::size_t t) {
    words.insert(words.end(), program.begin(), program.end());
    tris.push_back(static_cast<int>(t));
    counts.push_back(f.coverage[t].size());
    pixels += counts.back();
  }
  // Every output (`fields` values per pixel); Error when the unit's pixels are not the coverage
  // or, for a numbered pipeline (its pixels' third field the triangle's number, kTriMask bits),
  // a pixel's number is not its program's triangle.
  [[nodiscard]] std::vector<std::int64_t> run(Unit& unit, std::size_t fields, bool numbered,
                                              const RenderProgress& progress,
                                              std::string_view what) const {
    std::vector<std::int64_t> out = unit.run(words, progress, what);
    if (out.size() != fields * pixels) {
      throw Error(fmt::format("{}: the unit emitted {} pixels, coverage says {}", what,
                              out.size() / fields, pixels));
    }
    for (std::size_t k = 0, at = 0; numbered && k < tris.size(); ++k) {
      for (std::size_t i = 0; i < counts[k]; ++i, at += fields) {
        if (out[at + 2] != (tris[k] & kTriMask)) {
          throw Error(fmt::format("{}: a pixel of triangle {} came out numbered {}", what, tris[k],
                                  out[at + 2]));
        }
      }
    }
    return out;
  }
  // The frame's cycles and each program's, by triangle.
  [[nodiscard]] FrameReport frame(const Unit& unit) const {
    FrameReport r{unit.frame(), pixels, {}, {}};
    for (std::size_t k = 0; k < tris.size(); ++k) {
      r.triangles.emplace_back(tris[k], unit.vector_cycles()[k]);
    }
    return r;
  }
};

}  // namespace

UnitImage vertex_unit(bool linear, const Frame& f, Unit& unit, const RenderProgress& progress,
                      std::string_view what) {
  const QuadFormats qf = QuadFormats::from_config(unit.config());
  if (qf.sub_bits != kSubBits) {
    throw Error(fmt::format("{}: the renderer projects with {} subpixel bits; {} has {}", what,
                            kSubBits, unit.config().origin(), qf.sub_bits));
  }
  // The framebuffer's 255 means 1.0, the unit's largest output (255/256 for 0.8) does: colours
  // go in scaled by that top value, so the output's raw bits are the framebuffer value.
  const double top = fx::to_real(qf.out.max_raw(), qf.out);
  // shade_quad (triangle in, pixels out) takes the triangle's number after the walker's program
  // and returns it with every pixel, (x, y, tri, R, G, B); quad, the walker alone, (x, y, R, G, B).
  const bool numbered = unit.config().pipeline() == "shade_quad";
  const std::size_t fields = numbered ? 6 : 5;
  const std::vector<bool>& visible = f.visible;
  TrianglePrograms programs;
  for (std::size_t t = 0; t < visible.size(); ++t) {
    if (!visible[t]) continue;
    const auto c = sample_colours(f, static_cast<int>(t));
    std::array<quad::Coeffs, 3> colour;
    for (int ch = 0; ch < 3; ++ch) {
      quad::Samples r;
      for (int k = 0; k < 6; ++k) r[k] = channel(c[k], ch) * top;
      colour[ch] = linear ? quad::linear_coefficients(r[0], r[2], r[4]) : quad::coefficients(r);
    }
    // Clipped to the image, so the unit emits exactly the triangle's coverage.
    std::vector<std::int64_t> words =
        QuadModel::words(quad_program(f.screen[t], colour, qf, QuadScreen{f.width, f.height}));
    if (numbered) words.push_back(static_cast<std::int64_t>(t) & TrianglePrograms::kTriMask);
    programs.add(words, f, t);
  }
  const std::vector<std::int64_t> out = programs.run(unit, fields, numbered, progress, what);
  Image img = blank(f);
  std::size_t at = 0;
  for (std::size_t k = 0; k < programs.tris.size(); ++k) {
    for (std::size_t i = 0; i < programs.counts[k]; ++i, at += fields) {
      const auto x = static_cast<int>(out[at]);
      const auto y = static_cast<int>(out[at + 1]);
      if (x < 0 || y < 0 || x >= f.width || y >= f.height) continue;
      if (!f.shows(static_cast<std::size_t>(programs.tris[k]), x, y)) continue;
      const double full = static_cast<double>(qf.out.max_raw());
      const std::size_t rgb = at + fields - 3;
      img.at(x, y) =
          to_rgb8({static_cast<double>(out[rgb]) / full, static_cast<double>(out[rgb + 1]) / full,
                   static_cast<double>(out[rgb + 2]) / full});
    }
  }
  return {std::move(img), programs.frame(unit)};
}

UnitImage triangle_lyon_unit(const Frame& f, Unit& unit, const RenderProgress& progress,
                             std::string_view what) {
  const ShadeLyonModel m(ShadeLyonFormats::from_config(unit.config()));
  const ShadeLyonFormats& sf = m.formats();
  if (sf.walker.sub_bits != kSubBits) {
    throw Error(fmt::format("{}: the renderer projects with {} subpixel bits; {} has {}", what,
                            kSubBits, unit.config().origin(), sf.walker.sub_bits));
  }
  const std::vector<Light>& lights = f.lighting.lights;
  const std::size_t nl = lights.size();
  const Fragment material = material_fragment(f);
  const double shin = sf.lyon.arrangement == 8 ? root_shininess(material.shininess)
                                               : std::round(material.shininess);
  TrianglePrograms programs;
  for (std::size_t t = 0; t < f.visible.size(); ++t) {
    if (!f.visible[t]) continue;
    const auto& idx = f.geometry.triangles[t];
    ShadeLyonTriangle in{.tri = f.screen[t]};
    Vec3 centroid{0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const Vec3 n = f.geometry.normals[static_cast<std::size_t>(idx[k])];
      in.normal[k] = {n.x, n.y, n.z};
      centroid = centroid + f.geometry.positions[static_cast<std::size_t>(idx[k])] * (1.0 / 3);
    }
    const Vec3 v = f.lighting.v_at(centroid);
    in.v = {v.x, v.y, v.z};
    in.shin = shin;
    in.id = static_cast<std::int64_t>(t) & TrianglePrograms::kTriMask;
    for (const Light& light : lights) {
      const Vec3 l = Lighting::l_at(light, centroid);
      in.l = {l.x, l.y, l.z};
      programs.add(m.words(in, QuadScreen{f.width, f.height}), f, t);  // clipped to the image
    }
  }
  const std::vector<std::int64_t> out = programs.run(unit, 5, true, progress, what);
  // Each visible pixel's amounts, light by light, from the program of its triangle and light.
  std::vector<Amounts> amounts(f.fragments.size() * nl);
  std::size_t at = 0;
  for (std::size_t k = 0; k < programs.tris.size(); ++k) {
    for (std::size_t i = 0; i < programs.counts[k]; ++i, at += 5) {
      const auto x = static_cast<int>(out[at]);
      const auto y = static_cast<int>(out[at + 1]);
      if (x < 0 || y < 0 || x >= f.width || y >= f.height) continue;
      if (!f.shows(static_cast<std::size_t>(programs.tris[k]), x, y)) continue;
      const int fragment = f.owner[static_cast<std::size_t>(y) * static_cast<std::size_t>(f.width) +
                                   static_cast<std::size_t>(x)];
      if (fragment < 0) continue;
      amounts[static_cast<std::size_t>(fragment) * nl + k % nl] = {
          fx::to_real(out[at + 4], sf.lyon.diff), fx::to_real(out[at + 3], sf.lyon.spec)};
    }
  }
  Image img = blank(f);
  std::vector<Amounts> a(nl);
  for (std::size_t i = 0; i < f.fragments.size(); ++i) {
    std::copy_n(amounts.begin() + static_cast<std::ptrdiff_t>(i * nl), nl, a.begin());
    const Fragment& fr = f.fragments[i];
    img.at(fr.x, fr.y) = to_rgb8(combine(fr, lights, a));
  }
  return {std::move(img), programs.frame(unit)};
}

// The channel values are scaled by the output's top value, like the quadratic unit's (vertex_unit).
UnitImage kb_unit(const Frame& f, Unit& unit, const RenderProgress& progress,
                  std::string_view what) {
  const KbFormats kf = KbFormats::from_config(unit.config());
  const KbSetupOptions so = KbSetupOptions::from_config(unit.config());
  const double top = fx::to_real(kf.out.max_raw(), kf.out);
  const kb::QuadParams ab1 = kb_ab(1), abn = kb_ab(4 * f.material.shininess);
  // shade_kb takes a span's three channel programs side by side in span words (x0, y in the
  // header) and returns (x, y, R, G, B) per pixel; kb, one engine alone, takes the programs one
  // channel after the other and returns each channel's pixels (value, last) in turn.
  const bool colour = unit.config().pipeline() == "shade_kb";
  const std::vector<bool>& visible = f.visible;
  std::vector<std::int64_t> words;
  struct Placed {
    int tri, y, x0, x1;
  };
  std::vector<Placed> placed;
  for (std::size_t t = 0; t < visible.size(); ++t) {
    if (!visible[t]) continue;
    for (const Span& e : spans_of(f, t)) {
      const int length = e.x1 - e.x0 + 1;
      const double per_pixel = length == 1 ? 0.0 : 1.0 / (length - 1);
      // Per light: the diffuse and specular one-vector angles (the same for every channel).
      std::vector<std::pair<kb::ScanlineAngles, kb::ScanlineAngles>> angles;
      for (const Light& l : f.lighting.lights) {
        const KbLightEnds le = kb_light_ends(f, l, e);
        angles.emplace_back(kb::one_vector(e.n1, e.n2, le.l1, le.l2),
                            kb::one_vector(e.n1, e.n2, le.h1, le.h2));
      }
      std::array<std::vector<std::vector<std::int64_t>>, 3> programs;
      for (int ch = 0; ch < 3; ++ch) {
        KbSpan span;
        span.length = length;
        span.terms.push_back({0, 0, ab1, channel(f.material.ambient, ch) * top});
        for (std::size_t k = 0; k < angles.size(); ++k) {
          const Light& l = f.lighting.lights[k];
          const auto& [d, s] = angles[k];
          const double lc = channel(l.colour, ch) * top;
          span.terms.push_back({d.theta0, d.dtheta * per_pixel, ab1,
                                lc * channel(f.material.diffuse, ch) * std::max(d.scale, 0.0)});
          span.terms.push_back({s.theta0, s.dtheta * per_pixel, abn,
                                lc * channel(f.material.specular, ch) *
                                    std::pow(std::max(s.scale, 0.0), 4 * f.material.shininess)});
        }
        programs[static_cast<std::size_t>(ch)] = kb_program(span, so.policy, kf);
      }
      const auto put = [&words](const std::vector<std::vector<std::int64_t>>& program) {
        for (const auto& w : program) words.insert(words.end(), w.begin(), w.end());
      };
      if (colour) {
        put(shade_kb_span_words(programs, e.x0, e.y));
      } else {
        for (const auto& program : programs) put(program);
      }
      placed.push_back({static_cast<int>(t), e.y, e.x0, e.x1});
    }
  }
  const std::vector<std::int64_t> out = unit.run(words, progress, what);
  std::size_t pixels = 0;
  for (const Placed& p : placed) pixels += static_cast<std::size_t>(p.x1 - p.x0 + 1);
  const std::size_t per_pixel = colour ? 5 : 3 * 2;  // (x, y, R, G, B); 3 x (value, last)
  if (out.size() != per_pixel * pixels) {
    throw Error(fmt::format("{}: the unit emitted {} pixels, the spans have {}", what,
                            out.size() / per_pixel, pixels));
  }
  Image img = blank(f);
  const double full = static_cast<double>(kf.out.max_raw());
  std::size_t at = 0;
  for (const Placed& p : placed) {
    const std::size_t length = static_cast<std::size_t>(p.x1 - p.x0 + 1);
    for (std::size_t i = 0; i < length; ++i) {
      const int x = p.x0 + static_cast<int>(i);
      const std::size_t pixel = at + 5 * i;
      if (colour && (out[pixel] != x || out[pixel + 1] != p.y)) {
        throw Error(fmt::format("{}: span pixel ({}, {}) came out at ({}, {})", what, x, p.y,
                                out[pixel], out[pixel + 1]));
      }
      if (!f.shows(static_cast<std::size_t>(p.tri), x, p.y)) continue;
      const auto value = [&](int ch) {
        const auto c = static_cast<std::size_t>(ch);
        return static_cast<double>(out[colour ? pixel + 2 + c : at + 2 * (c * length + i)]) / full;
      };
      img.at(x, p.y) = to_rgb8({value(0), value(1), value(2)});
    }
    at += per_pixel * length;
  }
  return {std::move(img), {unit.frame(), pixels, {}, {}}};
}

}  // namespace phongsim::shading
