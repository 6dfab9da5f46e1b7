// The quadratic colour interpolator's registry entry, stimulus and analysis.
#include "sim/pipelines/quad.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "base/error.h"
#include "model/quad.h"
#include "model/quad_setup.h"
#include "sim/pipelines/guard_tables.h"
#include "sim/pipelines/native_walker.h"

namespace phongsim {

QuadMode quad_mode(const Config& cfg) {
  return cfg.setup("mode", {"quadratic", "linear"}) == "linear" ? QuadMode::linear
                                                                : QuadMode::quadratic;
}

quad::SubpixelTri random_triangle(Rng& rng, int sub_bits) {
  const double max_side = rng.below(128) == 0 ? 1024.0 : 64.0;
  const double w = std::exp(rng.uniform() * std::log(max_side));
  const double h = rng.below(4) == 0 ? std::exp(rng.uniform() * std::log(max_side)) : w;
  const double x = rng.uniform() * (2048 - w);
  const double y = rng.uniform() * (2048 - h);
  std::array<quad::Vertex2, 3> v;
  for (auto& p : v) p = {x + rng.uniform() * w, y + rng.uniform() * h};
  if (rng.below(32) == 0) v[2] = {(v[0].x + v[1].x) / 2, (v[0].y + v[1].y) / 2};  // collinear
  quad::SubpixelTri tri = quad::quantize(v[0], v[1], v[2], sub_bits);
  if (rng.below(2) == 0) tri = quad::reversed(tri);
  return tri;
}

quad::Coeffs random_colour(Rng& rng, QuadMode mode) {
  const auto sample = [&rng]() {
    return rng.below(8) == 0 ? 1.4 * rng.uniform() - 0.2 : rng.uniform();
  };
  if (mode == QuadMode::linear) return quad::linear_coefficients(sample(), sample(), sample());
  quad::Samples r;
  for (auto& x : r) x = sample();
  return quad::coefficients(r);
}

Stimulus make_quad_stimulus(const PipelineModel& model, QuadMode mode) {
  const auto& qm = dynamic_cast<const QuadModel&>(model);
  const QuadFormats f = qm.formats();
  const int s = f.sub_bits;
  const auto tri = [s](double x0, double y0, double x1, double y1, double x2, double y2) {
    return quad::quantize({x0, y0}, {x1, y1}, {x2, y2}, s);
  };
  const auto flat = [](double v) { return quad::linear_coefficients(v, v, v); };
  std::vector<std::vector<std::int64_t>> directed;
  const auto add = [&](const quad::SubpixelTri& t, const std::array<quad::Coeffs, 3>& colour) {
    directed.push_back(QuadModel::words(quad_program(t, colour, f)));
  };
  const std::array<quad::Coeffs, 3> grey{flat(0.5), flat(0.25), flat(0.75)};
  const std::array<quad::Coeffs, 3> ramp{quad::linear_coefficients(0, 1, 0.5),
                                         quad::linear_coefficients(1, 0, 0.5),
                                         quad::coefficients({0, 1, 0, 1, 0, 1})};
  const std::array<quad::Coeffs, 3> outside{flat(-0.3), flat(1.3), flat(1.0)};  // clamp corners
  // One pixel; vertices on pixel centres (top-left ties on every edge); both windings.
  add(tri(10.2, 10.2, 10.9, 10.3, 10.4, 10.9), grey);
  add(tri(20.5, 20.5, 30.5, 20.5, 20.5, 30.5), ramp);
  add(tri(20.5, 20.5, 20.5, 30.5, 30.5, 20.5), ramp);
  add(tri(40.5, 40.5, 50.5, 50.5, 40.5, 50.5), ramp);
  // A 1024 x 1024 right triangle, a sliver, a degenerate triangle, the screen's far corner.
  add(tri(0, 0, 1024, 0, 0, 1024), ramp);
  add(tri(100, 100, 900, 103, 100, 101), ramp);
  add(tri(5, 5, 10, 10, 15, 15), grey);
  add(tri(2040, 2040, 2048, 2047, 2043, 2048), outside);
  add(tri(60, 60, 70, 62, 61, 75), outside);

  // Random: three quarters through the setup, one quarter arbitrary words over a small box.
  const FieldRandom bits(model.inputs());
  auto random = [f, mode, bits](std::uint64_t seed, std::uint64_t index,
                                std::span<std::int64_t> in) {
    Rng rng(seed, kStimulusStream, index);
    if (rng.below(4) == 0) {
      bits(rng, in);
      in[0] = static_cast<std::int64_t>(rng.below(2016));  // box up to 32 x 32 pixels
      in[1] = static_cast<std::int64_t>(rng.below(2016));
      in[2] = in[0] + static_cast<std::int64_t>(rng.below(32));
      in[3] = in[1] + static_cast<std::int64_t>(rng.below(32));
      return;
    }
    const quad::SubpixelTri t = random_triangle(rng, f.sub_bits);
    std::array<quad::Coeffs, 3> colour;
    for (auto& c : colour) c = random_colour(rng, mode);
    const auto w = QuadModel::words(quad_program(t, colour, f));
    std::copy(w.begin(), w.end(), in.begin());
  };
  return Stimulus(model, std::move(directed), random);
}

// ---- analysis ----
namespace {

struct Walked {
  std::vector<std::int64_t> pixels;  // x, y, r, g, b per covered pixel
  std::vector<std::int64_t> acc;     // the three accumulators per covered pixel
};

// Walks `tri` with `colour` through `m` and calls visit(walked, pixel, channel, r(s, t)) for every
// covered pixel and channel, r evaluated directly at the pixel's centre (eqs. 4.1, 4.3).
template <class Visit>
void walk_with_direct(const QuadModel& m, const quad::SubpixelTri& tri,
                      const std::array<quad::Coeffs, 3>& colour, Visit visit) {
  Walked w;
  (void)m.walk(quad_program(tri, colour, m.formats()), w.pixels, &w.acc);
  const auto v = quad::to_pixels(tri);
  for (std::size_t i = 0; i < w.pixels.size() / 5; ++i) {
    const quad::St st = quad::st_at(v[0], v[1], v[2],
                                    {static_cast<double>(w.pixels[5 * i]) + 0.5,
                                     static_cast<double>(w.pixels[5 * i + 1]) + 0.5});
    for (int ch = 0; ch < 3; ++ch) visit(w, i, ch, quad::eval_st(colour[ch], st));
  }
}

}  // namespace

double quad_drift(int size, int guard_bits, fx::Format out, int triangles, std::uint64_t seed) {
  QuadFormats f;
  f.acc = fx::Format{true, 2, out.frac_bits + guard_bits};
  f.out = out;
  f.sub_bits = 4;
  const QuadModel m(f);
  const double lsb = std::ldexp(1.0, -out.frac_bits);
  const auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
  double worst = 0;
  for (int n = 0; n < triangles; ++n) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(n));
    const double x = rng.uniform() * (2048 - size);
    const double y = rng.uniform() * (2048 - size);
    std::array<quad::Vertex2, 3> v;
    for (auto& p : v) p = {x + rng.uniform() * size, y + rng.uniform() * size};
    const quad::SubpixelTri tri = quad::quantize(v[0], v[1], v[2], f.sub_bits);
    if (quad::orientation(tri) == 0) continue;
    std::array<quad::Coeffs, 3> colour;
    for (auto& c : colour) c = random_colour(rng, QuadMode::quadratic);
    walk_with_direct(m, tri, colour, [&](const Walked& w, std::size_t i, int ch, double exact) {
      const double got = clamp01(fx::to_real(w.acc[3 * i + ch], f.acc));
      worst = std::max(worst, std::abs(got - clamp01(exact)) / lsb);
    });
  }
  return worst;
}

QuadOutputError quad_output_error(const QuadFormats& f, QuadMode mode, int triangles,
                                  std::uint64_t seed, const InputContract* contract) {
  const QuadModel m(f);
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  const double top = fx::to_real(f.out.max_raw(), f.out);
  QuadOutputError e;
  double sum = 0;
  for (int n = 0; n < triangles; ++n) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(n));
    const quad::SubpixelTri tri = random_triangle(rng, f.sub_bits);
    std::array<quad::Coeffs, 3> colour;
    for (auto& c : colour) c = random_colour(rng, mode);
    if (contract != nullptr) {
      InputContract check = *contract;
      if (check.check(QuadModel::words(quad_program(tri, colour, f))) != InputContract::kIn) {
        ++e.out_of_contract;
        continue;
      }
    }
    walk_with_direct(m, tri, colour, [&](const Walked& w, std::size_t i, int ch, double exact) {
      // Clamped to what the output can hold: 0.8 tops out at 255/256, not 1.
      const double d =
          std::abs(fx::to_real(w.pixels[5 * i + 2 + ch], f.out) - std::clamp(exact, 0.0, top)) /
          lsb;
      e.max = std::max(e.max, d);
      sum += d;
      ++e.pixels;
    });
  }
  e.mean = e.pixels == 0 ? 0 : sum / static_cast<double>(e.pixels);
  return e;
}

std::vector<QuadContractRow> quad_out_of_contract(const QuadFormats& f, QuadMode mode,
                                                  const InputContract& contract,
                                                  std::uint64_t samples, std::uint64_t seed) {
  const QuadModel m(f);
  const std::size_t clauses = contract.clauses().size();
  std::vector<QuadContractRow> rows(clauses + 1);
  for (std::size_t c = 0; c < clauses; ++c) rows[c].clause = contract.clauses()[c];
  rows[clauses].clause = "(not checked) colour samples in [-8, 9]";
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  const double top = fx::to_real(f.out.max_raw(), f.out);
  const std::int64_t sub = std::int64_t{1} << f.sub_bits;
  const std::int64_t r_max = (std::int64_t{1} << f.r_bits()) - 1;
  // The largest square box the guard bits cover (the box clause).
  const int guard = f.acc.frac_bits - f.out.frac_bits;
  int box = 0;
  while (box < 2048 && quad_guard_bits_needed(box + 1, box + 1) <= guard) ++box;
  const auto check = [&contract](const std::vector<std::int64_t>& words) {
    InputContract c = contract;
    return c.check(words);
  };
  const std::uint64_t per_clause = std::max<std::uint64_t>(samples / (clauses + 1), 1);
  for (std::size_t c = 0; c <= clauses; ++c) {
    QuadContractRow& row = rows[c];
    if (c == 1 && box >= 2048) {
      row.note = "cannot be broken: the guard bits cover the whole 2048 x 2048 screen";
      continue;
    }
    for (std::uint64_t tries = 0; row.programs < per_clause && tries < 20 * per_clause; ++tries) {
      Rng rng(seed, kStimulusStream, (std::uint64_t{c} << 40) + tries);
      quad::SubpixelTri tri;
      if (c == 1) {  // vertices in a box larger than the guard bits cover
        const double side = std::exp(std::log(box + 1.0) +
                                     rng.uniform() * (std::log(2047.0) - std::log(box + 1.0)));
        const double x = rng.uniform() * (2048 - side), y = rng.uniform() * (2048 - side);
        std::array<quad::Vertex2, 3> v;
        for (auto& p : v) p = {x + rng.uniform() * side, y + rng.uniform() * side};
        tri = quad::quantize(v[0], v[1], v[2], f.sub_bits);
      } else {
        tri = random_triangle(rng, f.sub_bits);
      }
      if (quad::orientation(tri) == 0) continue;  // covers nothing: no colour to compare
      std::array<quad::Coeffs, 3> colour;
      for (auto& col : colour) {
        if (c == clauses) {
          const auto big = [&rng]() { return 17 * rng.uniform() - 8; };
          if (mode == QuadMode::linear) {
            col = quad::linear_coefficients(big(), big(), big());
          } else {
            quad::Samples r;
            for (auto& x : r) x = big();
            col = quad::coefficients(r);
          }
        } else {
          col = random_colour(rng, mode);
        }
      }
      std::vector<std::int64_t> words = QuadModel::words(quad_program(tri, colour, f));
      if (c == 0) {  // one used edge's words as the setup never writes them
        if (check(words) != InputContract::kIn) continue;
        std::vector<std::size_t> used;
        for (std::size_t k = 0; k < 3; ++k) {
          if (words[4 + 6 * k] == 1 || words[4 + 6 * k] == 2) used.push_back(4 + 6 * k);
        }
        if (used.empty()) continue;
        std::int64_t* e = words.data() + used[rng.below(used.size())];  // kind, q, r, d, dq, dr
        switch (rng.below(4)) {
          case 0:
            e[2] = e[3] + static_cast<std::int64_t>(rng.below(static_cast<std::uint64_t>(
                              std::max<std::int64_t>(r_max - e[3] + 1, 1))));
            break;
          case 1:
            e[5] = e[3] + static_cast<std::int64_t>(rng.below(static_cast<std::uint64_t>(
                              std::max<std::int64_t>(r_max - e[3] + 1, 1))));
            break;
          case 2:
            e[3] = std::min(r_max, e[3] + 1 +
                                       static_cast<std::int64_t>(
                                           rng.below(static_cast<std::uint64_t>(sub - 1))));
            break;
          default:
            e[0] = 3;
            break;
        }
      }
      const int broken = check(words);
      if (c < clauses ? broken != static_cast<int>(c) : broken != InputContract::kIn) continue;
      ++row.programs;
      std::vector<std::int64_t> pixels;
      (void)m.walk(QuadModel::program(words), pixels);
      // Coverage against the triangle's own pixels.
      const auto want = quad::raster(tri, 2048, 2048);
      std::vector<std::pair<int, int>> got;
      for (std::size_t i = 0; i < pixels.size() / 5; ++i) {
        got.emplace_back(static_cast<int>(pixels[5 * i]), static_cast<int>(pixels[5 * i + 1]));
      }
      const auto by_row = [](const std::pair<int, int>& a, const std::pair<int, int>& b) {
        return std::pair(a.second, a.first) < std::pair(b.second, b.first);
      };
      std::sort(got.begin(), got.end(), by_row);
      std::vector<std::pair<int, int>> extra, missing;
      std::set_difference(got.begin(), got.end(), want.begin(), want.end(),
                          std::back_inserter(extra), by_row);
      std::set_difference(want.begin(), want.end(), got.begin(), got.end(),
                          std::back_inserter(missing), by_row);
      row.extra += extra.size();
      row.missing += missing.size();
      row.worst_extra = std::max<std::uint64_t>(row.worst_extra, extra.size());
      // Channels against direct evaluation at every emitted pixel's centre.
      const auto v = quad::to_pixels(tri);
      for (std::size_t i = 0; i < pixels.size() / 5; ++i) {
        const quad::St st = quad::st_at(v[0], v[1], v[2],
                                        {static_cast<double>(pixels[5 * i]) + 0.5,
                                         static_cast<double>(pixels[5 * i + 1]) + 0.5});
        for (int ch = 0; ch < 3; ++ch) {
          const double d = std::abs(
              fx::to_real(pixels[5 * i + 2 + static_cast<std::size_t>(ch)], f.out) -
              std::clamp(quad::eval_st(colour[static_cast<std::size_t>(ch)], st), 0.0, top));
          row.max_error = std::max(row.max_error, d);
          if (d > lsb) ++row.off;
        }
        ++row.pixels;
      }
    }
  }
  return rows;
}

// quad_walker's state machine, with the source offering a program every cycle and the sink
// always ready: the program accepted in cycle 0 is loaded in cycle 1 (Idle); after that a
// program is loaded in the cycle its predecessor's last row ends, or in an Idle cycle after a
// program without rows. Each row costs a Row cycle and one cycle per covered pixel (the model's
// outputs say which); a pixel leaves through the output register the cycle after it fires.
FrameCycles walker_cycles(std::span<const std::int64_t> in, std::span<const std::int64_t> out,
                          std::size_t out_fields, std::span<const std::uint32_t> counts,
                          std::vector<FrameCycles>* per_vector) {
  const std::size_t programs = counts.size(), fields = programs == 0 ? 0 : in.size() / programs;
  if (per_vector != nullptr) per_vector->assign(programs, {});
  FrameCycles now, at_last;  // at_last: as of the last pixel so far
  std::uint64_t t = 1, last_fire = 0;
  std::size_t pixel = 0;  // the next output
  bool loaded = false;    // the next program is loaded without an Idle cycle
  for (std::size_t k = 0; k < programs; ++k) {
    const FrameCycles before = now;
    const std::uint64_t start = t;
    if (!loaded) {
      ++now.setup_cycles;
      ++t;
    }
    const std::int64_t y0 = in[k * fields + 1], y1 = in[k * fields + 3];
    const std::size_t end = pixel + counts[k];
    loaded = y0 <= y1;
    for (std::int64_t y = y0; y <= y1; ++y) {
      std::uint64_t w = 0;
      while (pixel + w < end && out[(pixel + w) * out_fields + 1] == y) ++w;
      ++(w == 0 ? now.empty_row_cycles : now.setup_cycles);
      ++t;
      if (w == 0) continue;
      now.outputs += w;
      t += w;
      pixel += w;
      last_fire = t - 1;
      at_last = now;
    }
    if (per_vector != nullptr) {
      (*per_vector)[k] = {.cycles = t - start,
                          .outputs = now.outputs - before.outputs,
                          .setup_cycles = now.setup_cycles - before.setup_cycles,
                          .empty_row_cycles = now.empty_row_cycles - before.empty_row_cycles};
    }
  }
  if (at_last.outputs == 0) return {};
  at_last.fill_cycles = 2;  // the input and output registers
  at_last.cycles = last_fire + 2;
  return at_last;
}

std::vector<PortBinding> walker_program_ports(const std::array<std::string, 3>& channel_ports,
                                              const std::array<std::string, 3>& prefixes) {
  std::vector<PortBinding> p{{"in_bbox_i", true, {"x0", "y0", "x1", "y1"}}};
  for (int k = 0; k < 3; ++k) {
    PortBinding edge{fmt::format("in_edge{}_i", k), true, {}};
    for (const char* w : {"kind", "q", "r", "d", "dq", "dr"})
      edge.fields.push_back(fmt::format("e{}_{}", k, w));
    p.push_back(std::move(edge));
  }
  for (std::size_t c = 0; c < 3; ++c) {
    PortBinding channel{channel_ports[c], true, {}};
    for (const char* w : {"f", "gy", "gx", "a", "b", "c"})
      channel.fields.push_back(fmt::format("{}_{}", prefixes[c], w));
    p.push_back(std::move(channel));
  }
  return p;
}

// ---- registry entry ----
namespace {

std::vector<PortBinding> ports() {
  std::vector<PortBinding> p =
      walker_program_ports({"in_red_i", "in_green_i", "in_blue_i"}, {"r", "g", "b"});
  p.insert(p.end(), {{"out_x_o", false, {"x"}},
                     {"out_y_o", false, {"y"}},
                     {"out_rgb_o", false, {"r", "g", "b"}}});
  return p;
}

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const QuadFormats formats = QuadFormats::from_config(cfg);
  (void)quad_mode(cfg);  // the stimulus reads it; check it here
  cfg.check_all_used();
  return std::make_unique<QuadModel>(formats);
}

Stimulus make_stimulus(const PipelineModel& model, const Config& cfg) {
  return make_quad_stimulus(model, quad_mode(cfg));
}

int latency(const Config&) { return 4; }  // program to its first pixel (docs/quad.md)

FrameCycles cycles(const Config&, std::span<const std::int64_t> in,
                   std::span<const std::int64_t> out, std::span<const std::uint32_t> counts,
                   std::vector<FrameCycles>* per_vector) {
  return walker_cycles(in, out, 5, counts, per_vector);
}

// configs/quad/default.toml's walker by hand: acc S2.32, out 0.8.
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  std::size_t n = 0;
  fx::on_kernel_isa([&] { n = native_walker<35, 32, 8, 8, 40, false>(in, out); });
  return n;
}

// The domain of the accuracy claims (docs/quad.md, "Input contract"), per program.
InputContract contract(const PipelineModel& model, const Config&) {
  const QuadFormats f = dynamic_cast<const QuadModel&>(model).formats();
  const std::int64_t sub = std::int64_t{1} << f.sub_bits;
  const std::int64_t d_max = std::int64_t{1} << (QuadFormats::kCoordBits + 2 * f.sub_bits);
  const int guard = f.acc.frac_bits - f.out.frac_bits;
  return InputContract(
      {"edges as the setup writes them", "box within the guard bits"},
      [=](std::span<const std::int64_t> in) {
        for (int k = 0; k < 3; ++k) {  // e<k>_{kind, q, r, d, dq, dr} from field 4 on
          const std::int64_t* e = in.data() + 4 + 6 * k;
          if (e[0] == 0) continue;
          if (e[0] > 2 || e[3] < sub || e[3] > d_max || e[3] % sub != 0 || e[2] >= e[3] ||
              e[5] >= e[3]) {
            return 0;
          }
        }
        const std::int64_t w = in[2] - in[0] + 1, h = in[3] - in[1] + 1;
        if (w <= 0 || h <= 0) return InputContract::kIn;  // no pixels
        return quad_guard_bits_needed(static_cast<int>(w), static_cast<int>(h)) <= guard
                   ? InputContract::kIn
                   : 1;
      });
}

// A program's stages: every covered pixel's three channel accumulators (before clamping and
// rounding), named by the pixel.
std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  const auto& m = dynamic_cast<const QuadModel&>(model);
  std::vector<std::int64_t> out, acc;
  const std::size_t n = m.walk(QuadModel::program(in), out, &acc);
  std::vector<StageValue> s;
  for (std::size_t i = 0; i < n; ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      s.push_back({fmt::format("pixel({},{}).{}_acc", out[5 * i], out[5 * i + 1], "rgb"[ch]),
                   fx::Fixed{acc[3 * i + static_cast<std::size_t>(ch)], m.formats().acc}});
    }
  }
  return s;
}

// Each channel's clamp to [0, 1] (low, high, neither) and requantization (saturating high: a
// clamped 1.0 in an output without integer bits; not); programs without rows, empty rows and
// one-pixel programs; each end of a row's span set by an edge rather than the box (quad_walker's
// narrowing compares), and the fill rule's ties there: the edge's remainder 0 (E - bias = 0 at
// the bound pixel: a centre on a top-left edge, covered) and d - 1 (E - bias = -1 just outside:
// a centre on a right or bottom edge, not covered) (docs/quad.md).
CoverpointSampler coverpoints(const PipelineModel& model, const Config&) {
  const QuadFormats f = dynamic_cast<const QuadModel&>(model).formats();
  CoverpointSampler c;
  const Clamp01Output output(c, f.acc, f.out, f.out_round);
  const std::size_t shape = c.points.declare("program.no_rows");
  c.points.declare("program.one_pixel");
  c.points.declare("row.empty");
  const std::size_t bound = c.points.declare("bound.lower.edge");
  for (const char* b : {"bound.lower.tie_in", "bound.lower.tie_out", "bound.upper.edge",
                        "bound.upper.tie_in", "bound.upper.tie_out"}) {
    c.points.declare(b);
  }
  // quad_walker_core's narrowing compares (`if (... 0 - q_ext[k] > lower) lower = ...` and the
  // upper one, the region marked `narrow`) sit in a `for` loop of an always_comb that Verilator
  // unrolls, and its line coverage never counts them although they decide every narrowed span
  // end, which the model counts as bound.{lower,upper}.edge and the co-simulation checks bit for
  // bit. (Their implicit elses, on the same lines, are counted: a marker waives statements only.)
  c.line_waivers.push_back({R"(\.u_walker$)", "rtl/quad/quad_walker_core.sv", "narrow",
                            "bound.{lower,upper}.edge: the narrowing compares in an unrolled "
                            "always_comb loop, which Verilator's line coverage does not count"});
  c.sample = [=](PipelineModel& model, std::span<const std::int64_t> in, Coverpoints& cp) {
    const auto& m = dynamic_cast<const QuadModel&>(model);
    const QuadProgram p = QuadModel::program(in);
    std::vector<std::int64_t> out, acc;
    std::vector<QuadRowTrace> rows;
    const std::size_t n = m.walk(p, out, &acc, &rows);
    if (p.y0 > p.y1) cp.hit(shape);
    if (n == 1) cp.hit(shape + 1);
    const auto end = [&](std::size_t at, int edge, std::int64_t r, std::int64_t d) {
      if (edge < 0) return;
      cp.hit(at);
      if (r == 0) cp.hit(at + 1);
      if (r == d - 1) cp.hit(at + 2);
    };
    for (const QuadRowTrace& row : rows) {
      if (row.lower > row.upper) cp.hit(shape + 2);
      end(bound, row.lower_edge, row.lower_r, row.lower_d);
      end(bound + 3, row.upper_edge, row.upper_r, row.upper_d);
    }
    for (const std::int64_t a : acc) output.hit(cp, a);
  };
  return c;
}

// Random triangles of the configuration's mode through the model, against direct evaluation.
ModelError float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  const QuadFormats f = QuadFormats::from_config(cfg);
  ModelError e;
  int triangles = 0;
  double mean_sum = 0;
  while (e.samples < samples && triangles < 100000) {
    const QuadOutputError q = quad_output_error(f, quad_mode(cfg), 10, seed + triangles);
    triangles += 10;
    e.max_lsb = std::max(e.max_lsb, q.max);
    mean_sum += q.mean * static_cast<double>(q.pixels);
    e.samples += q.pixels;
  }
  e.mean_lsb = e.samples == 0 ? 0 : mean_sum / static_cast<double>(e.samples);
  e.max_abs = e.max_lsb * std::ldexp(1.0, -f.out.frac_bits);
  return e;
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  const int triangles = static_cast<int>(std::max<std::uint64_t>(1, samples / 5000));
  const fx::Format out_fmt{false, 0, 8};
  const int sizes[] = {16, 64, 256, 1024};
  const int guards[] = {0, 4, 8, 12, 16, 20, 24, 40};
  out.print(
      "Drift: max |accumulator - r(s, t) evaluated directly (eqs. 4.1, 4.3)|, both clamped "
      "to [0, 1], in LSBs of an 8-bit output; {} random triangles with vertices in a "
      "size x size box per cell, quadratic colours, seed {}\n",
      triangles, seed);
  drift_table(out, "Drift in LSBs of an 8-bit output, by box size and guard bits", "size", 5, sizes,
              guards,
              [&](int size, int g) { return quad_drift(size, g, out_fmt, triangles, seed); });
  out.print(
      "\nGuard bits for a drift of at most 1/2 output LSB over a box: analytic bound "
      "G >= log2(1 + (w-1)^2 + (w-1)(h-1) + (h-1)^2), and the smallest G that met it on "
      "the triangles above\n");
  guard_bits_table(
      out, "Guard bits for a drift of at most 1/2 output LSB over a box", "size", 5, sizes,
      [](int size) { return quad_guard_bits_needed(size, size); },
      [&](int size, int g) { return quad_drift(size, g, out_fmt, triangles, seed); });
  out.print(
      "\nOutput against direct evaluation, per configuration: |output - r(s, t)|, r "
      "clamped to the output range, in output LSBs over {} random triangles of the "
      "co-simulation's distribution (boxes up to 1024 pixels), colours of the "
      "configuration's [setup] mode, seed {}; triangles outside the input contract "
      "(docs/quad.md) are left out\n",
      triangles * 10, seed);
  out.print("  {:<16} {:>9} {:>6} {:>5} {:>10} {:>9} {:>9} {:>9}\n", "config", "mode", "acc", "out",
            "pixels", "max", "mean", "left out");
  out.table("Output against direct evaluation inside the input contract, in output LSBs",
            {"config", "mode", "acc", "out", "pixels", "max_lsb", "mean_lsb", "out_of_contract"});
  for (const Config& cfg : configs) {
    const QuadFormats f = QuadFormats::from_config(cfg);
    const QuadMode mode = quad_mode(cfg);
    const QuadModel m(f);
    const InputContract c = contract(m, cfg);
    const QuadOutputError e = quad_output_error(f, mode, triangles * 10, seed, &c);
    out.print("  {:<16} {:>9} {:>6} {:>5} {:>10} {:>9.4f} {:>9.4f} {:>9}\n", cfg.name(),
              mode == QuadMode::linear ? "linear" : "quadratic", f.acc.str(), f.out.str(), e.pixels,
              e.max, e.mean, e.out_of_contract);
    out.row({cfg.name(), std::string(mode == QuadMode::linear ? "linear" : "quadratic"),
             f.acc.str(), f.out.str(), static_cast<std::int64_t>(e.pixels), e.max, e.mean,
             static_cast<std::int64_t>(e.out_of_contract)});
  }

  const std::uint64_t programs = std::max<std::uint64_t>(1, samples / 100);
  out.print(
      "\nOutside the input contract: pixels against the triangle each program was written for "
      "(emitted but not covered, covered but missed) and every emitted pixel's channels "
      "against r(s, t) evaluated directly, clamped to the output range, absolute; each clause "
      "broken alone in setup programs, then over-large colour samples (not checked by the "
      "contract); {} programs per row, seed {}\n",
      std::max<std::uint64_t>(programs / 3, 1), seed);
  out.table("Outside the input contract: coverage and channels against the triangle",
            {"config", "clause", "programs", "pixels", "extra_pixels", "missing_pixels",
             "most_extra_in_one", "max_error", "channels_off", "note"});
  for (const Config& cfg : configs) {
    const QuadFormats f = QuadFormats::from_config(cfg);
    const QuadModel m(f);
    const auto rows = quad_out_of_contract(f, quad_mode(cfg), contract(m, cfg), programs, seed);
    out.print("  {}\n  {:<40} {:>8} {:>9} {:>8} {:>8} {:>10} {:>8} {:>12}\n", cfg.name(),
              "clause broken first", "programs", "pixels", "extra", "missing", "most extra",
              "max err", "> 1 LSB off");
    for (const QuadContractRow& r : rows) {
      if (!r.note.empty()) {
        out.print("  {:<40} {}\n", r.clause, r.note);
      } else {
        out.print("  {:<40} {:>8} {:>9} {:>8} {:>8} {:>10} {:>8.4f} {:>12}\n", r.clause, r.programs,
                  r.pixels, r.extra, r.missing, r.worst_extra, r.max_error, r.off);
      }
      out.row({cfg.name(), r.clause, static_cast<std::int64_t>(r.programs),
               static_cast<std::int64_t>(r.pixels), static_cast<std::int64_t>(r.extra),
               static_cast<std::int64_t>(r.missing), static_cast<std::int64_t>(r.worst_extra),
               r.max_error, static_cast<std::int64_t>(r.off), r.note});
    }
  }
}

}  // namespace

const PipelineInfo& quad_pipeline() {
  static const PipelineInfo info{
      .name = "quad",
      .summary = "Quadratic/linear colour interpolator: triangle walker, forward differencing",
      .top = "quad_walker",
      .rtl_files = {"rtl/common", "rtl/quad/quad_channel.sv", "rtl/quad/quad_walker_core.sv",
                    "rtl/quad/quad_walker.sv"},
      .ports = ports(),
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = true,
      // Vectors are triangle programs, about a hundred pixels each on average.
      .default_vectors = 10000,
      .latency = latency,
      // One cycle per row on span set-up: below one pixel per clock by design (docs/quad.md).
      .one_per_clock = false,
      .cycles = cycles,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract = contract,
      .float_error = float_error,
      .analyze = analyze,
      .mutants =
          {{"quad-fill", "default", "rtl/quad/quad_walker_core.sv",
            "assign carry = sum >= {1'b0, d_q};", "assign carry = sum > {1'b0, d_q};",
            "edge DDA carries one remainder step late: spans off by a pixel"},
           {"quad-jump", "default", "rtl/quad/quad_channel.sv",
            "assign f_start = col_f + i0_ext * g0_q + a_q * i0_i0m1;",
            "assign f_start = col_f + i0_ext * g0_q;",
            "row start forgets the quadratic term a·i0(i0-1)"},
           {"quad-column", "default", "rtl/quad/quad_channel.sv", "    .d2_step_i(c_q << 1),",
            "    .d2_step_i(c_q),", "column second difference c instead of 2c"},
           {"quad-clip", "default", "rtl/quad/quad_walker_core.sv", "{1'b0}}, x0_q});",
            "{1'b0}}, x0_q}) - 1;", "span not clipped to the box on the left"},
           // Two bugs at the walker's seam to its output buffer that leave every pixel
           // right: only the stream assertions (rtl/common/stream_check.sv) see them.
           {"quad-seam-valid", "default", "rtl/quad/quad_walker_core.sv",
            "assign emitting  = state_q == Pixels;",
            "assign emitting  = state_q == Pixels && !u_out.u_check_in.stalled_q;",
            "a pixel offered, stalled, then withdrawn for a cycle", "valid dropped while stalled"},
           {"quad-seam-data", "default", "rtl/quad/quad_walker_core.sv",
            ".in_data_i  ({tag_q, rgb, y_q, x_q}),",
            ".in_data_i  (out_ready ? {tag_q, rgb, y_q, x_q} : '0),",
            "a stalled pixel's data zeroed until it is taken", "data changed while stalled"}},
  };
  return info;
}

}  // namespace phongsim
