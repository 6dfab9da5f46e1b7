// Double-precision reference for Kuijk & Blake, "Faster Phong shading via angular
// interpolation", CWI report CS-R8909 (1989): the three-piece quadratic f(θ) that replaces
// cos^n θ (section 2), its parameters (a, b) for each n, and the angular interpolation of a
// vector couple (N, L) along a scanline (section 1.2: eq. 1 exact, eq. 2 decomposition,
// eq. 4 one vector). Seed 001; errata in SEED-NOTES.md (the closed forms for a and b are printed
// with their labels exchanged; closed_form() uses the corrected labels).
//
// Angles are in radians. "Span" means one scanline segment from end 1 (t = 0) to end 2 (t = 1).
#pragma once

#include <cmath>

#include "base/vec3.h"

namespace phongsim::kb {

// ---- Section 2: f(θ), three quadratics ----

// Inner break points ±a, zeros ±b. Valid parameters are finite with 0 < a < b.
struct QuadParams {
  double a = 0;
  double b = 0;
};

namespace detail {
[[noreturn]] void bad_params(QuadParams p);  // throws Error
[[noreturn]] void nan_theta();               // throws Error
}  // namespace detail

// Throws Error unless p is valid. Every function taking QuadParams checks them. (This, quad()
// and section_of() are inline: a span's setup calls them per pixel and term.)
inline void check_params(QuadParams p) {
  if (!(std::isfinite(p.a) && std::isfinite(p.b) && p.a > 0 && p.b > p.a)) detail::bad_params(p);
}

namespace detail {
// quad() and section_of() below without their checks (p valid; section_of's θ not NaN) and
// without branches: each section's value is computed and one chosen, so that a loop over a
// span's pixels vectorizes (kb_span_values). The middle section is written as a product of two
// ratios so that neither factor over- or underflows.
[[nodiscard]] inline double quad_unchecked(double theta, QuadParams p) {
  const double x = std::abs(theta);
  const double middle = ((p.b - x) / p.b) * ((p.b - x) / (p.b - p.a));
  const double inner = 1 - (x / p.a) * (x / p.b);
  return x >= p.b ? 0.0 : x > p.a ? middle : inner;
}
[[nodiscard]] inline int section_unchecked(double theta, QuadParams p) {
  const double x = std::abs(theta);  // the same tests, in the same order, as quad()
  const int side = theta < 0 ? -1 : 1;
  return x >= p.b ? 2 * side : x > p.a ? side : 0;
}
}  // namespace detail

// f(θ) (section 2): 1 - θ²/(ab) for |θ| <= a; (|θ| - b)²/(b(b - a)) for a < |θ| < b; 0 for
// |θ| >= b. Even; value and slope continuous at ±a (value (b - a)/b, slope ∓2/b) and at ±b
// (both 0). NaN θ gives NaN.
[[nodiscard]] inline double quad(double theta, QuadParams p) {
  check_params(p);
  return detail::quad_unchecked(theta, p);
}

// df/dθ, with the same section conventions as quad() (continuous, so they do not matter).
[[nodiscard]] double quad_slope(double theta, QuadParams p);

// Which quadratic θ is on, with exactly quad()'s conventions: the closed inner interval
// [-a, a] is section 0 and the closed outer rays are ±2, so the open middle intervals are ±1.
//   -2: θ <= -b   -1: -b < θ < -a   0: -a <= θ <= a   1: a < θ < b   2: θ >= b
// Throws Error for NaN θ.
[[nodiscard]] inline int section_of(double theta, QuadParams p) {
  check_params(p);
  if (std::isnan(theta)) detail::nan_theta();
  return detail::section_unchecked(theta, p);
}

// f on one section as c2·θ² + c1·θ + c0 (for forward differencing):
//   0: c2 = -1/(ab), c1 = 0, c0 = 1
//   ±1: (θ ∓ b)²/(b(b - a)), i.e. c2 = 1/(b(b - a)), c1 = ∓2/(b - a), c0 = b/(b - a)
//   ±2: all zero.
// Throws Error for a section outside -2..2.
struct Section {
  double c2 = 0;
  double c1 = 0;
  double c0 = 0;
};
[[nodiscard]] Section section_poly(int section, QuadParams p);

// c2·θ² + c1·θ + c0 in Horner form. Agrees with quad() to a few ulps of c0 (the expanded
// middle sections cancel: c0 = b/(b - a) can be large when a is close to b).
[[nodiscard]] constexpr double eval(Section s, double theta) {
  return (s.c2 * theta + s.c1) * theta + s.c0;
}

// ---- Section 2: (a, b) for an exponent n ----

// The paper's fitted closed forms with the labels corrected (SEED-NOTES.md):
//   a = (n + 5.6)/(n(0.09n + 5.2)),  b = (n + 65.0)/(5.0n + 31.7).
// Fitted by the authors for 1 <= n <= 125; a < b holds for every n >= 1, so larger n are
// accepted (an extrapolation: b tends to 0.2 while the lobe of cos^n shrinks like n^-1/2).
// Throws Error unless n is finite and >= 1.
[[nodiscard]] QuadParams closed_form(double n);

// The project's least-squares (a, b) for integer n in 1..kMaxLeastSquaresN (the paper's table
// stops at 125; the renderer's halfway exponent 4n and sweeps go further, where the closed forms
// degrade fast): the minimizer of E(a, b) = integral over θ in [0, π] of (f(θ) - c(θ))² dθ,
// with c(θ) = cos^n θ for θ <= π/2 and 0 beyond (uniform weight; see kb_float.cpp for why).
// Each n is fitted on first use (about 1 ms) and kept; thread-safe. Throws Error outside the range.
inline constexpr int kMaxLeastSquaresN = 10000;
[[nodiscard]] QuadParams least_squares(int n);

// The fit behind least_squares(), uncached, for any real n in [1, 10000]: a coarse grid then
// damped Gauss-Newton on E (kb_float.cpp). Deterministic; a and b to better than 1e-9
// relative (the central-difference gradient of E vanishes there to its own truncation).
// least_squares(n) == fit_least_squares(n) exactly. Throws Error for n outside [1, 10000].
[[nodiscard]] QuadParams fit_least_squares(double n);

// Error of f against c(θ) (as above) over θ in [0, π] (f and c are even, so this covers
// [-π, π]); n finite and > 0, else Error.
// max_error: max |f - c|. Beyond min(b, π/2) one of f, c is 0 and the other falls, so interior
// maxima lie in [0, min(b, π/2)]: a 4097-point uniform grid there finds them and golden-section
// search refines each to 1e-13 in θ; the breakpoints a, b, π/2 are evaluated too. Accurate to
// rounding unless two maxima fall within one grid step (checked against 10^6-point grids).
// rms_error: sqrt((1/π) · E(a, b)), E by 24-point Gauss-Legendre on panels no wider than
// n^-1/2 between the breakpoints (graded towards π/2 for non-integer n). The quadrature error
// is below 1e-13 relative for n in [1, 10^4] (checked against panels 10 times narrower); what
// remains is the conditioning of cos^n θ itself, ~n·1e-16 relative. least_squares() minimizes
// exactly this quantity.
[[nodiscard]] double max_error(QuadParams p, double n);
[[nodiscard]] double rms_error(QuadParams p, double n);

// ---- Section 1.2: angular interpolation along a scanline ----
// Inputs are direction vectors; they need not be unit length (they are normalized) but must
// be finite and non-zero, else Error. N is the surface normal, L the direction to the light
// (or H, the halfway vector: the method is the same for any couple).

// The angle between u and v in [0, π], as atan2(|u × v|, u·v) (accurate for small angles).
[[nodiscard]] double angle(Vec3 u, Vec3 v);

// Constant-rate rotation from u to v along their great circle (unit result): t = 0 gives
// u/|u|, t = 1 gives v/|v|. Equal directions give u/|u| for every t. Throws Error for
// opposite directions (the great circle is undefined).
[[nodiscard]] Vec3 slerp(Vec3 u, Vec3 v, double t);

// Eq. (1), exact: cos α_t for N and L each rotated at a constant angular rate along its great
// circle (N from n1 to n2, L from l1 to l2), i.e. slerp(n1, n2, t)·slerp(l1, l2, t).
[[nodiscard]] double cos_exact(Vec3 n1, Vec3 n2, Vec3 l1, Vec3 l2, double t);

// One linearly interpolated angle: scale · cos(theta0 + t·dtheta), t in [0, 1] along the span.
// For a renderer stepping pixels, dtheta / (pixels - 1) is the per-pixel increment, and
// cos^n(α) ≈ scale^n · quad(theta0 + t·dtheta, ab(n)).
struct ScanlineAngles {
  double theta0 = 0;
  double dtheta = 0;
  double scale = 1;
  [[nodiscard]] double cos_at(double t) const { return scale * std::cos(theta0 + t * dtheta); }
};

// Eq. (2): cos α_t ≈ cos(n1 + t(n2 - n1)) · cos(l1 + t(l2 - l1)), the two factors as `n`
// (theta0 = n1, dtheta = n2 - n1) and `l` (theta0 = l1, dtheta = l2 - l1), both scale 1.
// Exact at t = 0 and t = 1; the construction (S', the sign conventions, degenerate cases) is
// documented at decompose() in kb_float.cpp.
struct Decomposition {
  ScanlineAngles n;
  ScanlineAngles l;
  [[nodiscard]] double cos_at(double t) const { return n.cos_at(t) * l.cos_at(t); }
};
[[nodiscard]] Decomposition decompose(Vec3 n1, Vec3 n2, Vec3 l1, Vec3 l2);

// The fixed reference vector of the one-vector method.
inline constexpr Vec3 kO{0, 0, 1};

// V = R·L with R the rotation by the smallest angle taking N to O (axis N × O). For N = -O
// exactly (axis undefined) R is the half turn about x: (x, y, z) -> (x, -y, -z).
[[nodiscard]] Vec3 align_to_o(Vec3 n, Vec3 l);

// Eq. (4): cos α_t = cos s · cos(ν + ν_t) for V interpolated by slerp from v1 to v2:
// scale = cos s (s the angle from O to the great circle through v1, v2), theta0 = ν (signed
// angle from the foot S of the perpendicular from O to v1, positive in the direction of
// travel), dtheta = angle(v1, v2). Exact for the slerped V at every t. Degenerate cases:
// v1 == v2 takes the great circle through v1 and O (s = 0); O perpendicular to the circle
// gives scale 0 (and theta0 = 0). Throws Error for opposite v1, v2.
[[nodiscard]] ScanlineAngles one_vector_from_v(Vec3 v1, Vec3 v2);

// Eq. (4) from per-vertex data: one_vector_from_v(align_to_o(n1, l1), align_to_o(n2, l2)).
// Exact at t = 0 and t = 1 (V_i·O = L_i·N_i); in between it approximates cos_exact().
[[nodiscard]] ScanlineAngles one_vector(Vec3 n1, Vec3 n2, Vec3 l1, Vec3 l2);

}  // namespace phongsim::kb
