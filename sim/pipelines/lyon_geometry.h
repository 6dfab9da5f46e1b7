// Lyon's random geometry (sim/pipelines/lyon_geometry.cpp): random_lyon_pixel, declared in
// sim/pipelines/lyon.h, one pixel at a time with the C library's sin and cos; and the same pixels
// a block at a time, quantized, without a library call in the loop. The block's geometry uses its
// own sine and cosine (a few units in the last place from the library's), so it can differ from
// random_lyon_pixel's by a bounded amount; a field whose value lies within that bound of a rounding
// boundary cannot be trusted to round the same way, and its pixel is made again by
// random_lyon_pixel. The quantized fields are therefore those of quantize_lyon_pixel(
// random_lyon_pixel(...)), bit for bit (tests/lyon_test.cpp).
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "base/vec3.h"
#include "model/lyon.h"

namespace phongsim {

// For each i: the pixel random_lyon_pixel draws from Rng::from_state(states[i]), quantized
// (quantize_lyon_pixel) into out[14 * rows[i] ...]. Runs on the kernel instruction set.
void random_lyon_pixels(std::span<const std::uint64_t> states, std::span<const std::uint32_t> rows,
                        const LyonFormats& f, std::span<std::int64_t> out);

namespace lyon_geometry_detail {

// sin(x) and cos(x) for 0 <= x <= 2π: within kSinCosError of the exact values (and so within
// kSinCosError + 2^-53 of the C library's). Inline so that a vectorized loop can use it.
constexpr double kSinCosError = 0x1p-52;

// The fast path's geometry against random_lyon_pixel's: no component of N0, N1, V or L differs by
// more than kGeometryError, unless the pixel is fragile: a tilt's random direction within
// kMinPerpendicular of its axis, where normalizing the perpendicular part would magnify the
// sine's error by more than 1/kMinPerpendicular. A bound on the rest: the sines differ by at most
// 2^-51; a unit vector from them by about 2^-50; a tilt's perpendicular part by 2^-48 before its
// normalization multiplies that by at most 2/kMinPerpendicular (N1: about 2^-43); N by twice
// that after its normalization (|N'| >= 1/sqrt 2); the mirror direction 2(N·L)N - L by about
// 2^-39; V's tilt by 2^3 more before and 2^5 in its normalization: about 2^-31, and kGeometryError
// is 2^5 above it. tests/lyon_test.cpp checks the largest difference on random pixels stays far
// below the bound.
constexpr double kGeometryError = 0x1p-26;
constexpr double kMinPerpendicular = 0x1p-4;

// The geometry of `count` pixels (count <= kChunk) from their generators' states, in
// structure-of-arrays form; `shin` is each pixel's shininess (exact, from the library's exp and
// log). A pixel with fragile[i] set must be made by random_lyon_pixel.
constexpr std::size_t kChunk = 128;
struct Chunk {
  double n0[3][kChunk], n1[3][kChunk], v[3][kChunk], l[3][kChunk];
  bool fragile[kChunk];
};
void approximate_geometry(const std::uint64_t* states, const double* shin, std::size_t count,
                          bool fig8, Chunk& c);

constexpr double kRound = 0x1.8p52;  // x + kRound - kRound: x rounded to an integer, |x| < 2^51

// x·scale (|x·scale| < 2^50, scale a power of two) rounded to nearest, ties to even, and
// saturated to [lo, hi]: fx::quantize(x', ...) with half_even and saturate for every x' within
// tol/scale of x, unless `near` is set (x·scale within tol of a half-integer, where they may
// round apart). Inline so that a vectorized loop can use it.
inline std::int64_t quantize_far(double x, double scale, double tol, double lo, double hi,
                                 bool& near) {
  const double s = x * scale;  // exact: a power of two
  const double r = (s + kRound) - kRound;
  near |= !(std::abs(s - r) < 0.5 - tol);
  const double q = std::min(std::max(r, lo), hi) + kRound;
  return static_cast<std::int64_t>(std::bit_cast<std::uint64_t>(q) -
                                   std::bit_cast<std::uint64_t>(kRound));
}

// approximate_geometry's sine and cosine, for tests.
void sincos(double x, double& s, double& c);

}  // namespace lyon_geometry_detail
}  // namespace phongsim
