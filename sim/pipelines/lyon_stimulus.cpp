// Stimulus for the Lyon pipeline: directed corners that hit its decision points exactly, and
// random vectors that are half plausible geometry (so the highlight is often non-zero) and half
// arbitrary bit patterns (so saturation and degenerate inputs are exercised).
#include <cmath>
#include <numbers>

#include "base/vec3.h"
#include "model/lyon.h"
#include "sim/pipelines/lyon_stimulus.h"

namespace phongsim {
namespace {

Vec3 random_unit(Rng& rng) {
  const double z = 2 * rng.uniform() - 1;
  const double phi = 2 * std::numbers::pi * rng.uniform();
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Rotates `a` towards a random direction by `angle` (radians).
Vec3 tilt(Rng& rng, Vec3 a, double angle) {
  Vec3 t = random_unit(rng);
  t = t - dot(t, a) * a;  // perpendicular part
  const double len = length(t);
  if (len < 1e-9) return a;
  return std::cos(angle) * a + std::sin(angle) * (t * (1 / len));
}

}  // namespace

LyonPixel random_lyon_pixel(Rng& rng, const LyonFormats& f) {
  LyonPixel p;
  p.n0 = random_unit(rng);
  p.n1 = tilt(rng, p.n0, rng.uniform() * std::numbers::pi / 2);
  p.a = rng.uniform();
  const Vec3 n = normalized(p.n0 * (1 - p.a) + p.n1 * p.a);
  const double shin_max = fx::to_real(f.shin.max_raw(), f.shin);
  p.shin = std::max(1.0, std::round(std::exp(rng.uniform() * std::log(shin_max))));
  const double n_equiv = f.arrangement == 8 ? p.shin * p.shin : p.shin;
  p.l = random_unit(rng);
  const Vec3 mirror = 2 * dot(n, p.l) * n - p.l;
  p.v = tilt(rng, mirror, rng.uniform() * 3 / std::sqrt(n_equiv));
  return p;
}

std::vector<std::int64_t> quantize_lyon_pixel(const LyonPixel& p, const LyonFormats& f) {
  const auto q = [](double x, fx::Format fmt) {
    return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
  };
  return {q(p.n0.x, f.vec), q(p.n0.y, f.vec), q(p.n0.z, f.vec), q(p.n1.x, f.vec), q(p.n1.y, f.vec),
          q(p.n1.z, f.vec), q(p.a, f.a),      q(p.v.x, f.vec),  q(p.v.y, f.vec),  q(p.v.z, f.vec),
          q(p.l.x, f.vec),  q(p.l.y, f.vec),  q(p.l.z, f.vec),  q(p.shin, f.shin)};
}

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
    const auto p = quantize_lyon_pixel(random_lyon_pixel(rng, f), f);
    std::copy(p.begin(), p.end(), in.begin());
  };
  return Stimulus(model, std::move(directed), random);
}

}  // namespace phongsim
