// Double-precision and exact-integer reference for quadratic colour interpolation after
// D. Vlasic, "Fake Phong Shading" (MIT M.Eng. thesis 2002), seed 000: eq. 3.5 (barycentric
// (s, t) -> screen (x, y)), eqs. 3.6-3.11 (forward differencing), eqs. 4.1-4.3 (the quadratic
// r(s, t), its coefficients from six samples, (s, t) as affine functions of (x, y)). Errata in
// SEED-NOTES.md: eq. 4.2's sample order is r0 = v0, r1 = mid(v0, v1), r2 = v1, r3 = mid(v1, v2),
// r4 = v2, r5 = mid(v2, v0), with s along v0->v1 and t along v0->v2; without perspective r is a
// quadratic in screen (x, y) (screen_poly()), so it can be forward differenced.
//
// Screen conventions shared with the hardware setup (rtl/quad/, model/quad_setup.*):
//  - pixels (x, y) are integer indices, y grows downward, pixel (x, y)'s centre is at
//    (x + 1/2, y + 1/2) in real screen coordinates (pixels);
//  - the coverage reference works in subpixel integer units, X = x·2^S, Y = y·2^S (S >= 1), where
//    pixel (x, y)'s centre is (x·2^S + 2^(S-1), y·2^S + 2^(S-1));
//  - E_ij(P) = (Xj - Xi)(Py - Yi) - (Yj - Yi)(Px - Xi) for the directed edge i -> j; the triangle
//    is positive when E_01(V2) > 0, negative ones are used reversed, E_01(V2) == 0 covers nothing;
//  - P is inside when, for the positive triangle's edges 0->1, 1->2, 2->0, every E > 0 or E == 0
//    on a top-left edge (dy < 0, or dy == 0 and dx > 0, with dx, dy of that directed edge).
//    This equals testing the point P + (ε, ε²) for an infinitesimal ε > 0 (right, and a little
//    less down), which lies on no edge: so triangles that tile a region cover each pixel centre
//    in its interior, edges and vertices included, exactly once.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "base/vec3.h"

namespace phongsim::quad {

// ---- Eqs. 4.1 and 4.2: r(s, t) on the triangle ----

// C0..C5 of eq. 4.1: r(s, t) = C0 + C1·s + C2·t + C3·s² + C4·s·t + C5·t².
using Coeffs = std::array<double, 6>;
// r0..r5 in the corrected eq. 4.2 order (see the top of this file).
using Samples = std::array<double, 6>;

struct St {
  double s = 0;
  double t = 0;
  bool operator==(const St&) const = default;
};

// (s, t) of the six samples: (0,0), (1/2,0), (1,0), (1/2,1/2), (0,1), (0,1/2).
inline constexpr std::array<St, 6> kSampleSt{{
    {0.0, 0.0},
    {0.5, 0.0},
    {1.0, 0.0},
    {0.5, 0.5},
    {0.0, 1.0},
    {0.0, 0.5},
}};

// Eq. 4.2 as printed: C0 = r0, C1 = -3r0 + 4r1 - r2, C2 = -3r0 - r4 + 4r5,
// C3 = 2r0 - 4r1 + 2r2, C4 = 4r0 - 4r1 + 4r3 - 4r5, C5 = 2r0 + 2r4 - 4r5.
// eval_st(coefficients(r), kSampleSt[k]) == r[k] (exactly when the arithmetic is exact).
[[nodiscard]] Coeffs coefficients(const Samples& r);

// Eq. 4.1 (no range check: s, t outside the triangle extrapolate).
[[nodiscard]] double eval_st(const Coeffs& c, double s, double t);
[[nodiscard]] inline double eval_st(const Coeffs& c, St st) { return eval_st(c, st.s, st.t); }

// Gouraud (linear) colour as eq. 4.1 coefficients: the plane through r_v0 at (0,0), r_v1 at
// (1,0) and r_v2 at (0,1), i.e. C0 = r_v0, C1 = r_v1 - r_v0, C2 = r_v2 - r_v0, C3 = C4 = C5 = 0.
// Equal to coefficients() of samples whose midpoint values are the averages of their vertices.
[[nodiscard]] Coeffs linear_coefficients(double r_v0, double r_v1, double r_v2);

// ---- Eq. 3.5 and eq. 4.3: screen (x, y) <-> barycentric (s, t) ----

// A point in real screen coordinates (pixels; pixel (x, y)'s centre is (x + 0.5, y + 0.5)).
struct Vertex2 {
  double x = 0;
  double y = 0;
  bool operator==(const Vertex2&) const = default;
};

// Eq. 3.5: v0 + s·(v1 - v0) + t·(v2 - v0).
[[nodiscard]] Vertex2 st_to_xy(Vertex2 v0, Vertex2 v1, Vertex2 v2, St st);

// f(x, y) = x_coef·x + y_coef·y + c.
struct Affine {
  double x_coef = 0;
  double y_coef = 0;
  double c = 0;
  [[nodiscard]] double at(double x, double y) const { return x_coef * x + y_coef * y + c; }
};

struct StMap {
  Affine s;
  Affine t;
  [[nodiscard]] St at(double x, double y) const { return {s.at(x, y), t.at(x, y)}; }
  [[nodiscard]] St at(Vertex2 p) const { return at(p.x, p.y); }
};

// Eq. 4.3 as printed, with D = (x2 - x0)(y1 - y0) - (x1 - x0)(y2 - y0):
//   s = ((y0 - y2)·x + (x2 - x0)·y + x0·y2 - x2·y0) / D
//   t = ((y1 - y0)·x + (x0 - x1)·y + x1·y0 - x0·y1) / D
// (checked by substitution: it is the inverse of eq. 3.5, with numerator and denominator both
// negated relative to the usual adjugate/determinant form). The constant terms cancel badly far
// from the origin; st_at() is the accurate form. Throws Error for non-finite input or D == 0.
[[nodiscard]] StMap st_affine(Vertex2 v0, Vertex2 v1, Vertex2 v2);

// (s, t) of point p, solving eq. 3.5 relative to v0 (Cramer's rule on p - v0). Same
// preconditions as st_affine().
[[nodiscard]] St st_at(Vertex2 v0, Vertex2 v1, Vertex2 v2, Vertex2 p);

// The six sample positions in eq. 4.2 order (vertices and edge midpoints).
[[nodiscard]] std::array<Vertex2, 6> sample_points(Vertex2 v0, Vertex2 v1, Vertex2 v2);

// The six sample normals for step 1 of the §4.3 procedure, in eq. 4.2 order: the vertex normals
// normalized, and each midpoint normal the normalized sum of its two (normalized) vertex
// normals (their bisector). Throws Error for a zero or non-finite normal and for two opposite
// vertex normals (no bisector).
[[nodiscard]] std::array<Vec3, 6> sample_normals(Vec3 n0, Vec3 n1, Vec3 n2);

// ---- r as a quadratic in screen pixel indices ----

// p(i, j) = a·i² + b·i·j + c·j² + p10·i + p01·j + p00 (p_kl: the coefficient of i^k·j^l; a, b, c
// keep the names of the program words they become).
struct ScreenPoly {
  double a = 0;
  double b = 0;
  double c = 0;
  double p10 = 0;
  double p01 = 0;
  double p00 = 0;
};

[[nodiscard]] double eval_poly(const ScreenPoly& p, double i, double j);

// The polynomial in pixel indices (i, j) relative to the origin pixel (x0, y0) such that
// p(i, j) = r(s, t) at the centre (x0 + i + 1/2, y0 + j + 1/2) of pixel (x0 + i, y0 + j), for the
// triangle v0, v1, v2 (real screen coordinates). The affine (s, t) is taken about the origin
// pixel's centre (st_at()), so g = r at that centre. Same preconditions as st_affine().
[[nodiscard]] ScreenPoly screen_poly(const Coeffs& coeffs, Vertex2 v0, Vertex2 v1, Vertex2 v2,
                                     int x0, int y0);

// Eqs. 3.6-3.11 with unit pixel steps: p(i, j) for 0 <= i < width, 0 <= j < height, row-major
// (index j·width + i), by additions only. Along a row f += gx, gx += 2a (eqs. 3.9-3.11, with
// gx = a(2i + 1) + b·j + d); down the first column f += gy, gy += 2c (gy = c(2j + 1) + b·i + e
// at i = 0) and each row's starting gx += b. Starts from f = g, gx = a + d, gy = c + e. Agrees
// with eval_poly() to rounding that grows with the number of steps. Throws Error for a negative
// size.
[[nodiscard]] std::vector<double> forward_difference(const ScreenPoly& p, int width, int height);

// ---- Exact coverage in subpixel units ----

inline constexpr int kMinSubpixelBits = 1;
inline constexpr int kMaxSubpixelBits = 16;
// Every vertex coordinate must satisfy |X|, |Y| <= kMaxCoord, so edge deltas fit in 31 bits and
// each edge function in 62: int64 arithmetic is exact.
inline constexpr std::int64_t kMaxCoord = std::int64_t{1} << 29;

// Vertices in subpixel units (X = x·2^S).
struct SubpixelTri {
  std::array<std::int64_t, 3> X{};
  std::array<std::int64_t, 3> Y{};
  int S = 4;
  bool operator==(const SubpixelTri&) const = default;
};

// Throws Error unless kMinSubpixelBits <= S <= kMaxSubpixelBits and |X|, |Y| <= kMaxCoord.
void check(const SubpixelTri& tri);

// E_ij at (px, py) in subpixel units, for vertex indices i, j in 0..2 (no orientation fix-up).
[[nodiscard]] std::int64_t edge_function(const SubpixelTri& tri, int i, int j, std::int64_t px,
                                         std::int64_t py);

// E_01(V2): > 0 positive, < 0 negative, 0 degenerate.
[[nodiscard]] std::int64_t orientation(const SubpixelTri& tri);

// The same triangle with vertices 1 and 2 exchanged (opposite winding).
[[nodiscard]] SubpixelTri reversed(const SubpixelTri& tri);

// Pixel (x, y)'s centre in subpixel units: x·2^S + 2^(S-1).
[[nodiscard]] std::int64_t pixel_centre(int x, int S);

// Whether the centre of pixel (x, y) is inside `tri` under the conventions at the top of this
// file, by direct evaluation of the three edge functions. Degenerate triangles cover nothing.
// Throws Error as check().
[[nodiscard]] bool covers(const SubpixelTri& tri, int x, int y);

// Covered pixels with 0 <= x < width and 0 <= y < height, row-major (by y, then x): covers()
// over the triangle's bounding box clipped to the screen. Throws Error as check() and for a
// negative width or height.
[[nodiscard]] std::vector<std::pair<int, int>> raster(const SubpixelTri& tri, int width,
                                                      int height);

// Rounds each coordinate to the nearest subpixel unit (llround(v·2^S): halves away from zero).
// Throws Error for non-finite coordinates or a result check() rejects.
[[nodiscard]] SubpixelTri quantize(Vertex2 v0, Vertex2 v1, Vertex2 v2, int S);

// The vertices in real screen coordinates (exact: X / 2^S).
[[nodiscard]] std::array<Vertex2, 3> to_pixels(const SubpixelTri& tri);

// ---- Test meshes (deterministic for a seed; splitmix64) ----
// Every generator quantizes each shared vertex once, so shared edges are identical in all
// triangles that use them, builds all triangles with one orientation (so they tile their
// outline), checks every triangle is non-degenerate after quantization (Error otherwise: reduce
// the jitter or raise S), then reverses a random half of them (both windings appear).

// cols x rows cells of cell_w x cell_h pixels with top-left grid vertex (x0, y0), two triangles
// per cell. Every grid vertex (boundary ones too) is moved by independent uniform offsets in
// [-jitter, jitter] in x and in y; jitter must be < min(cell_w, cell_h)/4, which keeps every
// triangle's orientation. The cell diagonal alternates in a checkerboard pattern, or is chosen
// at random per cell when flip_diagonals_randomly. With jitter 0 and grid vertices on pixel
// centres, many centres lie exactly on edges and vertices.
[[nodiscard]] std::vector<SubpixelTri> grid_mesh(int cols, int rows, double x0, double y0,
                                                 double cell_w, double cell_h, double jitter,
                                                 std::uint64_t seed, int S,
                                                 bool flip_diagonals_randomly);

// A polygon with `sides` rim vertices at angles phase + 2πk/sides (k = 0..sides-1, increasing
// angle = clockwise on screen since y grows downward) on the circle of the given radius around
// (cx, cy), each moved by uniform offsets in [-jitter, jitter] in x and y, fanned from the
// centre (cx, cy). The rim is convex for jitter 0 (up to quantization), star-shaped around the
// centre otherwise; Error unless every fan triangle keeps its orientation and the rim winds once
// around the centre. sides >= 3, radius > 0.
[[nodiscard]] std::vector<SubpixelTri> fan_mesh(double cx, double cy, double radius, int sides,
                                                double phase, double jitter, std::uint64_t seed,
                                                int S);

// Slivers: the triangle (apex, (base_x0, base_y), (base_x1, base_y)) cut into `count` thin
// triangles from the apex to `count - 1` distinct random points of the (quantized, exactly
// horizontal) base. Needs base_x0 < base_x1, the apex off the base line, count >= 1 and
// count - 1 at most half the subpixel positions strictly inside the base.
[[nodiscard]] std::vector<SubpixelTri> sliver_fan(double apex_x, double apex_y, double base_x0,
                                                  double base_x1, double base_y, int count,
                                                  std::uint64_t seed, int S);

}  // namespace phongsim::quad
