// Double-precision reference for Lyon, "Phong Shading Reformulation for Hardware Renderer
// Simplification", Apple TR #43 (1993): the shape functions f_k, the approximate reciprocal
// square roots g1/g2, and the twelve specular models of the appendix's specfuns.m (Figure 9).
// Section names below are those of the report (seed 002, errata in SEED-NOTES.md).
//
// Conventions (from the report and specfuns.m): all of N, L, V point away from the surface;
// "n" / `shininess` is Phong's exponent; the reflect methods use R = 2(V·N)N - V and
// D = L - R; the halfway methods use H = (L + V)/2 and the shininess 4n.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>

#include "base/vec3.h"

namespace phongsim::lyon {

inline constexpr int kMaxK = 3;  // shape orders supported: k = 0..3 (up to 8 = 2^3 squarings)

// Shape function f_k(x) = (1 - x/2^k)^(2^k) for x <= 2^k, 0 for x > 2^k ("Phong Specularity
// Reformulation"): one subtraction and k squarings. x = (n/2)|D|^2 >= 0 in every use; a negative
// x is not clamped (the polynomial is evaluated, as specfuns.m would). Throws Error unless
// 0 <= k <= kMaxK.
[[nodiscard]] double shape(double x, int k);

// Approximate 1/sqrt(z) about z = 1 ("Approximate Normalization"), with y = 1 - z:
// g1 = 1 + y/2 (first-order Taylor), g2 = 1 + (y + y^2)/2 (second order, coefficient 3/8
// over-corrected to 1/2 on purpose).
[[nodiscard]] double g1(double z);
[[nodiscard]] double g2(double z);

// Length after approximate normalization of a vector of length `len`: len * g_order(len^2),
// order 1 or 2; order 0 means no normalization (returns len). Throws Error for other orders.
[[nodiscard]] double normalized_length(double len, int order);

// The twelve rows of specfuns.m / Figure 9, in MATLAB order (Spec::phong is MATLAB row 1).
enum class Spec : std::size_t {
  phong,               // 1. (R.L)^n
  lyon_k0,             // 2. f_0((n/2)|L - R|^2)
  lyon_k1,             // 3. f_1(same x)
  lyon_k2,             // 4. f_2(same x)
  blinn_d1,            // 5. (H*.N)^(4n), H* = H/|H|
  halfway_unit_k2,     // 6. D = H* - N, f_2
  halfway_proj_k2,     // 7. D = H - (H.N)N, f_2
  halfway_g2_proj_k2,  // 8. D = Hg2 - (Hg2.N)N, Hg2 = g2(H.H) H, f_2
  halfway_g2_proj_k1,  // 9. as 8 with f_1
  halfway_g2_k2,       // 10. D = Hg2 - N, f_2
  torrance_sparrow,    // 11. exp(-(4n/2) acos(H*.N)^2), Blinn's D2
  trowbridge_reitz,    // 12. (1/(1 + (1 - (H*.N)^2) n))^2, Blinn's D3 (n, not 4n)
};
inline constexpr std::size_t kNumSpecs = 12;
[[nodiscard]] constexpr std::size_t index(Spec s) { return static_cast<std::size_t>(s); }

// All twelve specular amounts for unit N, L, V, shininess n > 0, exactly as specfuns.m computes
// them (quirks and the two deliberate deviations are documented in lyon_float.cpp).
[[nodiscard]] std::array<double, kNumSpecs> specfuns(Vec3 n, Vec3 l, Vec3 v, double shininess);

// Short captions for the rows, following Figure 9 ("Phong (R.L)^n", ..., "Trowbridge-Reitz
// (Blinn D3)"), indexed like specfuns().
[[nodiscard]] std::span<const std::string_view> specfun_names();

// The individual models (each is the specfuns.m row named; specfuns() is built from them).
// Row 1: (R.L)^n, 0 when R.L <= 0.
[[nodiscard]] double phong(Vec3 n, Vec3 l, Vec3 v, double shininess);
// Row 5: (H*.N)^(4n), 0 when H*.N <= 0; H* = (L + V)/|L + V|.
[[nodiscard]] double blinn(Vec3 n, Vec3 l, Vec3 v, double shininess);
// Rows 2-4 (k = 0, 1, 2; k = 3 also allowed): f_k((n/2)|L - R|^2).
[[nodiscard]] double lyon_reflect(Vec3 n, Vec3 l, Vec3 v, double shininess, int k);
// Rows 7 (h_norm 0, k 2), 8 (h_norm 2, k 2), 9 (h_norm 2, k 1): D = H' - (H'.N)N, the
// difference of H' and its projection on N, with H' = H g_{h_norm}(H.H) (h_norm 0: H itself;
// 1: g1, not used by specfuns.m), then f_k((4n/2)|D|^2). Throws Error for h_norm outside 0..2.
[[nodiscard]] double lyon_halfway(Vec3 n, Vec3 l, Vec3 v, double shininess, int k, int h_norm);

// The Lyon unit of rtl/lyon/lyon_top.sv and model/lyon.h in double precision: the same
// structure (LIRP, g-normalization, reflect or halfway D, x, f_k, diffuse) without any
// quantization. The reference for the fixed-point unit's output error (phongsim analyze lyon).
// `shininess` is Phong's n (for the root-shininess arrangement pass m², since (m|D|)² = n|D|²).
struct DatapathParams {
  bool halfway = false;  // D = H' - (H'.N)N with the shininess 4n, instead of D = L - R
  int norm = 2;          // N' normalization order (0, 1, 2)
  int h_norm = 0;        // H normalization order (halfway)
  int k = 2;             // shape function order
};
struct DatapathOut {
  double spec = 0;  // f_k(x)
  double diff = 0;  // max(N.L, 0)
};
[[nodiscard]] DatapathOut datapath(Vec3 n0, Vec3 n1, double a, Vec3 v, Vec3 l, double shininess,
                                   const DatapathParams& p);

// Shape-function accuracy against Phong for unit vectors, as a function of the angle alpha
// between R and L: error(alpha) = f_k(x) - c with x = (n/2)|D|^2, |D| = 2 sin(alpha/2) (the exact
// chord, as the reflect method sees it), c = cos^n(alpha) for alpha <= pi/2 and 0 beyond.
// Equivalently x = n(1 - cos alpha), so c = (1 - x/n)^n while f_k = (1 - x/2^k)^(2^k): for
// n = 2^k the two coincide and the error is 0 (up to rounding).
// Both throw Error unless shininess is finite and > 0 and 0 <= k <= kMaxK.
//
// max_shape_error: max |error| over alpha in [0, pi]. A 200001-point uniform grid followed by
// golden-section refinement around every sampled local maximum, plus the two kinks (f_k reaching
// 0 and alpha = pi/2). Accurate to 1e-9 absolute for 0.5 <= n <= 10^4: smooth maxima agree with
// a 2*10^7-point grid to 2e-11, kink maxima with their closed forms, e.g. (1 - 1/n)^n for k = 0.
[[nodiscard]] double max_shape_error(double shininess, int k);
// rms_shape_error: sqrt((1/pi) * integral over [0, pi] of error^2), trapezoidal rule on the same
// grid. [0, pi] rather than [0, pi/2] so that the tail f_k keeps beyond 90 degrees when n < 2^k
// counts; for large n both intervals dilute the lobe (the value falls like n^-1/4). Accurate
// to 2e-8 absolute over the same range of n (1.1e-8 worst, at n = 0.5 where cos^n has an
// infinite slope at pi/2; against a 2*10^7-point grid).
[[nodiscard]] double rms_shape_error(double shininess, int k);

}  // namespace phongsim::lyon
