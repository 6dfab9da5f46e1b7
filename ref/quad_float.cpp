// Double-precision and exact-integer quadratic-shading reference; see quad_float.h. Equation
// numbers are Vlasic's (seed 000) with the sample order of SEED-NOTES.md.
#include "ref/quad_float.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>

#include "base/error.h"
#include "base/rng.h"

namespace phongsim::quad {
namespace {

bool finite(Vertex2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// (x1 - x0)(y2 - y0) - (x2 - x0)(y1 - y0): eq. 3.5's determinant (twice the signed area; > 0 for
// a triangle that is positive in the edge-function sense, since y grows downward in both).
double checked_det(Vertex2 v0, Vertex2 v1, Vertex2 v2) {
  if (!finite(v0) || !finite(v1) || !finite(v2)) {
    throw Error(fmt::format("triangle ({}, {}) ({}, {}) ({}, {}) has a non-finite coordinate", v0.x,
                            v0.y, v1.x, v1.y, v2.x, v2.y));
  }
  const double det = (v1.x - v0.x) * (v2.y - v0.y) - (v2.x - v0.x) * (v1.y - v0.y);
  if (det == 0 || !std::isfinite(det)) {
    throw Error(fmt::format("triangle ({}, {}) ({}, {}) ({}, {}) is degenerate", v0.x, v0.y, v1.x,
                            v1.y, v2.x, v2.y));
  }
  return det;
}

void check_subpixel_bits(int S) {
  if (S < kMinSubpixelBits || S > kMaxSubpixelBits) {
    throw Error(fmt::format("subpixel bits S = {} is outside {}..{}", S, kMinSubpixelBits,
                            kMaxSubpixelBits));
  }
}

// floor(a / b) for b > 0.
std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

// The positive edge (dx, dy) is top-left: dy < 0, or dy == 0 and dx > 0.
bool top_left(std::int64_t dx, std::int64_t dy) { return dy < 0 || (dy == 0 && dx > 0); }

std::int64_t to_subpixel(double v, int S) {
  const double scaled = std::ldexp(v, S);
  if (!std::isfinite(scaled) || std::abs(scaled) > static_cast<double>(kMaxCoord)) {
    throw Error(fmt::format("coordinate {} is not finite or exceeds the subpixel range", v));
  }
  return std::llround(scaled);
}

struct IPoint {
  std::int64_t X = 0;
  std::int64_t Y = 0;
};

SubpixelTri make_tri(IPoint a, IPoint b, IPoint c, int S) {
  SubpixelTri t{{a.X, b.X, c.X}, {a.Y, b.Y, c.Y}, S};
  check(t);
  return t;
}

// Common tail of the generators: every triangle positive, then a random half reversed.
std::vector<SubpixelTri> finish_mesh(std::vector<SubpixelTri> tris, Rng& rng, const char* what) {
  for (auto& t : tris) {
    if (orientation(t) <= 0) {
      throw Error(fmt::format(
          "{}: a triangle is degenerate or inverted after quantization (reduce the jitter or "
          "raise S)",
          what));
    }
  }
  for (auto& t : tris) {
    if (rng.coin()) t = reversed(t);
  }
  return tris;
}

}  // namespace

// ---- Eqs. 4.1 and 4.2 ----

Coeffs coefficients(const Samples& r) {
  return {
      r[0],
      -3 * r[0] + 4 * r[1] - r[2],
      -3 * r[0] - r[4] + 4 * r[5],
      2 * r[0] - 4 * r[1] + 2 * r[2],
      4 * r[0] - 4 * r[1] + 4 * r[3] - 4 * r[5],
      2 * r[0] + 2 * r[4] - 4 * r[5],
  };
}

double eval_st(const Coeffs& c, double s, double t) {
  return c[0] + c[1] * s + c[2] * t + c[3] * s * s + c[4] * s * t + c[5] * t * t;
}

Coeffs linear_coefficients(double r_v0, double r_v1, double r_v2) {
  return {r_v0, r_v1 - r_v0, r_v2 - r_v0, 0, 0, 0};
}

// ---- Eqs. 3.5 and 4.3 ----

Vertex2 st_to_xy(Vertex2 v0, Vertex2 v1, Vertex2 v2, St st) {
  return {(v1.x - v0.x) * st.s + (v2.x - v0.x) * st.t + v0.x,
          (v1.y - v0.y) * st.s + (v2.y - v0.y) * st.t + v0.y};
}

StMap st_affine(Vertex2 v0, Vertex2 v1, Vertex2 v2) {
  checked_det(v0, v1, v2);
  // Eq. 4.3 transcribed term by term (its denominator is minus eq. 3.5's determinant).
  const double d = (v2.x - v0.x) * (v1.y - v0.y) - (v1.x - v0.x) * (v2.y - v0.y);
  StMap m;
  m.s = {(v0.y - v2.y) / d, (v2.x - v0.x) / d, (v0.x * v2.y - v2.x * v0.y) / d};
  m.t = {(v1.y - v0.y) / d, (v0.x - v1.x) / d, (v1.x * v0.y - v0.x * v1.y) / d};
  return m;
}

St st_at(Vertex2 v0, Vertex2 v1, Vertex2 v2, Vertex2 p) {
  const double det = checked_det(v0, v1, v2);
  const double dx = p.x - v0.x;
  const double dy = p.y - v0.y;
  return {((v2.y - v0.y) * dx - (v2.x - v0.x) * dy) / det,
          ((v1.x - v0.x) * dy - (v1.y - v0.y) * dx) / det};
}

std::array<Vertex2, 6> sample_points(Vertex2 v0, Vertex2 v1, Vertex2 v2) {
  const auto mid = [](Vertex2 a, Vertex2 b) { return Vertex2{(a.x + b.x) / 2, (a.y + b.y) / 2}; };
  return {v0, mid(v0, v1), v1, mid(v1, v2), v2, mid(v2, v0)};
}

std::array<Vec3, 6> sample_normals(Vec3 n0, Vec3 n1, Vec3 n2) {
  const auto unit = [](Vec3 n, const char* what) {
    const double len = length(n);
    if (!std::isfinite(len) || len == 0) {
      throw Error(fmt::format("{} ({}, {}, {}) is zero or not finite", what, n.x, n.y, n.z));
    }
    return normalized(n);
  };
  const Vec3 u0 = unit(n0, "vertex normal 0");
  const Vec3 u1 = unit(n1, "vertex normal 1");
  const Vec3 u2 = unit(n2, "vertex normal 2");
  const auto bisector = [&unit](Vec3 a, Vec3 b) {
    return unit(a + b, "sum of two opposite vertex normals");
  };
  return {u0, bisector(u0, u1), u1, bisector(u1, u2), u2, bisector(u2, u0)};
}

// ---- r as a quadratic in pixel indices ----

double eval_poly(const ScreenPoly& p, double i, double j) {
  return p.a * i * i + p.b * i * j + p.c * j * j + p.p10 * i + p.p01 * j + p.p00;
}

ScreenPoly screen_poly(const Coeffs& coeffs, Vertex2 v0, Vertex2 v1, Vertex2 v2, int x0, int y0) {
  // s = p·i + q·j + u and t = m·i + n·j + w: one pixel step changes (x, y) by one, so p, q, m, n
  // are eq. 4.3's x and y coefficients; (u, w) is (s, t) at the origin pixel's centre.
  const StMap map = st_affine(v0, v1, v2);
  const St origin = st_at(v0, v1, v2, {x0 + 0.5, y0 + 0.5});
  const double p = map.s.x_coef, q = map.s.y_coef, u = origin.s;
  const double m = map.t.x_coef, n = map.t.y_coef, w = origin.t;
  const auto& C = coeffs;
  // Substitute into eq. 4.1 and collect powers of i and j.
  ScreenPoly r;
  r.a = C[3] * p * p + C[4] * p * m + C[5] * m * m;
  r.b = 2 * C[3] * p * q + C[4] * (p * n + q * m) + 2 * C[5] * m * n;
  r.c = C[3] * q * q + C[4] * q * n + C[5] * n * n;
  r.p10 = C[1] * p + C[2] * m + 2 * C[3] * p * u + C[4] * (p * w + m * u) + 2 * C[5] * m * w;
  r.p01 = C[1] * q + C[2] * n + 2 * C[3] * q * u + C[4] * (q * w + n * u) + 2 * C[5] * n * w;
  r.p00 = eval_st(C, u, w);
  return r;
}

std::vector<double> forward_difference(const ScreenPoly& p, int width, int height) {
  if (width < 0 || height < 0) {
    throw Error(fmt::format("forward_difference: negative size {}x{}", width, height));
  }
  std::vector<double> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const double a2 = 2 * p.a;
  const double c2 = 2 * p.c;
  double row_f = p.p00;         // p(0, j)
  double row_gx = p.a + p.p10;  // p(1, j) - p(0, j) = a + b·j + p10
  double gy = p.c + p.p01;      // p(0, j + 1) - p(0, j) = c(2j + 1) + p01
  for (int j = 0; j < height; ++j) {
    double f = row_f;
    double gx = row_gx;
    for (int i = 0; i < width; ++i) {
      out[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
          static_cast<std::size_t>(i)] = f;
      f += gx;   // eq. 3.9
      gx += a2;  // eq. 3.11
    }
    row_f += gy;
    gy += c2;
    row_gx += p.b;
  }
  return out;
}

// ---- Exact coverage ----

void check(const SubpixelTri& tri) {
  check_subpixel_bits(tri.S);
  for (int k = 0; k < 3; ++k) {
    if (std::abs(tri.X[k]) > kMaxCoord || std::abs(tri.Y[k]) > kMaxCoord) {
      throw Error(fmt::format("subpixel vertex {} ({}, {}) exceeds +-2^29", k, tri.X[k], tri.Y[k]));
    }
  }
}

std::int64_t edge_function(const SubpixelTri& tri, int i, int j, std::int64_t px, std::int64_t py) {
  return (tri.X[j] - tri.X[i]) * (py - tri.Y[i]) - (tri.Y[j] - tri.Y[i]) * (px - tri.X[i]);
}

std::int64_t orientation(const SubpixelTri& tri) {
  return edge_function(tri, 0, 1, tri.X[2], tri.Y[2]);
}

SubpixelTri reversed(const SubpixelTri& tri) {
  SubpixelTri r = tri;
  std::swap(r.X[1], r.X[2]);
  std::swap(r.Y[1], r.Y[2]);
  return r;
}

std::int64_t pixel_centre(int x, int S) {
  check_subpixel_bits(S);
  return x * (std::int64_t{1} << S) + (std::int64_t{1} << (S - 1));
}

bool covers(const SubpixelTri& input, int x, int y) {
  check(input);
  const std::int64_t o = orientation(input);
  if (o == 0) return false;
  const SubpixelTri tri = o > 0 ? input : reversed(input);
  const std::int64_t px = pixel_centre(x, tri.S);
  const std::int64_t py = pixel_centre(y, tri.S);
  // Every vertex is within +-kMaxCoord, so a centre beyond that is outside (and E stays exact).
  if (std::abs(px) > kMaxCoord || std::abs(py) > kMaxCoord) return false;
  static constexpr std::array<std::array<int, 2>, 3> kEdges{{{0, 1}, {1, 2}, {2, 0}}};
  for (const auto& [i, j] : kEdges) {
    const std::int64_t e = edge_function(tri, i, j, px, py);
    if (e > 0) continue;
    if (e < 0) return false;
    if (!top_left(tri.X[j] - tri.X[i], tri.Y[j] - tri.Y[i])) return false;
  }
  return true;
}

std::vector<std::pair<int, int>> raster(const SubpixelTri& tri, int width, int height) {
  check(tri);
  if (width < 0 || height < 0) {
    throw Error(fmt::format("raster: negative screen size {}x{}", width, height));
  }
  std::vector<std::pair<int, int>> out;
  if (width == 0 || height == 0) return out;
  const std::int64_t unit = std::int64_t{1} << tri.S;
  const auto [min_x, max_x] = std::minmax({tri.X[0], tri.X[1], tri.X[2]});
  const auto [min_y, max_y] = std::minmax({tri.Y[0], tri.Y[1], tri.Y[2]});
  // Pixel x's centre lies in [x·unit, (x + 1)·unit), so these ranges hold every centre in the
  // bounding box (and possibly one more pixel, which covers() rejects).
  const int x_lo = static_cast<int>(std::max<std::int64_t>(floor_div(min_x, unit), 0));
  const int x_hi = static_cast<int>(std::min<std::int64_t>(floor_div(max_x, unit), width - 1));
  const int y_lo = static_cast<int>(std::max<std::int64_t>(floor_div(min_y, unit), 0));
  const int y_hi = static_cast<int>(std::min<std::int64_t>(floor_div(max_y, unit), height - 1));
  for (int y = y_lo; y <= y_hi; ++y) {
    for (int x = x_lo; x <= x_hi; ++x) {
      if (covers(tri, x, y)) out.emplace_back(x, y);
    }
  }
  return out;
}

SubpixelTri quantize(Vertex2 v0, Vertex2 v1, Vertex2 v2, int S) {
  check_subpixel_bits(S);
  SubpixelTri t;
  t.S = S;
  const std::array<Vertex2, 3> v{v0, v1, v2};
  for (int k = 0; k < 3; ++k) {
    t.X[k] = to_subpixel(v[k].x, S);
    t.Y[k] = to_subpixel(v[k].y, S);
  }
  check(t);
  return t;
}

std::array<Vertex2, 3> to_pixels(const SubpixelTri& tri) {
  std::array<Vertex2, 3> v;
  for (int k = 0; k < 3; ++k) {
    v[k] = {std::ldexp(static_cast<double>(tri.X[k]), -tri.S),
            std::ldexp(static_cast<double>(tri.Y[k]), -tri.S)};
  }
  return v;
}

// ---- Test meshes ----

std::vector<SubpixelTri> grid_mesh(int cols, int rows, double x0, double y0, double cell_w,
                                   double cell_h, double jitter, std::uint64_t seed, int S,
                                   bool flip_diagonals_randomly) {
  check_subpixel_bits(S);
  if (cols < 1 || rows < 1 || cols > 4096 || rows > 4096) {
    throw Error(fmt::format("grid_mesh: {}x{} cells is outside 1..4096 each way", cols, rows));
  }
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(cell_w) ||
      !std::isfinite(cell_h) || cell_w <= 0 || cell_h <= 0) {
    throw Error(
        fmt::format("grid_mesh: bad origin ({}, {}) or cell size {}x{}", x0, y0, cell_w, cell_h));
  }
  if (!std::isfinite(jitter) || jitter < 0 || jitter >= std::min(cell_w, cell_h) / 4) {
    throw Error(fmt::format("grid_mesh: jitter {} is not in [0, min(cell_w, cell_h)/4)", jitter));
  }
  Rng rng = Rng::from_state(seed);
  const int nx = cols + 1;
  std::vector<IPoint> v(static_cast<std::size_t>(nx) * static_cast<std::size_t>(rows + 1));
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      const double x = x0 + i * cell_w + jitter * rng.symmetric();
      const double y = y0 + j * cell_h + jitter * rng.symmetric();
      v[static_cast<std::size_t>(j * nx + i)] = {to_subpixel(x, S), to_subpixel(y, S)};
    }
  }
  const auto at = [&](int i, int j) { return v[static_cast<std::size_t>(j * nx + i)]; };
  std::vector<SubpixelTri> tris;
  tris.reserve(2 * static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows));
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const IPoint p00 = at(i, j), p10 = at(i + 1, j), p01 = at(i, j + 1), p11 = at(i + 1, j + 1);
      const bool main_diagonal = flip_diagonals_randomly ? rng.coin() : (i + j) % 2 == 0;
      if (main_diagonal) {  // p00-p11
        tris.push_back(make_tri(p00, p10, p11, S));
        tris.push_back(make_tri(p00, p11, p01, S));
      } else {  // p10-p01
        tris.push_back(make_tri(p00, p10, p01, S));
        tris.push_back(make_tri(p10, p11, p01, S));
      }
    }
  }
  return finish_mesh(std::move(tris), rng, "grid_mesh");
}

std::vector<SubpixelTri> fan_mesh(double cx, double cy, double radius, int sides, double phase,
                                  double jitter, std::uint64_t seed, int S) {
  check_subpixel_bits(S);
  if (sides < 3 || sides > 65536) {
    throw Error(fmt::format("fan_mesh: {} sides is outside 3..65536", sides));
  }
  if (!std::isfinite(radius) || radius <= 0 || !std::isfinite(phase) || !std::isfinite(jitter) ||
      jitter < 0) {
    throw Error(
        fmt::format("fan_mesh: bad radius {}, phase {} or jitter {}", radius, phase, jitter));
  }
  Rng rng = Rng::from_state(seed);
  const IPoint centre{to_subpixel(cx, S), to_subpixel(cy, S)};
  std::vector<IPoint> rim(static_cast<std::size_t>(sides));
  for (int k = 0; k < sides; ++k) {
    const double angle = phase + 2 * std::numbers::pi * k / sides;
    const double x = cx + radius * std::cos(angle) + jitter * rng.symmetric();
    const double y = cy + radius * std::sin(angle) + jitter * rng.symmetric();
    rim[static_cast<std::size_t>(k)] = {to_subpixel(x, S), to_subpixel(y, S)};
  }
  std::vector<SubpixelTri> tris;
  double turn = 0;  // total angle swept by the spokes
  for (int k = 0; k < sides; ++k) {
    const IPoint a = rim[static_cast<std::size_t>(k)];
    const IPoint b = rim[static_cast<std::size_t>((k + 1) % sides)];
    tris.push_back(make_tri(centre, a, b, S));
    const double ax = static_cast<double>(a.X - centre.X), ay = static_cast<double>(a.Y - centre.Y);
    const double bx = static_cast<double>(b.X - centre.X), by = static_cast<double>(b.Y - centre.Y);
    turn += std::atan2(ax * by - ay * bx, ax * bx + ay * by);
  }
  // With every triangle positive each step is in (0, π), so the total is 2π times the number of
  // turns; more than one turn would overlap.
  if (turn > 3 * std::numbers::pi) {
    throw Error("fan_mesh: the rim winds around the centre more than once (reduce the jitter)");
  }
  return finish_mesh(std::move(tris), rng, "fan_mesh");
}

std::vector<SubpixelTri> sliver_fan(double apex_x, double apex_y, double base_x0, double base_x1,
                                    double base_y, int count, std::uint64_t seed, int S) {
  check_subpixel_bits(S);
  const IPoint apex{to_subpixel(apex_x, S), to_subpixel(apex_y, S)};
  const std::int64_t bx0 = to_subpixel(base_x0, S);
  const std::int64_t bx1 = to_subpixel(base_x1, S);
  const std::int64_t by = to_subpixel(base_y, S);
  if (bx0 >= bx1 || apex.Y == by) {
    throw Error("sliver_fan: the base must run left to right with the apex off its line");
  }
  const std::int64_t inner = bx1 - bx0 - 1;  // subpixel positions strictly inside the base
  if (count < 1 || count - 1 > inner / 2) {
    throw Error(fmt::format("sliver_fan: {} slivers do not fit a base of {} subpixel units", count,
                            bx1 - bx0));
  }
  Rng rng = Rng::from_state(seed);
  std::set<std::int64_t> cuts;
  while (static_cast<int>(cuts.size()) < count - 1) {
    cuts.insert(bx0 + 1 + static_cast<std::int64_t>(rng.below(static_cast<std::uint64_t>(inner))));
  }
  std::vector<std::int64_t> xs{bx0};
  xs.insert(xs.end(), cuts.begin(), cuts.end());
  xs.push_back(bx1);
  // (apex, left, right) is positive when the apex is below the base (E = (Ay - by)·Δx).
  const bool apex_below = apex.Y > by;
  std::vector<SubpixelTri> tris;
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const IPoint left{xs[k], by};
    const IPoint right{xs[k + 1], by};
    tris.push_back(apex_below ? make_tri(apex, left, right, S) : make_tri(apex, right, left, S));
  }
  return finish_mesh(std::move(tris), rng, "sliver_fan");
}

}  // namespace phongsim::quad
