// Lyon's random geometry, a pixel at a time and a block at a time (sim/pipelines/lyon_geometry.h).
#include "sim/pipelines/lyon_geometry.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "base/rng.h"
#include "model/fixed.h"
#include "model/plan.h"
#include "sim/pipelines/lyon.h"

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

void quantize_lyon_pixel(const LyonPixel& p, const LyonFormats& f, std::span<std::int64_t> out) {
  const auto q = [](double x, fx::Format fmt) {
    return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
  };
  const double values[14] = {p.n0.x, p.n0.y, p.n0.z, p.n1.x, p.n1.y, p.n1.z, p.a,
                             p.v.x,  p.v.y,  p.v.z,  p.l.x,  p.l.y,  p.l.z,  p.shin};
  for (std::size_t i = 0; i < 14; ++i) {
    out[i] = q(values[i], i == 6 ? f.a : i == 13 ? f.shin : f.vec);
  }
}

std::vector<std::int64_t> quantize_lyon_pixel(const LyonPixel& p, const LyonFormats& f) {
  std::vector<std::int64_t> raw(14);
  quantize_lyon_pixel(p, f, raw);
  return raw;
}

// ---- a block at a time ----

namespace lyon_geometry_detail {
namespace {

// The pixel's draws, in random_lyon_pixel's order: N0's z and φ, N1's tilt angle, z and φ, a,
// the shininess, L's z and φ, V's tilt angle, z and φ.
enum Draw { kN0z, kN0phi, kN1angle, kN1z, kN1phi, kA, kShin, kLz, kLphi, kVangle, kVz, kVphi };

// Rng::uniform() of draw k from `state`, exactly, with no 64-bit conversion (which x86-64-v3
// cannot vectorize): the 53 bits as two exact halves.
inline double uniform(std::uint64_t state, std::uint64_t k) {
  const std::uint64_t bits = Rng::output(state, k) >> 11;
  const auto exact = [](std::uint64_t x) {  // x < 2^32
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(0x1p52) | x) - 0x1p52;
  };
  return (exact(bits >> 32) * 0x1p32 + exact(bits & 0xffffffffU)) * 0x1p-53;
}

// fdlibm's kernels (Sun Microsystems, 1993; permission to use granted) on [-π/4, π/4] after
// reducing x by the nearest multiple of π/2, whose first 33 bits make k·(π/2) exact for k <= 4.
inline void sincos_inline(double x, double& s, double& c) {
  constexpr double kPio2Hi = 1.57079632673412561417e+00, kPio2Lo = 6.07710050650619224932e-11;
  const double kt = x * (2 / std::numbers::pi) + kRound;
  const double k = kt - kRound;
  const auto quadrant = std::bit_cast<std::uint64_t>(kt) - std::bit_cast<std::uint64_t>(kRound);
  const double r = (x - k * kPio2Hi) - k * kPio2Lo;
  const double z = r * r;
  const double ps =
      -1.66666666666666324348e-01 +
      z * (8.33333333332248946124e-03 +
           z * (-1.98412698298579493134e-04 +
                z * (2.75573137070700676789e-06 +
                     z * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10))));
  const double sin_r = r + r * z * ps;
  const double pc =
      z * (4.16666666666666019037e-02 +
           z * (-1.38888888888741095749e-03 +
                z * (2.48015872894767294178e-05 +
                     z * (-2.75573143513906633035e-07 +
                          z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11)))));
  const double hz = 0.5 * z;
  const double w = 1 - hz;
  const double cos_r = w + (((1 - w) - hz) + z * pc);
  // sin(r + kπ/2) and cos(r + kπ/2) by quadrant.
  const bool odd = (quadrant & 1) != 0;
  const double s0 = odd ? cos_r : sin_r;
  const double c0 = odd ? sin_r : cos_r;
  s = (quadrant & 2) != 0 ? -s0 : s0;
  c = ((quadrant + 1) & 2) != 0 ? -c0 : c0;
}

inline Vec3 unit(double u_z, double u_phi) {
  const double z = 2 * u_z - 1;
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  double s = 0, c = 0;
  sincos_inline(2 * std::numbers::pi * u_phi, s, c);
  return {r * c, r * s, z};
}

inline Vec3 tilt(Vec3 a, double angle, Vec3 t, bool& fragile) {
  t = t - dot(t, a) * a;
  const double len = length(t);
  fragile |= !(len >= kMinPerpendicular);
  double s = 0, c = 0;
  sincos_inline(angle, s, c);
  return c * a + s * (t * (1 / len));
}

// The chunk's 12 vector components quantized to `fmt` (quantize_far; `tol` in LSBs) into raw, in
// the chunk's order (N0, N1, V, L); near[i] set where pixel i has a field near a boundary.
void quantize_chunk(const Chunk& ch, std::size_t count, fx::Format fmt, double tol,
                    std::int64_t (*raw)[kChunk], std::int64_t* near) {
  const double scale = std::ldexp(1.0, fmt.frac_bits);
  const auto lo = static_cast<double>(fmt.min_raw()), hi = static_cast<double>(fmt.max_raw());
  const double* src[12] = {ch.n0[0], ch.n0[1], ch.n0[2], ch.n1[0], ch.n1[1], ch.n1[2],
                           ch.v[0],  ch.v[1],  ch.v[2],  ch.l[0],  ch.l[1],  ch.l[2]};
  std::fill_n(near, count, 0);
  for (int k = 0; k < 12; ++k) {
    const double* x = src[k];
    std::int64_t* out = raw[k];
    fx::on_kernel_isa([&] {
      // Copied: the stores through `out` (int64_t) could alias the captured count (size_t).
      const std::size_t n = count;
      const double sc = scale, t = tol, low = lo, high = hi;
      const double* in = x;
      std::int64_t* o = out;
      std::int64_t* flag = near;
      for (std::size_t i = 0; i < n; ++i) {
        bool close = false;
        o[i] = quantize_far(in[i], sc, t, low, high, close);
        flag[i] |= static_cast<std::int64_t>(close);  // int64_t: a mask of doubles' width
      }
    });
  }
}

}  // namespace

void sincos(double x, double& s, double& c) { sincos_inline(x, s, c); }

void approximate_geometry(const std::uint64_t* states, const double* shin, std::size_t count,
                          bool fig8, Chunk& ch) {
  // Captured by value: a captured reference would be reloaded after every store to the chunk.
  fx::on_kernel_isa([states, shin, count, fig8, c = &ch] {
    Chunk& ch = *c;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t st = states[i];
      bool fragile = false;
      const Vec3 n0 = unit(uniform(st, kN0z), uniform(st, kN0phi));
      const Vec3 n1 = tilt(n0, uniform(st, kN1angle) * std::numbers::pi / 2,
                           unit(uniform(st, kN1z), uniform(st, kN1phi)), fragile);
      const double a = uniform(st, kA);
      const Vec3 normal = normalized(n0 * (1 - a) + n1 * a);
      const double n = shin[i];
      const double n_equiv = fig8 ? n * n : n;
      const Vec3 l = unit(uniform(st, kLz), uniform(st, kLphi));
      const Vec3 mirror = 2 * dot(normal, l) * normal - l;
      const Vec3 v = tilt(mirror, uniform(st, kVangle) * 3 / std::sqrt(n_equiv),
                          unit(uniform(st, kVz), uniform(st, kVphi)), fragile);
      ch.n0[0][i] = n0.x, ch.n0[1][i] = n0.y, ch.n0[2][i] = n0.z;
      ch.n1[0][i] = n1.x, ch.n1[1][i] = n1.y, ch.n1[2][i] = n1.z;
      ch.v[0][i] = v.x, ch.v[1][i] = v.y, ch.v[2][i] = v.z;
      ch.l[0][i] = l.x, ch.l[1][i] = l.y, ch.l[2][i] = l.z;
      ch.fragile[i] = fragile;
    }
  });
}

}  // namespace lyon_geometry_detail

void random_lyon_pixels(std::span<const std::uint64_t> states, std::span<const std::uint32_t> rows,
                        const LyonFormats& f, std::span<std::int64_t> out) {
  using namespace lyon_geometry_detail;
  const double shin_max = fx::to_real(f.shin.max_raw(), f.shin);
  const double log_shin_max = std::log(shin_max);
  // The block's rounding needs x·2^frac well inside double's integers and a tolerance below
  // half an LSB; wider vector formats take the pixel-at-a-time path.
  const bool fast = f.vec.frac_bits <= 22 && f.vec.width() <= 48;
  const double tol = kGeometryError * std::ldexp(1.0, f.vec.frac_bits);
  Chunk ch;
  double shin[kChunk];
  std::int64_t raw[12][kChunk];
  std::int64_t near[kChunk];
  for (std::size_t first = 0; first < states.size(); first += kChunk) {
    const std::size_t count = std::min(kChunk, states.size() - first);
    const std::uint64_t* st = states.data() + first;
    // The shininess as random_lyon_pixel computes it (the library's exp and log).
    for (std::size_t i = 0; i < count; ++i)
      shin[i] = std::max(1.0, std::round(std::exp(uniform(st[i], kShin) * log_shin_max)));
    if (fast) {
      approximate_geometry(st, shin, count, f.arrangement == 8, ch);
      quantize_chunk(ch, count, f.vec, tol, raw, near);
    }
    for (std::size_t i = 0; i < count; ++i) {
      const std::span<std::int64_t> row = out.subspan(14 * std::size_t{rows[first + i]}, 14);
      if (!fast || ch.fragile[i] || near[i] != 0) {
        Rng rng = Rng::from_state(st[i]);
        quantize_lyon_pixel(random_lyon_pixel(rng, f), f, row);
        continue;
      }
      // Fields in the model's input order: N0, N1, a, V, L, shininess.
      constexpr int kField[12] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12};
      for (int k = 0; k < 12; ++k) row[kField[k]] = raw[k][i];
      row[6] = fx::quantize(uniform(st[i], kA), f.a, fx::Round::half_even, fx::Overflow::saturate);
      row[13] = fx::quantize(shin[i], f.shin, fx::Round::half_even, fx::Overflow::saturate);
    }
  }
}

}  // namespace phongsim
