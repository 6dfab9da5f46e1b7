// Stimulus for the Lyon pipeline: directed corners that hit its decision points exactly, and
// random vectors that are half plausible geometry (so the highlight is often non-zero) and half
// arbitrary bit patterns (so saturation and degenerate inputs are exercised).
#include "sim/pipelines/lyon.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/error.h"
#include "base/vec3.h"
#include "model/lyon.h"
#include "model/plan.h"
#include "ref/lyon_float.h"
#include "sim/pipelines/lyon_geometry.h"

namespace phongsim {

Stimulus make_lyon_stimulus(const PipelineModel& model) {
  const LyonFormats& f = dynamic_cast<const LyonModel&>(model).formats();
  const bool fig8 = f.arrangement == 8;
  const auto pixel = [&f](Vec3 n0, Vec3 n1, double a, Vec3 v, Vec3 l, double shin) {
    return quantize_lyon_pixel(LyonPixel{n0, n1, a, v, l, shin}, f);
  };
  const double shin_max = fx::to_real(f.shin.max_raw(), f.shin);
  const Vec3 up{0, 0, 1};
  std::vector<std::vector<std::int64_t>> directed;

  // Shininess corners: 1, the largest value, and Lyon's extremes (n = 8000, m = 63) if they fit.
  std::vector<double> shins{1, shin_max, fig8 ? 63.0 : 8000.0, fig8 ? 8.0 : 64.0};
  // Axis-aligned geometry with exact +-1.0 components: R exactly on L (D = 0, spec = f(0) = 1),
  // L opposite N (N·L = -1, diffuse clamps to 0), L perpendicular.
  const Vec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3 n : axes) {
    for (const double shin : shins) {
      directed.push_back(pixel(n, n, 0.0, n, n, shin));                    // D = 0
      directed.push_back(pixel(n, n, 1.0, n, -1.0 * n, shin));             // N·L = -1
      directed.push_back(pixel(n, n, 0.5, n, Vec3{n.y, n.z, n.x}, shin));  // N·L = 0
    }
  }
  // x/2^k just below, at and just above 1 (the comparator), with N = V = R = (0,0,1) and
  // L = (-dx, 0, 1) so that D = (dx, 0, 0) exactly: x = (n/2)·dx² (reflect variant; for the
  // halfway variant these are still valid, merely different, points).
  for (const double dx : {0.5, 0.25, 0.125, 0.5 - std::ldexp(1.0, -f.vec.frac_bits)}) {
    const Vec3 l{-dx, 0, 1};
    const double two_to_k = std::ldexp(1.0, f.k);
    const double at = 2 * two_to_k / (dx * dx);  // n with x = 2^k
    for (const double n : {at - 1, at, at + 1}) {
      directed.push_back(pixel(up, up, 0.0, up, l, fig8 ? std::round(std::sqrt(n)) : n));
      if (fig8) directed.push_back(pixel(up, up, 0.0, up, l, std::floor(std::sqrt(n))));
    }
  }
  // A zero normal: N'·N' = 0, so y = 1 - z = 1 saturates y (S0.x stops below 1).
  directed.push_back(pixel(Vec3{0, 0, 0}, Vec3{0, 0, 0}, 0.0, up, up, 1.0));
  // Unnormalized N': endpoints 90 degrees apart interpolated at a = 1/2 (length cos 45° = 0.71),
  // and short endpoints (length 0.7) with a = 0 and 1.
  const Vec3 side{1, 0, 0};
  for (const double shin : shins) {
    directed.push_back(pixel(up, side, 0.5, up, up, shin));
    directed.push_back(pixel(0.7 * up, 0.7 * up, 0.0, up, up, shin));
    directed.push_back(pixel(0.7 * side, 0.8 * up, 1.0, side, side, shin));
  }

  // Random: half plausible geometry near the mirror direction, half arbitrary bits.
  const FieldRandom bits(model.inputs());
  auto random = [f, bits](std::uint64_t seed, std::uint64_t index, std::span<std::int64_t> in) {
    Rng rng(seed, kStimulusStream, index);
    if (rng.below(2) == 0) {
      bits(rng, in);
      return;
    }
    quantize_lyon_pixel(random_lyon_pixel(rng, f), f, in);
  };
  // The same a block at a time: each vector's generator and coin (below(2) of its first draw)
  // vectorized; the generators split by coin without a branch on it; then the bits from
  // FieldRandom's vectorized fill (after the coin's draw) and the geometry
  // (random_lyon_pixels, from the generators after the coin).
  auto block = [f, bits](std::uint64_t seed, std::uint64_t first, std::size_t count,
                         std::span<std::int64_t> out) {
    std::vector<std::uint64_t> starts(count), coins(count);
    fx::on_kernel_isa([&] {
      std::uint64_t *s = starts.data(), *c = coins.data();  // locals: not reloaded per store
      for (std::size_t v = 0, n = count; v < n; ++v) {
        s[v] = Rng::start(seed, kStimulusStream, first + v);
        c[v] = Rng::scaled_narrow(Rng::output(s[v], 0), 2);
      }
    });
    std::vector<std::uint64_t> bit_starts(count), geometric(count);
    std::vector<std::uint32_t> bit_rows(count), geometric_rows(count);
    std::size_t n_bits = 0, n_geometric = 0;
    for (std::size_t v = 0; v < count; ++v) {
      Rng rng = Rng::from_state(starts[v]);
      rng.discard(1);
      bit_starts[n_bits] = starts[v];
      bit_rows[n_bits] = geometric_rows[n_geometric] = static_cast<std::uint32_t>(v);
      geometric[n_geometric] = rng.state();
      n_bits += 1 - coins[v];
      n_geometric += coins[v];
    }
    bits.fill_rows(std::span(bit_starts).first(n_bits), std::span(bit_rows).first(n_bits), out, 1);
    random_lyon_pixels(std::span(geometric).first(n_geometric),
                       std::span(geometric_rows).first(n_geometric), f, out);
  };
  return Stimulus(model, std::move(directed), random, block);
}

// ---- input contract ----

InputContract lyon_contract(const LyonFormats& f) {
  // Lengths from raw components, at the vector format's precision: a unit vector quantized to
  // `vec` is within sqrt(3)/2 LSB of length 1, so two LSBs of tolerance.
  const double vs = std::ldexp(1.0, -f.vec.frac_bits);
  const double as = std::ldexp(1.0, -f.a.frac_bits);
  const double tol = 2 * vs;
  const double unit_lo = (1 - tol) * (1 - tol), unit_hi = (1 + tol) * (1 + tol);
  const double np_lo = (std::sqrt(0.5) - tol) * (std::sqrt(0.5) - tol);
  const double shin_one = std::ldexp(1.0, f.shin.frac_bits);
  constexpr std::size_t n_in = 14;  // LyonModel::inputs: N0, N1, a, V, L, shininess
  return InputContract(
      {"a in [0, 1]", "|N'| in [1/sqrt 2, 1]", "|V| = 1", "|L| = 1", "shininess >= 1"},
      InputContract::Check([=](std::span<const std::int64_t> vectors, std::size_t width,
                               std::span<std::int16_t> out) {
        if (width != n_in) {
          throw Error(fmt::format("a Lyon vector has {} fields, not {}", n_in, width));
        }
        // A block of vectors at a time, field by field (structure of arrays), so that the
        // clauses' loop vectorizes; every clause evaluated without a branch (random vectors
        // break them at random), the first one broken kept. The file is compiled without FMA
        // contraction, so every instruction set computes the same lengths.
        fx::on_kernel_isa([&] {
          for_each_field_block<double, n_in>(
              vectors, out, [&](const auto& v, std::size_t m, std::int16_t* o) {
                for (std::size_t k = 0; k < m; ++k) {
                  const double a = v[6][k] * as;
                  double np2 = 0;  // N' = (1 - a)·N0 + a·N1, exactly (as reals)
                  for (std::size_t c = 0; c < 3; ++c) {
                    const double x = (v[c][k] * (1 - a) + v[3 + c][k] * a) * vs;
                    np2 += x * x;
                  }
                  const auto len2 = [&](std::size_t first) {
                    const double x = v[first][k] * vs, y = v[first + 1][k] * vs,
                                 z = v[first + 2][k] * vs;
                    return x * x + y * y + z * z;
                  };
                  const double v2 = len2(7), l2 = len2(10);
                  const std::int64_t broken[5] = {
                      (a < 0) | (a > 1), (np2 < np_lo) | (np2 > unit_hi),
                      (v2 < unit_lo) | (v2 > unit_hi), (l2 < unit_lo) | (l2 > unit_hi),
                      v[13][k] < shin_one};
                  std::int64_t clause = InputContract::kIn;
                  for (int c = 4; c >= 0; --c) clause = broken[c] != 0 ? c : clause;
                  o[k] = static_cast<std::int16_t>(clause);
                }
              });
        });
      }));
}

// ---- analysis ----
namespace {

double length_of(const Vec3Fx& v) {
  double sum = 0;
  for (const auto& c : v) sum += c.real() * c.real();
  return std::sqrt(sum);
}

Vec3 real_vec(std::span<const std::int64_t> raw, fx::Format fmt) {
  return {fx::to_real(raw[0], fmt), fx::to_real(raw[1], fmt), fx::to_real(raw[2], fmt)};
}

}  // namespace

std::vector<LyonNormRow> lyon_norm_table(const LyonModel& model) {
  const LyonFormats& f = model.formats();
  std::vector<LyonNormRow> rows;
  for (int i = 0; i <= 6; ++i) {
    LyonNormRow r;
    r.length = 0.70 + 0.05 * i;
    r.g1 = lyon::normalized_length(r.length, 1);
    r.g2 = lyon::normalized_length(r.length, 2);
    // N0 = N1 = length·(0.6, 0, 0.8) (a 3-4-5 direction), a = 0: N' is that vector.
    const Vec3 n{0.6 * r.length, 0, 0.8 * r.length};
    const LyonPixel p{n, n, 0, {0, 0, 1}, {0, 0, 1}, 1};
    const auto raw = quantize_lyon_pixel(p, f);
    const LyonStages s =
        model.stages({raw[0], raw[1], raw[2]}, {raw[3], raw[4], raw[5]}, raw[6],
                     {raw[7], raw[8], raw[9]}, {raw[10], raw[11], raw[12]}, raw[13]);
    r.fixed = length_of(s.n.out);
    rows.push_back(r);
  }
  return rows;
}

std::vector<LyonShapeRow> lyon_shape_table() {
  std::vector<LyonShapeRow> rows;
  for (const double n : {1.0, 4.0, 16.0, 64.0, 100.0, 256.0, 1000.0}) {
    LyonShapeRow r;
    r.n = n;
    for (int k = 0; k <= 3; ++k) r.max_error[k] = lyon::max_shape_error(n, k);
    rows.push_back(r);
  }
  return rows;
}

LyonOutputError lyon_output_error(const LyonModel& model, std::uint64_t samples, std::uint64_t seed,
                                  bool exact_inputs) {
  const LyonFormats& f = model.formats();
  const lyon::DatapathParams params{f.halfway, f.norm, f.h_norm, f.k};
  const double spec_lsb = std::ldexp(1.0, -f.spec.frac_bits);
  const double diff_lsb = std::ldexp(1.0, -f.diff.frac_bits);
  LyonOutputError e;
  InputContract contract = lyon_contract(f);
  double spec_sum = 0;
  double diff_sum = 0;
  for (std::uint64_t i = 0; i < samples; ++i) {
    Rng rng(seed, kStimulusStream, i);
    const LyonPixel pixel = random_lyon_pixel(rng, f);
    const auto raw = quantize_lyon_pixel(pixel, f);
    if (contract.check(raw) != InputContract::kIn) {  // the claims are made inside the contract
      ++e.out_of_contract;
      continue;
    }
    ++e.samples;
    const LyonStages s =
        model.stages({raw[0], raw[1], raw[2]}, {raw[3], raw[4], raw[5]}, raw[6],
                     {raw[7], raw[8], raw[9]}, {raw[10], raw[11], raw[12]}, raw[13]);
    // The float datapath sees exactly the quantized inputs: the error is the unit's own.
    const std::span<const std::int64_t> in(raw);
    const double shin = fx::to_real(raw[13], f.shin);
    const double n = f.arrangement == 8 ? shin * shin : shin;
    const lyon::DatapathOut ref =
        exact_inputs
            ? lyon::datapath(pixel.n0, pixel.n1, pixel.a, pixel.v, pixel.l, n, params)
            : lyon::datapath(real_vec(in.subspan(0, 3), f.vec), real_vec(in.subspan(3, 3), f.vec),
                             fx::to_real(raw[6], f.a), real_vec(in.subspan(7, 3), f.vec),
                             real_vec(in.subspan(10, 3), f.vec), n, params);
    const double spec_err = std::abs(s.spec.real() - ref.spec) / spec_lsb;
    const double diff_err = std::abs(s.diff.real() - ref.diff) / diff_lsb;
    e.spec_max = std::max(e.spec_max, spec_err);
    if ((f.arrangement == 8 ? shin * shin : shin) <= 256) {
      e.spec_max_low_n = std::max(e.spec_max_low_n, spec_err);
    }
    e.diff_max = std::max(e.diff_max, diff_err);
    spec_sum += spec_err;
    diff_sum += diff_err;
    if (ref.spec >= spec_lsb) ++e.spec_nonzero;
  }
  const auto n = static_cast<double>(std::max<std::uint64_t>(e.samples, 1));
  e.spec_mean = spec_sum / n;
  e.diff_mean = diff_sum / n;
  return e;
}

std::vector<LyonContractRow> lyon_out_of_contract(const LyonModel& model, std::uint64_t samples,
                                                  std::uint64_t seed) {
  const LyonFormats& f = model.formats();
  const lyon::DatapathParams params{f.halfway, f.norm, f.h_norm, f.k};
  InputContract contract = lyon_contract(f);
  const std::size_t clauses = contract.clauses().size();
  std::vector<LyonContractRow> rows(clauses + 1);
  for (std::size_t c = 0; c < clauses; ++c) rows[c].clause = contract.clauses()[c];
  rows[clauses].clause = "any (arbitrary bits)";
  const double vec_max = fx::to_real(f.vec.max_raw(), f.vec);
  const double a_max = fx::to_real(f.a.max_raw(), f.a);
  // Scales a vector by s, but keeps every component inside the format.
  const auto scaled = [vec_max](Vec3 v, double s) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return v * std::min(s, vec_max / std::max(m, 1e-9));
  };
  const auto record = [&](LyonContractRow& r, const std::vector<std::int64_t>& raw) {
    const std::span<const std::int64_t> in(raw);
    const LyonStages s =
        model.stages({raw[0], raw[1], raw[2]}, {raw[3], raw[4], raw[5]}, raw[6],
                     {raw[7], raw[8], raw[9]}, {raw[10], raw[11], raw[12]}, raw[13]);
    const double shin = fx::to_real(raw[13], f.shin);
    const lyon::DatapathOut ref = lyon::datapath(
        real_vec(in.subspan(0, 3), f.vec), real_vec(in.subspan(3, 3), f.vec),
        fx::to_real(raw[6], f.a), real_vec(in.subspan(7, 3), f.vec),
        real_vec(in.subspan(10, 3), f.vec), f.arrangement == 8 ? shin * shin : shin, params);
    ++r.samples;
    // Against the float value clamped to the output's range: what a saturating output could
    // give at best (the float datapath's g2 grows without bound for long N').
    const auto clamped = [](double x, fx::Format fmt) {
      return std::clamp(x, fx::to_real(fmt.min_raw(), fmt), fx::to_real(fmt.max_raw(), fmt));
    };
    const double spec_err = std::abs(s.spec.real() - clamped(ref.spec, f.spec));
    if (spec_err > r.spec_max_error || r.samples == 1) {
      r.spec_max_error = spec_err;
      r.worst_spec = s.spec.real();
      r.worst_spec_float = clamped(ref.spec, f.spec);
      r.worst = raw;
    }
    r.diff_max_error =
        std::max(r.diff_max_error, std::abs(s.diff.real() - clamped(ref.diff, f.diff)));
    r.diff_max = std::max(r.diff_max, s.diff.real());
    if (s.diff.real() > 1) ++r.diff_above_one;
  };
  const std::uint64_t per_clause = std::max<std::uint64_t>(samples / (clauses + 1), 1);
  const FieldRandom bits(model.inputs());
  std::vector<std::int64_t> raw(model.inputs().size());
  for (std::size_t c = 0; c <= clauses; ++c) {
    for (std::uint64_t i = 0, tries = 0; i < per_clause && tries < 20 * per_clause; ++tries) {
      Rng rng(seed, kStimulusStream, (std::uint64_t{c} << 40) + tries);
      if (c == clauses) {
        bits(rng, raw);
      } else {  // an in-contract pixel with this one clause broken
        LyonPixel p = random_lyon_pixel(rng, f);
        const double u = rng.uniform();
        switch (c) {
          case 0:
            p.a = 1 + u * (a_max - 1);
            break;
          case 1:  // N' too short or too long: both ends scaled alike
            if (rng.below(2) == 0) {
              p.n0 = scaled(p.n0, 0.7 * u);
              p.n1 = scaled(p.n1, 0.7 * u);
            } else {
              p.n0 = scaled(p.n0, 1.05 + u);
              p.n1 = scaled(p.n1, 1.05 + u);
            }
            break;
          case 2:
            p.v = scaled(p.v, rng.below(2) == 0 ? 0.95 * u : 1.05 + u);
            break;
          case 3:
            p.l = scaled(p.l, rng.below(2) == 0 ? 0.95 * u : 1.05 + u);
            break;
          default:
            p.shin = 0;
            break;
        }
        raw = quantize_lyon_pixel(p, f);
      }
      const int broken = contract.check(raw);
      if (broken == InputContract::kIn) continue;
      if (c < clauses && static_cast<std::size_t>(broken) != c) continue;
      record(rows[c], raw);
      ++i;
    }
  }
  return rows;
}

std::string lyon_stage_formats(const LyonModel& model) {
  const LyonFormats& f = model.formats();
  const LyonStages s = model.stages({0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, {0, 0, 0}, 0);
  std::string out;
  const auto row = [&out](std::string_view stage, std::string_view signal, fx::Format fmt) {
    out += fmt::format("  {:<6} {:<28} {:>8} {:>3} bits\n", stage, signal, fmt.str(), fmt.width());
  };
  row("in", "N0, N1, V, L components", f.vec);
  row("in", "a", f.a);
  row("in", f.arrangement == 7 ? "n" : "m", f.shin);
  row("2", "N'", s.np[0].fmt);
  if (f.norm > 0) {
    row("3", "z = N'.N'", s.n.z.fmt);
    row("4", "y = 1 - z", s.n.y.fmt);
    row("4", f.norm == 1 ? "g1 = 1 + y/2" : "g2 = 1 + (y + y^2)/2", s.n.g.fmt);
  }
  row("5", "N", s.n.out[0].fmt);
  if (f.halfway) {
    row("2", "H = (L + V)/2", s.h[0].fmt);
    row("5", f.h_norm == 0 ? "H (requantized)" : "H normalized", s.hn.out[0].fmt);
  }
  row("6", f.halfway ? "H.N" : "N.V", s.dot.fmt);
  row("6", "diff = N.L", s.diff.fmt);
  row("7", f.halfway ? "(H.N)N" : "R = 2(N.V)N - V", s.r[0].fmt);
  row("8", "D", s.d[0].fmt);
  if (f.arrangement == 7) {
    row("9", "D.D", s.dd.fmt);
  } else {
    row("9", "|D|", s.dabs[0].fmt);
    row("9", "w = m|D|/2^s (squarer input)", s.w[0].fmt);
  }
  row("10", "x/2^k (exact)", s.xk.fmt);
  row("10", "x/2^k (requantized)", s.xf.fmt);
  row("11", "sq_0 = 1 - x/2^k", s.sq[0].fmt);
  for (int j = 1; j <= f.k; ++j)
    row(std::to_string(11 + j), fmt::format("sq_{} = sq_0^{}", j, 1 << j), s.sq[j].fmt);
  row("out", "spec", s.spec.fmt);
  return out;
}

// ---- registry entry ----
namespace {

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const LyonFormats formats = LyonFormats::from_config(cfg);
  try {
    return std::make_unique<LyonModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

Stimulus make_stimulus(const PipelineModel& model, const Config&) {
  return make_lyon_stimulus(model);
}

int latency(const Config& cfg) { return LyonModel(LyonFormats::from_config(cfg)).latency(); }

// configs/lyon/default.toml by hand (Fig. 7, k = 2, g2, reflect, half_even, saturating), every
// format a constant: drop D fraction bits with convergent rounding, saturate to [lo, hi].
template <int D, std::int64_t Lo, std::int64_t Hi>
std::int64_t rq(std::int64_t v) {
  if constexpr (D > 0) v = (v + (std::int64_t{1} << (D - 1)) - 1 + ((v >> D) & 1)) >> D;
  return std::clamp(v, Lo, Hi);
}

// Laid out as the model's plan is (model/lyon_plan.cpp), so the two are compared on equal terms:
// a block of pixels at a time on structure-of-arrays temporaries, run on the same instruction
// set (fx::on_kernel_isa; the loops inside the call, so that they are compiled for that set).
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  const std::size_t n = in.size() / 14;
  const std::size_t at = out.size();
  out.resize(at + 2 * n);
  fx::on_kernel_isa([&] {
    fx::for_each_block<14, 2>(
        in.data(), out.data() + at, n,
        [](const std::int64_t* const* f, std::int64_t* const* o, std::size_t m) {
          alignas(64) std::int64_t spec[fx::kBlock], diff[fx::kBlock];  // locals: no aliasing
          for (std::size_t i = 0; i < m; ++i) {
            const auto p = [&](int field) { return f[field][i]; };  // n0 0-2, n1 3-5, a 6, shin 13
            const auto v = [&](int c) { return f[7 + c][i]; };
            const auto l = [&](int c) { return f[10 + c][i]; };
            std::int64_t np[3], nv[3], d[3];
            for (int c = 0; c < 3; ++c) {  // N' (S1.10) = rq(S4.20: (n0 << 10) + a·(n1 - n0))
              np[c] = rq<10, -2048, 2047>((p(c) << 10) + p(6) * (p(3 + c) - p(c)));
            }
            // z 1.12 from N'·N' (S5.20); y S0.12 = 1 - z; g 1.12 from 1 + (y + y²)/2 (S2.25).
            const std::int64_t z = rq<8, 0, 8191>(np[0] * np[0] + np[1] * np[1] + np[2] * np[2]);
            const std::int64_t y = rq<0, -4096, 4095>(4096 - z);
            const std::int64_t g = rq<13, 0, 8191>((std::int64_t{1} << 25) + (y << 12) + y * y);
            for (int c = 0; c < 3; ++c)
              nv[c] = rq<12, -2048, 2047>(g * np[c]);  // N S1.10 from S2.22
            diff[i] = rq<8, 0, 8191>(nv[0] * l(0) + nv[1] * l(1) + nv[2] * l(2));  // diff 1.12
            const std::int64_t dot = rq<8, -8192, 8191>(nv[0] * v(0) + nv[1] * v(1) + nv[2] * v(2));
            for (int c = 0; c < 3; ++c) {  // R S1.10 from 2(N·V)N - V (S5.21); D S1.10 = R - L
              const std::int64_t r = rq<11, -2048, 2047>(dot * nv[c] - (v(c) << 11));
              d[c] = rq<0, -2048, 2047>(r - l(c));
            }
            // D·D 3.19; x/2^k = n·D·D/8 as 13.22; xf 0.16; sq 1.16 = 1 - xf, squared twice;
            // spec 1.12.
            const std::int64_t dd =
                rq<1, 0, (std::int64_t{1} << 22) - 1>(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const std::int64_t xk = p(13) * dd;
            const std::int64_t xf = rq<6, 0, 65535>(xk);
            std::int64_t sq = rq<0, 0, 131071>(65536 - xf);
            sq = rq<16, 0, 131071>(sq * sq);
            sq = rq<16, 0, 131071>(sq * sq);
            const std::int64_t shaded = rq<4, 0, 8191>(sq);
            spec[i] = (xk >> 22) != 0 ? 0 : shaded;
          }
          std::copy_n(spec, m, o[0]);
          std::copy_n(diff, m, o[1]);
        });
  });
  return n;
}

std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  const auto& m = dynamic_cast<const LyonModel&>(model);
  const LyonFormats& f = m.formats();
  const LyonStages st = m.stages({in[0], in[1], in[2]}, {in[3], in[4], in[5]}, in[6],
                                 {in[7], in[8], in[9]}, {in[10], in[11], in[12]}, in[13]);
  std::vector<StageValue> s;
  const auto vec = [&](const std::string& name, const Vec3Fx& v) {
    for (int c = 0; c < 3; ++c) s.push_back({name + "_" + "xyz"[c], v[c]});
  };
  const auto flag = [&](const std::string& name, bool b) {
    s.push_back({name, fx::Fixed{b ? 1 : 0, fx::Format{false, 1, 0}}});
  };
  const auto norm = [&](const std::string& name, const LyonNormStages& n) {
    s.push_back({name + ".z", n.z});
    s.push_back({name + ".y", n.y});
    s.push_back({name + ".g", n.g});
    vec(name, n.out);
  };
  vec("np", st.np);
  norm("n", st.n);
  if (f.halfway) {
    vec("h", st.h);
    norm("hn", st.hn);
  }
  s.push_back({"dot", st.dot});
  s.push_back({"diff", st.diff});
  vec("r", st.r);
  vec("d", st.d);
  if (f.arrangement == 7) {
    s.push_back({"dd", st.dd});
  } else {
    vec("abs_d", st.dabs);
    vec("w", st.w);
    flag("big", st.big);
  }
  s.push_back({"xk", st.xk});
  flag("zero", st.zero);
  s.push_back({"xf", st.xf});
  for (int j = 0; j <= f.k; ++j) s.push_back({fmt::format("sq_{}", j), st.sq[j]});
  s.push_back({"spec", st.spec});
  return s;
}

// Waives the outcomes the formats allow but the arithmetic before them rules out, each with the
// bound that rules it out (docs/verification.md, "Waivers"). A wrong reason shows: hitting a
// waived point is an error.
// The instance (a regex on Verilator's hierarchy under lyon_top) computing requantization
// `point` (docs/lyon.md's stage names; "" for none).
std::string rtl_instance(const std::string& point) {
  static const std::pair<std::string_view, std::string_view> kInstances[] = {
      {"n.z", R"(\.u_norm_n\..*\.u_z\.)"},
      {"n.y", R"(\.u_norm_n\..*\.u_y\.)"},
      {"n.g", R"(\.u_norm_n\..*\.u_g\.)"},
      {"n", R"(\.u_norm_n\..*\.u_out\.)"},
      {"hn.z", R"(\.u_norm_h\..*\.u_z\.)"},
      {"hn.y", R"(\.u_norm_h\..*\.u_y\.)"},
      {"hn.g", R"(\.u_norm_h\..*\.u_g\.)"},
      {"hn", R"(\.u_norm_h\..*\.u_out\.)"},
      {"h", R"(\.u_h\.)"},
      {"dd", R"(\.u_dd\.)"},
      {"sq_0", R"(\.u_sq_0\.)"},
      {"spec", R"(\.u_spec\.)"},
      {"np", R"(\.u_lirp\..*u_round)"},
      {"diff", R"(\.u_diff\.)"},
      {"dot", R"(\.u_dot\.)"},
      {"r", R"(\.u_r\.)"},
      {"d", R"(\.u_d\.)"},
      {"dabs", R"(\.u_dabs\.)"},
      {"w", R"(\.u_w\.)"},
      {"xf", R"(\.u_xf\.)"}};
  for (const auto& [name, re] : kInstances) {
    if (point == name) return std::string(re);
  }
  // sq_1 ... sq_k: one generate loop, one instance name (Verilator writes the index as [*]).
  if (point.rfind("sq_", 0) == 0) return R"(\.u_sq_j\.)";
  return "";
}

// For outcome `name` of a requantization ("n.z.low", "dd.high"): the saturation arm of its
// fx_resize (`wide > MaxV` or `wide < MinV`, marked in the RTL) as an RTL line waiver.
void waive_line(CoverpointSampler& c, const std::string& name, const std::string& reason) {
  const auto dot = name.rfind('.');
  const std::string point = name.substr(0, dot), side = name.substr(dot + 1);
  const std::string instance = rtl_instance(point);
  if (instance.empty() || (side != "low" && side != "high")) return;
  c.line_waivers.push_back(fx_resize_saturation_waiver(instance, side, name + ": " + reason));
}

}  // namespace

void waive_lyon_outcome(CoverpointSampler& c, const std::string& name, const std::string& reason) {
  c.points.waive(name, reason);
  waive_line(c, name, reason);
}

namespace {

// Where N's and H's normalizations have the same parameters (halfway, hn's formats n's),
// Verilator makes one module of u_norm_n and u_norm_h and counts each of its lines once for both,
// under a hierarchy with ".*" in their place ("top.lyon_top.u_core.*.g_approximate.u_g...", or
// u_lyon in shade_lyon): such a point is waived where the arm is waived in both instances
// (n.g.high and hn.g.high, ...).
void waive_shared_norm_lines(CoverpointSampler& c) {
  const auto name_of = [](const LineWaiver& w) { return w.reason.substr(0, w.reason.find(": ")); };
  std::vector<LineWaiver> shared;
  for (const LineWaiver& n : c.line_waivers) {
    const std::string name = name_of(n);
    if (name.rfind("n.", 0) != 0) continue;
    const auto h =
        std::find_if(c.line_waivers.begin(), c.line_waivers.end(), [&](const LineWaiver& w) {
          return name_of(w) == "h" + name && w.file == n.file && w.marker == n.marker;
        });
    const std::string prefix = R"(\.u_norm_n\..*)";
    if (h == c.line_waivers.end() || n.hier.rfind(prefix, 0) != 0) continue;
    shared.push_back({R"(\.\*.*)" + n.hier.substr(prefix.size()), n.file, n.marker,
                      fmt::format("{} and h{} (one point for both)", n.reason, name)});
  }
  c.line_waivers.insert(c.line_waivers.end(), shared.begin(), shared.end());
}

void waive_unreachable(const LyonFormats& f, CoverpointSampler& c) {
  const auto waive = [&c](const std::string& name, const std::string& reason) {
    waive_lyon_outcome(c, name, reason);
  };
  const fx::Fixed one{1, fx::Format{false, 1, 0}};
  const auto side = [&f](fx::Fixed v, fx::Format to) {
    return fx::resize_side(v.raw, v.fmt, to, f.round);
  };
  const auto rq = [&f](fx::Fixed v, fx::Format to) {
    return fx::resize(v, to, f.round, fx::Overflow::saturate);
  };
  const auto top = [](fx::Format fmt) { return fx::Fixed{fmt.max_raw(), fmt}; };
  const auto real = [](fx::Fixed v) { return fmt::format("{}", fx::to_real(v.raw, v.fmt)); };
  for (const char* p : {"n.z.low", "hn.z.low", "dd.low"}) {
    waive(p, "a sum of squares is never negative");
  }
  // The normalization: z in [0, max z], so y = rq(1 - z) in [y_lo, y_hi]; g = 1 + poly(y)/2 rises
  // with y from y = -1/2 on (poly = y + y^2 is at least -1/4), and g1's poly = y always.
  const fx::Fixed y_lo = rq(fx::sub(one, top(f.z)), f.y);
  const fx::Fixed y_hi = rq(one, f.y);
  const int norms[] = {f.norm, f.halfway ? f.h_norm : 0};
  const char* names[] = {"n", "hn"};
  const fx::Format ins[] = {f.np, f.h};
  const fx::Format outs[] = {f.n, f.h};
  for (int v = 0; v < 2; ++v) {
    if (norms[v] == 0) continue;
    const std::string n = names[v];
    if (side(fx::sub(one, top(f.z)), f.y) >= 0) {
      waive(n + ".y.low", "y = 1 - z >= 1 - max z = " + real(fx::sub(one, top(f.z))));
    }
    const auto g_of = [&](fx::Fixed y) {
      const fx::Fixed poly = norms[v] == 1 ? y : fx::add(y, fx::mul(y, y));
      return fx::add(one, fx::scale(poly, -1));
    };
    const fx::Fixed g_hi = g_of(y_hi);
    if (side(g_hi, f.g) <= 0) waive(n + ".g.high", "g <= g(max y) = " + real(g_hi));
    const double y_min = fx::to_real(y_lo.raw, y_lo.fmt);
    const fx::Fixed g_lo = norms[v] == 2 && y_min < -0.5
                               ? fx::add(one, fx::Fixed{-1, fx::Format{true, 0, 3}})
                               : g_of(y_lo);
    if (side(g_lo, f.g) >= 0) waive(n + ".g.low", "g >= " + real(g_lo));
    // z >= 1 makes y <= 0 and (y >= -1) g <= 1: |g N'_c| <= |N'_c|; z < 1 makes |N'_c| < 1 and
    // g |N'_c| at most about 1.002 (g2; 1 for g1): inside an output that holds N' and 1.
    const fx::Format in = ins[v], out = outs[v];
    if (y_min >= -1 && out.is_signed && out.int_bits >= std::max(in.int_bits, 1) &&
        out.frac_bits >= in.frac_bits) {
      const std::string why =
          fmt::format("|g N'_c| stays within {} (z >= 1: g <= 1) or near 1 (z < 1), which {} holds",
                      in.str(), out.str());
      waive(n + ".low", why);
      waive(n + ".high", why);
    }
  }
  // H = (L + V)/2 lies between the smallest and the largest vector component.
  if (side(top(f.vec), f.h) <= 0) {
    waive("h.high", "(L + V)/2 <= max component " + real(top(f.vec)) + ", which h holds");
  }
  if (side(fx::Fixed{f.vec.min_raw(), f.vec}, f.h) >= 0) {
    waive("h.low", "(L + V)/2 >= min component, which h holds");
  }
  // The shape function: xf in [0, max xf], sq_0 = rq(1 - xf) at most rq(1), squares of values
  // at most 1 no larger.
  if (side(fx::sub(one, top(f.xf)), f.sq) >= 0) {
    waive("sq_0.low", "1 - xf >= 1 - max xf = " + real(fx::sub(one, top(f.xf))));
  }
  const fx::Fixed s_hi = rq(one, f.sq);
  if (!f.xf.is_signed && side(one, f.sq) <= 0) {
    waive("sq_0.high", "1 - xf <= 1, which sq holds");
  }
  if (fx::to_real(s_hi.raw, s_hi.fmt) <= 1 && side(fx::mul(s_hi, s_hi), f.sq) <= 0) {
    for (int j = 1; j <= f.k; ++j) {
      waive(fmt::format("sq_{}.high", j), "the square of a value in [0, 1] is in [0, 1]");
    }
  }
  if (side(s_hi, f.spec) <= 0) {
    waive("spec.high", "sq_k <= " + real(s_hi) + ", which spec holds");
  }
  if (f.arrangement == 8 && f.k % 2 == 1) {
    waive("compare.equal",
          "x/2^k = w_x^2 + w_y^2 + w_z^2 with binary fractions w_c < 1: 4^m is a sum of "
          "three squares only as (2^m)^2 + 0 + 0, so x/2^k is never exactly 1");
  }
}

// Every requantization the configuration has (docs/lyon.md's stage table: a vector's components
// one point) saturating low, high and not; the zero flag set and clear, and near the comparator
// x/2^k >= 1: exactly 1, within 2^-8 below and above; arrangement 8's big flag set and clear; the
// normalization (order 1 or 2) correcting a length (g != 1); the output through the k squarings
// (not zeroed, sq_k > 0).
CoverpointSampler coverpoints(const PipelineModel& model, const Config&) {
  const auto& m = dynamic_cast<const LyonModel&>(model);
  const LyonFormats f = m.formats();
  CoverpointSampler c;
  std::vector<LyonRqSide> sides;
  (void)m.stages({0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, {0, 0, 0}, 0, &sides);
  std::vector<std::string_view> points;  // the requantizations, each once, in stage order
  std::vector<Coverpoints::Sides> first;
  for (const LyonRqSide& s : sides) {
    if (std::find(points.begin(), points.end(), s.point) != points.end()) continue;
    points.push_back(s.point);
    first.push_back(c.points.declare_sides(std::string(s.point), s.from, s.to, f.round));
    // The outcomes the formats rule out have no coverpoint; their RTL arms are waived.
    const std::string why = fmt::format("{} rounded into {} cannot", s.from.str(), s.to.str());
    if (first.back().low == Coverpoints::kNone) {
      waive_line(c, std::string(s.point) + ".low", why + " go below it");
    }
    if (first.back().high == Coverpoints::kNone) {
      waive_line(c, std::string(s.point) + ".high", why + " go above it");
    }
  }
  const std::size_t zero = c.points.declare("zero.set");
  c.points.declare("zero.clear");
  const std::size_t cmp = c.points.declare("compare.equal");
  c.points.declare("compare.just_below");
  c.points.declare("compare.just_above");
  const bool fig8 = f.arrangement == 8;
  const std::size_t big = fig8 ? c.points.declare("big.set") : 0;
  if (fig8) c.points.declare("big.clear");
  std::vector<std::size_t> norm;  // N's, then H's (halfway)
  if (f.norm > 0) norm.push_back(c.points.declare(fmt::format("norm.n.g{}", f.norm)));
  if (f.halfway && f.h_norm > 0) {
    norm.push_back(c.points.declare(fmt::format("norm.hn.g{}", f.h_norm)));
  }
  const std::size_t shape = c.points.declare(fmt::format("shape.k{}", f.k));
  waive_unreachable(f, c);
  waive_shared_norm_lines(c);
  c.sample = [=](PipelineModel& model, std::span<const std::int64_t> in, Coverpoints& cp) {
    const auto& lm = dynamic_cast<const LyonModel&>(model);
    std::vector<LyonRqSide> s;
    const LyonStages st = lm.stages({in[0], in[1], in[2]}, {in[3], in[4], in[5]}, in[6],
                                    {in[7], in[8], in[9]}, {in[10], in[11], in[12]}, in[13], &s);
    for (const LyonRqSide& r : s) {
      const auto at = std::find(points.begin(), points.end(), r.point) - points.begin();
      cp.hit_side(first[static_cast<std::size_t>(at)], r.side);
    }
    cp.hit(zero + (st.zero ? 0 : 1));
    // x/2^k against 1, exactly: raw against 2^frac.
    const std::int64_t one = std::int64_t{1} << st.xk.fmt.frac_bits;
    const std::int64_t near = std::int64_t{1} << std::max(0, st.xk.fmt.frac_bits - 8);
    if (st.xk.raw == one) cp.hit(cmp);
    if (st.xk.raw < one && st.xk.raw >= one - near) cp.hit(cmp + 1);
    if (st.xk.raw > one && st.xk.raw <= one + near) cp.hit(cmp + 2);
    if (fig8) cp.hit(big + (st.big ? 0 : 1));
    const std::int64_t g_one = std::int64_t{1} << f.g.frac_bits;
    std::size_t j = 0;
    if (f.norm > 0 && st.n.g.raw != g_one) cp.hit(norm[j]);
    if (f.norm > 0) ++j;
    if (f.halfway && f.h_norm > 0 && st.hn.g.raw != g_one) cp.hit(norm[j]);
    if (!st.zero && st.sq[f.k].raw > 0) cp.hit(shape);
  };
  return c;
}

ModelError float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  const LyonModel model(LyonFormats::from_config(cfg));
  const LyonOutputError l = lyon_output_error(model, samples, seed, /*exact_inputs=*/true);
  ModelError e;
  e.max_lsb = l.spec_max;
  e.mean_lsb = l.spec_mean;
  e.max_abs = l.spec_max * std::ldexp(1.0, -model.formats().spec.frac_bits);
  e.samples = l.samples;
  return e;
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  std::vector<LyonModel> models;
  for (const Config& cfg : configs) models.emplace_back(LyonFormats::from_config(cfg));
  // The normalization table uses the first configuration that normalizes N.
  std::size_t norm = 0;
  while (norm + 1 < models.size() && models[norm].formats().norm == 0) ++norm;
  const LyonModel& nm = models[norm];
  out.print("Approximate normalization: length of a vector after g (Lyon, Fig. 4)\n");
  out.print("  {:>6}  {:>10}  {:>10}  {:>10}   fixed: {} (g{})\n", "length", "g1 float", "g2 float",
            "fixed", configs[norm].name(), nm.formats().norm);
  out.table(fmt::format("Approximate normalization: length after g, fixed: {} (g{})",
                        configs[norm].name(), nm.formats().norm),
            {"length", "g1_float", "g2_float", "fixed"});
  for (const auto& r : lyon_norm_table(nm)) {
    out.print("  {:>6.2f}  {:>10.5f}  {:>10.5f}  {:>10.5f}\n", r.length, r.g1, r.g2, r.fixed);
    out.row({r.length, r.g1, r.g2, r.fixed});
  }
  out.print("  at y = 1/2 (length 0.7071): g1 = {}, g2 = {}, exact 1/sqrt(1/2) = {:.4f}\n\n",
            lyon::g1(0.5), lyon::g2(0.5), 1 / std::sqrt(0.5));

  out.print("Shape function: max over alpha of |f_k(x) - cos^n alpha|, x = (n/2)|D|^2, float\n");
  out.print("  {:>6}  {:>9}  {:>9}  {:>9}  {:>9}\n", "n", "k=0", "k=1", "k=2", "k=3");
  out.table("Shape function: max over alpha of |f_k(x) - cos^n alpha|, float",
            {"n", "k0", "k1", "k2", "k3"});
  for (const auto& r : lyon_shape_table()) {
    out.print("  {:>6}  {:>9.6f}  {:>9.6f}  {:>9.6f}  {:>9.6f}\n", r.n, r.max_error[0],
              r.max_error[1], r.max_error[2], r.max_error[3]);
    out.row(
        {static_cast<double>(r.n), r.max_error[0], r.max_error[1], r.max_error[2], r.max_error[3]});
  }
  out.print(
      "\nFixed-point output against the float datapath (same quantized inputs), in output "
      "LSBs; {} random pixels, seed {}\n",
      samples, seed);
  out.print("  {:<14} {:>9} {:>13} {:>9} {:>9} {:>9} {:>11}\n", "config", "spec max", "max n<=256",
            "spec mean", "diff max", "diff mean", "highlights");
  out.table("Fixed-point output against the float datapath, in output LSBs",
            {"config", "spec_max", "spec_max_n_le_256", "spec_mean", "diff_max", "diff_mean",
             "highlights_percent"});
  std::uint64_t left_out = 0;
  for (std::size_t i = 0; i < models.size(); ++i) {
    const LyonOutputError e = lyon_output_error(models[i], samples, seed);
    left_out += e.out_of_contract;
    out.print("  {:<14} {:>9.2f} {:>13.2f} {:>9.3f} {:>9.2f} {:>9.3f} {:>10.1f}%\n",
              configs[i].name(), e.spec_max, e.spec_max_low_n, e.spec_mean, e.diff_max, e.diff_mean,
              100.0 * static_cast<double>(e.spec_nonzero) / static_cast<double>(e.samples));
    out.row({configs[i].name(), e.spec_max, e.spec_max_low_n, e.spec_mean, e.diff_max, e.diff_mean,
             100.0 * static_cast<double>(e.spec_nonzero) / static_cast<double>(e.samples)});
  }
  out.print(
      "  (inside the input contract, docs/lyon.md: pixels outside it are left out; here {} of "
      "{} over all configurations)\n",
      left_out, samples * models.size());

  // Outside the contract: each clause broken alone (an in-contract pixel with that one input
  // moved out), and arbitrary bit patterns over the whole formats, as co-simulation draws them.
  out.print(
      "\nOutside the input contract: the fixed-point unit against the same datapath in float "
      "(same quantized inputs, clamped to the output range), absolute; each clause broken "
      "alone, then arbitrary bits; {} pixels per row, seed {}\n",
      std::max<std::uint64_t>(samples / 6, 1), seed);
  out.table("Outside the input contract: fixed point against the float datapath, absolute",
            {"config", "clause", "pixels", "spec_max_error", "worst_spec", "worst_spec_float",
             "diff_max_error", "diff_max", "diff_above_one"});
  for (std::size_t i = 0; i < models.size(); ++i) {
    out.print("  {}\n  {:<24} {:>7} {:>10} {:>19} {:>10} {:>9} {:>9}\n", configs[i].name(),
              "clause broken first", "pixels", "spec err", "worst: fixed/float", "diff err",
              "diff max", "diff > 1");
    const std::vector<LyonContractRow> rows = lyon_out_of_contract(models[i], samples, seed);
    const LyonContractRow* worst = nullptr;
    for (const LyonContractRow& r : rows) {
      out.print("  {:<24} {:>7} {:>10.4f} {:>9.4f}/{:<9.4f} {:>10.4f} {:>9.4f} {:>9}\n", r.clause,
                r.samples, r.spec_max_error, r.worst_spec, r.worst_spec_float, r.diff_max_error,
                r.diff_max, r.diff_above_one);
      out.row({configs[i].name(), r.clause, static_cast<double>(r.samples), r.spec_max_error,
               r.worst_spec, r.worst_spec_float, r.diff_max_error, r.diff_max,
               static_cast<double>(r.diff_above_one)});
      if (worst == nullptr || r.spec_max_error > worst->spec_max_error) worst = &r;
    }
    if (worst != nullptr && !worst->worst.empty()) {
      std::string fields;
      const auto& ins = models[i].inputs();
      for (std::size_t k = 0; k < ins.size(); ++k) {
        fields += fmt::format("{}{}={}", k == 0 ? "" : " ", ins[k].name,
                              fx::to_real(worst->worst[k], ins[k].fmt));
      }
      out.print("  largest spec error ({}): {}\n", worst->clause, fields);
    }
  }
  for (std::size_t i = 0; i < models.size(); ++i) {
    out.print("\nStage formats of {} ({}, latency {} cycles)\n{}", configs[i].origin(),
              configs[i].description(), models[i].latency(), lyon_stage_formats(models[i]));
  }
}

}  // namespace

const PipelineInfo& lyon_pipeline() {
  static const PipelineInfo info{
      .name = "lyon",
      .summary = "Lyon specular unit: LIRP, g1/g2 normalization, D, x, f_k (Figs. 7, 8), diffuse",
      .top = "lyon_top",
      .rtl_files = {"rtl/common", "rtl/lirp/lirp_core.sv", "rtl/lyon/lyon_norm.sv",
                    "rtl/lyon/lyon_x.sv", "rtl/lyon/lyon_shape.sv", "rtl/lyon/lyon_core.sv",
                    "rtl/lyon/lyon_top.sv"},
      .ports = {{"in_n0_i", true, {"n0_x", "n0_y", "n0_z"}},
                {"in_n1_i", true, {"n1_x", "n1_y", "n1_z"}},
                {"in_a_i", true, {"a"}},
                {"in_v_i", true, {"v_x", "v_y", "v_z"}},
                {"in_l_i", true, {"l_x", "l_y", "l_z"}},
                {"in_shin_i", true, {"shin"}},
                {"out_spec_o", false, {"spec"}},
                {"out_diff_o", false, {"diff"}}},
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = true,
      .default_vectors = 1000000,
      .latency = latency,
      .one_per_clock = true,
      .cycles = one_per_clock<latency>,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract =
          [](const PipelineModel& model, const Config&) {
            return lyon_contract(dynamic_cast<const LyonModel&>(model).formats());
          },
      .float_error = float_error,
      .analyze = analyze,
      .mutants = {{"lyon-g2", "default", "rtl/lyon/lyon_norm.sv", "if (en_i[1]) g_q <= g_d;",
                   "if (en_i[1]) g_q <= g_d + 1'b1;", "g2 one LSB too large"},
                  {"lyon-square", "default", "rtl/lyon/lyon_shape.sv",
                   "fx_rq #(.InFmt(SqSqFmt), .OutFmt(SqFmt), .Round(Round))",
                   "fx_rq #(.InFmt(SqSqFmt), .OutFmt(SqFmt), .Round(fx_pkg::FxTruncate))",
                   "shape-function squarers truncate instead of rounding to even (one LSB)"},
                  {"lyon-compare", "default", "rtl/lyon/lyon_x.sv",
                   "assign zero_d = |xk[XkW-1:XkFrac];", "assign zero_d = |xk[XkW-1:XkFrac-1];",
                   "comparator fires at x/2^k >= 1/2 instead of >= 1"},
                  {"lyon-fig8-w", "fig8_k1", "rtl/lyon/lyon_x.sv",
                   "fx_rq #(.InFmt(UFmt), .OutFmt(WFmt), .Round(Round))",
                   "fx_rq #(.InFmt(UFmt), .OutFmt(WFmt), .Round(fx_pkg::FxTruncate))",
                   "Fig. 8 squarer inputs truncated instead of rounded (one LSB)"},
                  {"lyon-sqrt2", "fig8_k2", "rtl/lyon/lyon_x.sv",
                   "localparam bit [31:0] S         = (K + 2) / 2;",
                   "localparam bit [31:0] S         = (K + 1) / 2;",
                   "Fig. 8 shift without the even-k sqrt(2) correction"},
                  {"lyon-halfway", "halfway", "rtl/lyon/lyon_core.sv", ".b_i(v_q1[c*VecW+:VecW])",
                   ".b_i(l_q1[c*VecW+:VecW])", "H = (L + L)/2 instead of (L + V)/2"},
                  {"lyon-diffuse-delay", "default", "rtl/lyon/lyon_core.sv",
                   "pipe_delay #(.Width(DiffW), .Depth(Depth - 7))",
                   "pipe_delay #(.Width(DiffW), .Depth(Depth - 8))",
                   "diffuse term one stage short: paired with the wrong pixel"}},
  };
  return info;
}

}  // namespace phongsim
