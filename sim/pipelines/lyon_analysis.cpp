#include "sim/pipelines/lyon_analysis.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ref/lyon_float.h"
#include "sim/pipelines/lyon_stimulus.h"

namespace phongsim {
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
  e.samples = samples;
  double spec_sum = 0;
  double diff_sum = 0;
  for (std::uint64_t i = 0; i < samples; ++i) {
    Rng rng(seed, kStimulusStream, i);
    const LyonPixel pixel = random_lyon_pixel(rng, f);
    const auto raw = quantize_lyon_pixel(pixel, f);
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
  e.spec_mean = spec_sum / static_cast<double>(samples);
  e.diff_mean = diff_sum / static_cast<double>(samples);
  return e;
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

}  // namespace phongsim
