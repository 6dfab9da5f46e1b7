// Double-precision Lyon TR #43 reference; see lyon_float.h. Every formula cites the report
// section or the specfuns.m line it follows. The operation order copies the MATLAB so that the
// results match it to the last bit where MATLAB is deterministic (scalars, x-y-z dot products).
//
// specfuns.m quirks kept on purpose (marked "MATLAB quirk" below):
//  - H = (L + V)/2, not the report's H = V + L; its length is <= 1, which is what g2 expects.
//  - Every halfway row (5-11) uses 4n, Blinn's exponent for the same lobe width; row 12 uses n.
//  - Row 11 has no H*.N > 0 test: it stays positive for back-facing H*; row 12 returns its
//    H*.N = 0 value (1/(1+n))^2 for every H*.N <= 0 and never reaches 0.
//  - Rows 1-4 and 7-9 see N only through (.N)N, so N and -N give the same amount (no backside
//    test; the report leaves that to the caller, "Pixel Shading Hardware Datapaths").
//  - Rows 7-9 project an unnormalized (or g2-normalized) H, so a short H gives a short D: at
//    L = -V (H = 0) they return 1 whatever N is ("this effect could be a feature or a bug").
// Deliberate deviations (MATLAB would give NaN or a complex number):
//  - L = -V exactly (H = 0): MATLAB's hv2 = 1/sqrt(0)*[0 0 0] is NaN. Here H* = 0 there, so
//    H*.N = 0 (the 90-degree case) and rows 5, 6, 11, 12 stay finite.
//  - acos in row 11 gets H*.N clamped to [-1, 1]; rounding can push it past 1 by an ulp, where
//    MATLAB's acos turns complex.
#include "ref/lyon_float.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "base/error.h"

namespace phongsim::lyon {
namespace {

void check_k(int k) {
  if (k < 0 || k > kMaxK) {
    throw Error("Lyon shape order k = " + std::to_string(k) + " is outside 0.." +
                std::to_string(kMaxK));
  }
}

void check_order(int order, const char* what) {
  if (order < 0 || order > 2) {
    throw Error(std::string(what) + " = " + std::to_string(order) +
                " is outside 0..2 (none, g1, g2)");
  }
}

// specfuns.m: rv = 2*nv*(vv*nv')-vv, the view vector reflected about N (Figure 2).
Vec3 reflected_view(Vec3 n, Vec3 v) { return n * (2 * dot(v, n)) - v; }

// specfuns.m: hv = (lv+vv)/2. MATLAB quirk: the report's H is V + L ("The Half-way Vector
// Approach"); halving keeps |H| <= 1 for unit L, V.
Vec3 halfway(Vec3 l, Vec3 v) { return (l + v) * 0.5; }

// g_order(H.H) H: order 2 is specfuns.m's hv1 = (1+0.5*(dl+dl*dl))*hv with dl = 1 - hl.
Vec3 approx_normalized(Vec3 h, int order) {
  const double z = dot(h, h);
  switch (order) {
    case 1:
      return h * g1(z);
    case 2:
      return h * g2(z);
    default:
      return h;
  }
}

// specfuns.m: hv2 = 1/sqrt(hl)*hv. Deviation: H = 0 (L = -V) gives H* = 0 instead of NaN.
Vec3 unit_halfway(Vec3 l, Vec3 v) {
  const Vec3 h = halfway(l, v);
  return dot(h, h) == 0 ? Vec3{} : normalized(h);
}

// specfuns.m, every row 2-4, 6-10: xs = (dv*dv')*n/2, then f_k(xs). `shininess` is n or n4.
double shape_of_difference(Vec3 d, double shininess, int k) {
  return shape(dot(d, d) * shininess / 2, k);
}

// specfuns.m: n4 = 4*n, "n" for halfway vector method. MATLAB quirk: applied to rows 5-11.
double halfway_shininess(double shininess) { return 4 * shininess; }

// Rows 1 and 5: dot^n when dot > 0, else 0.
double positive_power(double d, double exponent) { return d > 0 ? std::pow(d, exponent) : 0.0; }

// Row 6 (H*, h_norm unused) and row 10 (Hg2): D = H' - N, no projection. Row 10 "loses the
// glancing hilite" ("Simulation Results"): a short H stays short after g2, so D never vanishes.
double halfway_minus_normal(Vec3 h, Vec3 n, double shininess, int k) {
  return shape_of_difference(h - n, halfway_shininess(shininess), k);
}

// Row 11, Blinn D2 (Torrance-Sparrow): alpha = acos(dot); exp(-(n4/2)*alpha*alpha). MATLAB
// quirk: `dot` is row 5's H*.N (the recomputation is commented out in specfuns.m) and there is
// no dot > 0 test. Deviation: dot clamped to [-1, 1] for acos.
double torrance_sparrow(double h_dot_n, double shininess) {
  const double alpha = std::acos(std::clamp(h_dot_n, -1.0, 1.0));
  return std::exp(-(halfway_shininess(shininess) / 2) * alpha * alpha);
}

// Row 12, Blinn D3 (Trowbridge-Reitz): (1/(1+(1-dot*dot)*n))^2 for dot > 0, else (1/(1+n))^2
// ("as low as it gets!"). MATLAB quirk: n, not n4, unlike the other halfway rows. (The listing
// has a stray second `end;` before this row's `count = count+1; amounts(count) = amount;`,
// which would end the function early; Figure 9 shows 12 rows, so the store is meant.)
double trowbridge_reitz(double h_dot_n, double shininess) {
  const double d = h_dot_n > 0 ? h_dot_n : 0.0;  // d = 0 reproduces the else branch exactly
  const double r = 1 / (1 + (1 - d * d) * shininess);
  return r * r;
}

}  // namespace

double shape(double x, int k) {
  check_k(k);
  const double scale = static_cast<double>(1 << k);  // 2^k: a shift in hardware (Figure 7d)
  // specfuns.m: `if xs > 4; amount = 0`, strictly greater; at x = 2^k the polynomial is 0 anyway.
  if (x > scale) {
    return 0.0;
  }
  double amount = 1 - x / scale;
  for (int i = 0; i < k; ++i) {
    amount = amount * amount;  // "square k times"
  }
  return amount;
}

// "Approximate Normalization": y = 1 - z, g1 = 1 + y/2, g2 = 1 + (y + y^2)/2, written as
// specfuns.m's 1+0.5*(dl+dl*dl).
double g1(double z) {
  const double y = 1 - z;
  return 1 + 0.5 * y;
}

double g2(double z) {
  const double y = 1 - z;
  return 1 + 0.5 * (y + y * y);
}

double normalized_length(double len, int order) {
  check_order(order, "normalization order");
  const double z = len * len;
  switch (order) {
    case 1:
      return len * g1(z);
    case 2:
      return len * g2(z);
    default:
      return len;
  }
}

double phong(Vec3 n, Vec3 l, Vec3 v, double shininess) {
  // specfuns.m row 1: dot = rv*lv'; dot^n if dot > 0.
  return positive_power(dot(reflected_view(n, v), l), shininess);
}

double blinn(Vec3 n, Vec3 l, Vec3 v, double shininess) {
  // specfuns.m row 5: dot = hv2*nv'; dot^n4 if dot > 0.
  return positive_power(dot(unit_halfway(l, v), n), halfway_shininess(shininess));
}

double lyon_reflect(Vec3 n, Vec3 l, Vec3 v, double shininess, int k) {
  // specfuns.m rows 2-4: dv = lv - rv ("Phong Specularity Reformulation": |D| = 2 sin(alpha/2)).
  return shape_of_difference(l - reflected_view(n, v), shininess, k);
}

double lyon_halfway(Vec3 n, Vec3 l, Vec3 v, double shininess, int k, int h_norm) {
  check_order(h_norm, "halfway normalization order");
  // specfuns.m rows 7-9: dv = hv - nv*(hv*nv') (row 7), hv1 - nv*(hv1*nv') (rows 8, 9); the
  // report's D3 = (H.N)N - H up to sign, which needs no normalization of H.
  const Vec3 h = approx_normalized(halfway(l, v), h_norm);
  return shape_of_difference(h - n * dot(h, n), halfway_shininess(shininess), k);
}

DatapathOut datapath(Vec3 n0, Vec3 n1, double a, Vec3 v, Vec3 l, double shininess,
                     const DatapathParams& p) {
  check_order(p.norm, "normalization order");
  const Vec3 n = approx_normalized(n0 * (1 - a) + n1 * a, p.norm);  // Fig. 7a: LIRP, then g
  DatapathOut out;
  out.diff = std::max(dot(n, l), 0.0);
  out.spec = p.halfway ? lyon_halfway(n, l, v, shininess, p.k, p.h_norm)
                       : lyon_reflect(n, l, v, shininess, p.k);
  return out;
}

std::array<double, kNumSpecs> specfuns(Vec3 n, Vec3 l, Vec3 v, double shininess) {
  const double h_dot_n = dot(unit_halfway(l, v), n);  // row 5's `dot`, reused by rows 11, 12
  std::array<double, kNumSpecs> out{};
  out[index(Spec::phong)] = phong(n, l, v, shininess);
  out[index(Spec::lyon_k0)] = lyon_reflect(n, l, v, shininess, 0);
  out[index(Spec::lyon_k1)] = lyon_reflect(n, l, v, shininess, 1);
  out[index(Spec::lyon_k2)] = lyon_reflect(n, l, v, shininess, 2);
  out[index(Spec::blinn_d1)] = blinn(n, l, v, shininess);
  out[index(Spec::halfway_unit_k2)] = halfway_minus_normal(unit_halfway(l, v), n, shininess, 2);
  out[index(Spec::halfway_proj_k2)] = lyon_halfway(n, l, v, shininess, 2, 0);
  out[index(Spec::halfway_g2_proj_k2)] = lyon_halfway(n, l, v, shininess, 2, 2);
  out[index(Spec::halfway_g2_proj_k1)] = lyon_halfway(n, l, v, shininess, 1, 2);
  out[index(Spec::halfway_g2_k2)] =
      halfway_minus_normal(approx_normalized(halfway(l, v), 2), n, shininess, 2);
  out[index(Spec::torrance_sparrow)] = torrance_sparrow(h_dot_n, shininess);
  out[index(Spec::trowbridge_reitz)] = trowbridge_reitz(h_dot_n, shininess);
  return out;
}

std::span<const std::string_view> specfun_names() {
  // Figure 9's captions, shortened; H* is the normalized and Hg2 the g2-normalized halfway
  // vector, "proj" the projection of H on N.
  static constexpr std::array<std::string_view, kNumSpecs> kNames = {
      "Phong (R.L)^n",
      "Lyon k=0",
      "Lyon k=1",
      "Lyon k=2",
      "Blinn D1 (H*.N)^4n",
      "D = H* - N, k=2",
      "D = H - proj, k=2",
      "D = Hg2 - proj, k=2",
      "D = Hg2 - proj, k=1",
      "D = Hg2 - N, k=2",
      "Torrance-Sparrow (Blinn D2)",
      "Trowbridge-Reitz (Blinn D3)",
  };
  return kNames;
}

// ---- shape-function accuracy ("Phong Specularity Reformulation", Figure 3) ----
namespace {

// 200001 points on [0, pi]: spacing 1.6e-5 rad. The lobe's width is ~1/sqrt(n) ("nominal radius
// 1/sqrt(n)"), 0.032 rad = 2000 spacings at n = 1000 and still 640 at n = 10^4, so every local
// maximum of |error| is bracketed by its grid neighbours; refinement then removes the O(h^2)
// sampling error (about n h^2 / 2 = 1e-7 at n = 1000 without it).
constexpr int kGridPoints = 200001;

void check_shininess(double shininess) {
  if (!(shininess > 0) || !std::isfinite(shininess)) {
    throw Error("shininess n = " + std::to_string(shininess) + " must be finite and > 0");
  }
}

double alpha_at(int i) { return std::numbers::pi * i / (kGridPoints - 1); }

// f_k(x) - c at angle alpha between R and L.
double shape_error(double alpha, double shininess, int k) {
  const double half_chord = std::sin(alpha / 2);
  const double x = 2 * shininess * half_chord * half_chord;  // (n/2)|D|^2, |D| = 2 sin(alpha/2)
  const double c = std::cos(alpha);
  return shape(x, k) - positive_power(c, shininess);  // Phong is 0 past 90 degrees (row 1)
}

std::vector<double> sampled_errors(double shininess, int k) {
  check_shininess(shininess);
  check_k(k);
  std::vector<double> e(kGridPoints);
  for (int i = 0; i < kGridPoints; ++i) {
    e[i] = shape_error(alpha_at(i), shininess, k);
  }
  return e;
}

// Golden-section search for the maximum of |error| on [a, b], where it is unimodal (a two-cell
// bracket around a sampled local maximum; kinks are fine). 80 steps shrink 3e-5 rad below 1e-15.
double refine_max(double a, double b, double shininess, int k) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  auto f = [&](double alpha) { return std::abs(shape_error(alpha, shininess, k)); };
  double c = b - r * (b - a);
  double d = a + r * (b - a);
  double fc = f(c);
  double fd = f(d);
  for (int i = 0; i < 80 && c < d; ++i) {
    if (fc >= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - r * (b - a);
      fc = f(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + r * (b - a);
      fd = f(d);
    }
  }
  return std::max({fc, fd, f(a), f(b)});
}

}  // namespace

double max_shape_error(double shininess, int k) {
  const std::vector<double> e = sampled_errors(shininess, k);
  double best = 0;
  for (int i = 0; i < kGridPoints; ++i) {
    const double here = std::abs(e[i]);
    best = std::max(best, here);
    const bool rises = i == 0 || here > std::abs(e[i - 1]);
    const bool falls = i == kGridPoints - 1 || here >= std::abs(e[i + 1]);
    if (rises && falls && here > 0) {
      best = std::max(best, refine_max(alpha_at(std::max(i - 1, 0)),
                                       alpha_at(std::min(i + 1, kGridPoints - 1)), shininess, k));
    }
  }
  // The kinks, exactly: f_k reaches 0 at x = 2^k, i.e. cos(alpha) = 1 - 2^k/n; Phong's clamp
  // at pi/2 (a kink for n <= 1).
  best = std::max(best, std::abs(shape_error(std::numbers::pi / 2, shininess, k)));
  const double cos_zero = 1 - static_cast<double>(1 << k) / shininess;
  if (cos_zero >= -1) {
    best = std::max(best, std::abs(shape_error(std::acos(cos_zero), shininess, k)));
  }
  return best;
}

double rms_shape_error(double shininess, int k) {
  const std::vector<double> e = sampled_errors(shininess, k);
  double sum = 0;  // trapezoidal rule: interior weight 1, end points 1/2
  for (int i = 0; i < kGridPoints; ++i) {
    const double w = (i == 0 || i == kGridPoints - 1) ? 0.5 : 1.0;
    sum += w * e[i] * e[i];
  }
  return std::sqrt(sum / (kGridPoints - 1));  // (1/pi) * h * sum, h = pi / (points - 1)
}

}  // namespace phongsim::lyon
