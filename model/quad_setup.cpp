#include "model/quad_setup.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace phongsim {
namespace {

std::int64_t floor_div(std::int64_t a, std::int64_t b) {  // b > 0
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}
std::int64_t ceil_div(std::int64_t a, std::int64_t b) { return -floor_div(-a, b); }  // b > 0

}  // namespace

QuadProgram quad_program(const quad::SubpixelTri& tri_in, const std::array<quad::Coeffs, 3>& colour,
                         const QuadFormats& f, QuadScreen screen) {
  quad::check(tri_in);
  const int s = tri_in.S;
  if (s != f.sub_bits) {
    throw Error(
        fmt::format("triangle has {} subpixel bits; the configuration has {}", s, f.sub_bits));
  }
  const std::int64_t limit = std::int64_t{2048} << s;
  for (int v = 0; v < 3; ++v) {
    if (tri_in.X[v] < 0 || tri_in.X[v] > limit || tri_in.Y[v] < 0 || tri_in.Y[v] > limit) {
      throw Error(fmt::format("vertex ({}, {}) is outside the 2048 x 2048 screen",
                              std::ldexp(static_cast<double>(tri_in.X[v]), -s),
                              std::ldexp(static_cast<double>(tri_in.Y[v]), -s)));
    }
  }
  QuadProgram p;  // no rows until proven otherwise
  const std::int64_t orient = quad::orientation(tri_in);
  if (orient == 0) return p;
  const quad::SubpixelTri tri = orient > 0 ? tri_in : quad::reversed(tri_in);
  const std::int64_t unit = std::int64_t{1} << s;
  const std::int64_t half = unit / 2;

  // Box of pixel centres: x with x·2^S + h in [min X, max X], clipped to the screen.
  const auto [minx, maxx] = std::minmax({tri.X[0], tri.X[1], tri.X[2]});
  const auto [miny, maxy] = std::minmax({tri.Y[0], tri.Y[1], tri.Y[2]});
  std::int64_t x0 = std::max<std::int64_t>(0, ceil_div(minx - half, unit));
  std::int64_t x1 = std::min<std::int64_t>(screen.width - 1, floor_div(maxx - half, unit));
  std::int64_t y0 = std::max<std::int64_t>(0, ceil_div(miny - half, unit));
  std::int64_t y1 = std::min<std::int64_t>(screen.height - 1, floor_div(maxy - half, unit));

  // Edges i -> j of the positive triangle: E(x, y) = A·x + B·y + C over pixel indices, at
  // pixel centres; covered iff E - bias >= 0 with bias 0 on top-left edges, 1 otherwise.
  for (int k = 0; k < 3; ++k) {
    const int i = k;
    const int j = (k + 1) % 3;
    const std::int64_t dx = tri.X[j] - tri.X[i];
    const std::int64_t dy = tri.Y[j] - tri.Y[i];
    const bool top_left = dy < 0 || (dy == 0 && dx > 0);
    const std::int64_t a = -dy * unit;
    const std::int64_t b = dx * unit;
    const std::int64_t c = dx * (half - tri.Y[i]) - dy * (half - tri.X[i]) - (top_left ? 0 : 1);
    QuadEdge& e = p.edges[k];
    if (a == 0) {  // horizontal edge: it only limits the rows, b·y + c >= 0
      if (b > 0) y0 = std::max(y0, ceil_div(-c, b));
      if (b < 0) y1 = std::min(y1, floor_div(c, -b));
      continue;
    }
    // x >= -floor(M/d) (lower, a > 0) or x <= floor(M/d) (upper, a < 0), M = b·y + c, d = |a|.
    e.kind = a > 0 ? 1 : 2;
    e.d = a > 0 ? a : -a;
    const std::int64_t m = b * y0 + c;
    e.q = floor_div(m, e.d);
    e.r = m - e.q * e.d;
    e.dq = floor_div(b, e.d);
    e.dr = b - e.dq * e.d;
  }
  if (x0 > x1 || y0 > y1) return QuadProgram{};
  p.x0 = static_cast<int>(x0);
  p.x1 = static_cast<int>(x1);
  p.y0 = static_cast<int>(y0);
  p.y1 = static_cast<int>(y1);

  // Channels: the quadratic over pixel offsets from (x0, y0), rounded to nearest (ties to even)
  // in the accumulator format: f = p(0,0), gy = p(0,1) - p(0,0) = c + e,
  // gx = p(1,0) - p(0,0) = a + d, and a, b, c. Wrapped, not saturated: for a sliver the
  // polynomial's terms far exceed the format's range while its values at covered pixels do not,
  // and the walker's modular sums then still land on them (docs/quad.md).
  const auto v = quad::to_pixels(tri_in);
  const auto q = [&f](double x) {
    return fx::quantize(x, f.acc, fx::Round::half_even, fx::Overflow::wrap);
  };
  for (int ch = 0; ch < 3; ++ch) {
    const quad::ScreenPoly poly = quad::screen_poly(colour[ch], v[0], v[1], v[2], p.x0, p.y0);
    p.channels[ch] = {q(poly.p00), q(poly.c + poly.p01), q(poly.a + poly.p10), q(poly.a), q(poly.b),
                      q(poly.c)};
  }
  return p;
}

int quad_guard_bits_needed(int w, int h) {
  const double a = w - 1;
  const double b = h - 1;
  return static_cast<int>(std::ceil(std::log2(1 + a * a + a * b + b * b)));
}

}  // namespace phongsim
