// Double-precision Kuijk–Blake reference; see kb_float.h. Equation numbers are the report's
// (seed 001): (1) exact angle along a scanline, (2) decomposition method, (4) one-vector method;
// "f" is the three-piece quadratic of section 2.
#include "ref/kb_float.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <vector>

#include <fmt/format.h>

#include "base/error.h"

namespace phongsim::kb {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = std::numbers::pi / 2;

// ---- the target c(θ) and the integrals over [0, π] ----

// c(θ) = cos^n θ up to π/2, 0 beyond (the renderer clamps back-facing light to zero).
double target(double theta, double n) {
  return theta < kHalfPi ? std::pow(std::cos(theta), n) : 0.0;
}

void check_n(double n) {
  if (!std::isfinite(n) || n <= 0) throw Error(fmt::format("exponent n = {} is not > 0", n));
}

// Gauss–Legendre rule on [-1, 1] (Newton on the Legendre recurrence, computed once).
constexpr int kGauss = 24;
struct GaussRule {
  std::array<double, kGauss> x{};
  std::array<double, kGauss> w{};
};
const GaussRule& gauss() {
  static const GaussRule rule = [] {
    GaussRule r;
    for (int i = 0; i < kGauss; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (kGauss + 0.5));
      double dp = 0;
      for (int iter = 0; iter < 100; ++iter) {
        double p0 = 1;
        double p1 = x;
        for (int k = 2; k <= kGauss; ++k) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = kGauss * (x * p1 - p0) / (x * x - 1);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      r.x[i] = x;
      r.w[i] = 2 / ((1 - x * x) * dp * dp);
    }
    return r;
  }();
  return rule;
}

// Calls visit(θ, weight) for the nodes of a composite Gauss–Legendre rule over [0, π], split
// at a, b and π/2 (where f or c change formula) into panels no wider than `width`/sqrt(n) (the
// lobe of cos^n is ~n^-1/2 wide). For integer n each piece's integrand is analytic; for other
// n, cos^n θ ~ (π/2 - θ)^n is not smooth at π/2, so the panel ending there is split
// geometrically towards π/2 (48 halvings; the rest, < 1e-14·h wide, is dropped). Pieces beyond
// both b and π/2, where f = c = 0, are skipped.
template <class Visit>
void for_each_node(QuadParams p, double n, double width, Visit&& visit) {
  std::array<double, 5> cut{0.0, std::min(p.a, kPi), std::min(p.b, kPi), kHalfPi, kPi};
  std::sort(cut.begin(), cut.end());
  const double end = std::max(std::min(p.b, kPi), kHalfPi);
  const double h_max = width / std::sqrt(n);
  const bool graded = n != std::floor(n);
  const GaussRule& g = gauss();
  const auto panel = [&](double lo, double hi) {
    const double mid = 0.5 * (lo + hi);
    const double half = 0.5 * (hi - lo);
    for (int i = 0; i < kGauss; ++i) visit(mid + half * g.x[i], half * g.w[i]);
  };
  for (std::size_t k = 0; k + 1 < cut.size(); ++k) {
    const double x0 = cut[k];
    const double x1 = std::min(cut[k + 1], end);
    if (!(x1 > x0)) continue;
    const int panels = static_cast<int>(std::ceil((x1 - x0) / h_max));
    const double h = (x1 - x0) / panels;
    const bool grade_last = graded && x1 == kHalfPi;
    for (int j = 0; j < panels - (grade_last ? 1 : 0); ++j) panel(x0 + j * h, x0 + (j + 1) * h);
    if (grade_last) {
      double w = h;
      for (int level = 0; level < 48; ++level, w *= 0.5) panel(x1 - w, x1 - 0.5 * w);
    }
  }
}

// E(a, b) = ∫_0^π (f - c)² dθ, the least-squares objective and the rms numerator.
double objective(QuadParams p, double n, double width = 1.0) {
  double sum = 0;
  for_each_node(p, n, width, [&](double theta, double w) {
    const double r = quad(theta, p) - target(theta, n);
    sum += w * r * r;
  });
  return sum;
}

// E, its gradient and the Gauss–Newton matrix J^T J (J = (∂f/∂a, ∂f/∂b)). f is C¹ in (θ, a, b)
// jointly (∂f/∂a = 1/b and ∂f/∂b = a/b² on both sides of θ = a, both 0 at θ = b), so moving
// breakpoints contribute no boundary terms: ∂E/∂a = 2∫(f - c)∂f/∂a, likewise for b.
struct Moments {
  double e = 0;
  double ga = 0, gb = 0;
  double maa = 0, mab = 0, mbb = 0;
};
Moments moments(QuadParams p, double n) {
  Moments m;
  const double a = p.a;
  const double b = p.b;
  for_each_node(p, n, 1.0, [&](double theta, double w) {
    const double r = quad(theta, p) - target(theta, n);
    double fa = 0;
    double fb = 0;
    if (theta <= a) {  // 1 - θ²/(ab)
      fa = theta * theta / (a * a * b);
      fb = theta * theta / (a * b * b);
    } else if (theta < b) {  // (b - θ)²/D, D = b(b - a)
      const double d = b - theta;
      const double den = b * (b - a);
      fa = d * d / (b * (b - a) * (b - a));
      fb = (2 * d * den - d * d * (2 * b - a)) / (den * den);
    }
    m.e += w * r * r;
    m.ga += 2 * w * r * fa;
    m.gb += 2 * w * r * fb;
    m.maa += 2 * w * fa * fa;
    m.mab += 2 * w * fa * fb;
    m.mbb += 2 * w * fb * fb;
  });
  return m;
}

bool feasible(QuadParams p) { return p.a > 0 && p.b > p.a && p.b <= kPi; }

// Least-squares fit of f to c. Why this objective: (2) and (4) advance θ linearly along the
// scanline, so a uniform weight in θ weights every pixel of a span equally (the paper only says
// "by least square fitting"); [0, π] because f and c are even (the fit over [-π, π] is the
// same) and because for small n f keeps a tail beyond π/2 (b ≈ 1.8 for n = 1, the smooth
// terminator of Photograph 5) that must be charged against c = 0 there.
//
// Method: a coarse grid over (a√n, b√n) (the lobe of cos^n scales like n^-1/2, so one grid
// fits every n), with a cheaper quadrature; then damped Gauss–Newton from the best grid point
// with the exact gradient and backtracking on E. E is smooth and, on the grid's range, has a
// single minimum; Gauss–Newton converges linearly (the residual is not small) in ~10-20 steps
// to the point where the step falls below 1e-13.
QuadParams fit(double n) {
  const double root = std::sqrt(n);
  QuadParams best{};
  double best_e = std::numeric_limits<double>::infinity();
  for (int i = 1; i <= 12; ++i) {
    for (int j = 1; j <= 16; ++j) {
      const QuadParams p{0.25 * i / root, 0.375 * j / root};
      if (!feasible(p)) continue;
      const double e = objective(p, n, 4.0);
      if (e < best_e) {
        best_e = e;
        best = p;
      }
    }
  }
  QuadParams p = best;
  Moments m = moments(p, n);
  for (int iter = 0; iter < 200; ++iter) {
    const double det = m.maa * m.mbb - m.mab * m.mab;
    const double da = -(m.mbb * m.ga - m.mab * m.gb) / det;
    const double db = -(m.maa * m.gb - m.mab * m.ga) / det;
    double step = 1;
    bool moved = false;
    for (int half = 0; half < 60; ++half, step *= 0.5) {
      const QuadParams q{p.a + step * da, p.b + step * db};
      if (!feasible(q)) continue;
      const Moments mq = moments(q, n);
      // Accept no increase beyond E's rounding (E sums ~10^3 positive terms).
      if (mq.e <= m.e * (1 + 1e-13)) {
        moved = q.a != p.a || q.b != p.b;
        p = q;
        m = mq;
        break;
      }
    }
    if (!moved || std::abs(step * da) + std::abs(step * db) < 1e-13 * p.b) break;
  }
  return p;
}

// ---- vectors ----

Vec3 unit(Vec3 v, const char* what) {
  const double len = length(v);
  if (!std::isfinite(len) || len == 0) {
    throw Error(
        fmt::format("{} ({}, {}, {}) is not a finite non-zero vector", what, v.x, v.y, v.z));
  }
  return v * (1 / len);
}

// A unit vector perpendicular to unit u: u × (the axis least aligned with u).
Vec3 any_perpendicular(Vec3 u) {
  const double ax = std::abs(u.x);
  const double ay = std::abs(u.y);
  const double az = std::abs(u.z);
  const Vec3 e =
      (ax <= ay && ax <= az) ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  return normalized(cross(u, e));
}

// Pole (unit normal of the plane) of the great circle from unit u to unit v, oriented so that
// the rotation from u to v is positive about it; the zero vector when u and v are parallel.
Vec3 pole(Vec3 u, Vec3 v) {
  const Vec3 k = cross(u, v);
  const double len = length(k);
  return len > 0 ? k * (1 / len) : Vec3{};
}

// Rotation of v by `angle` about unit axis k (Rodrigues).
Vec3 rotate(Vec3 v, Vec3 k, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

// x wrapped into (-π, π].
double wrap(double x) {
  x = std::remainder(x, 2 * kPi);
  return x <= -kPi ? x + 2 * kPi : x;
}

}  // namespace

// ---- f(θ) ----

void detail::bad_params(QuadParams p) {
  throw Error(fmt::format("Kuijk-Blake parameters a = {}, b = {} need 0 < a < b", p.a, p.b));
}

double quad_slope(double theta, QuadParams p) {
  check_params(p);
  const double x = std::abs(theta);
  double slope = 0;  // d f / d|θ|
  if (x >= p.b) {
    slope = 0;
  } else if (x > p.a) {
    slope = -2 * (p.b - x) / (p.b * (p.b - p.a));
  } else {
    slope = -2 * x / (p.a * p.b);
  }
  return theta < 0 ? -slope : slope;
}

void detail::nan_theta() { throw Error("section_of: θ is NaN"); }

Section section_poly(int section, QuadParams p) {
  check_params(p);
  const double a = p.a;
  const double b = p.b;
  switch (section) {
    case 0:
      return {-1 / (a * b), 0, 1};
    case 1:
    case -1:  // (θ ∓ b)²/(b(b - a)) expanded
      return {1 / (b * (b - a)), -2.0 * section / (b - a), b / (b - a)};
    case 2:
    case -2:
      return {0, 0, 0};
    default:
      throw Error(fmt::format("Kuijk-Blake section {} is outside -2..2", section));
  }
}

// ---- (a, b) ----

QuadParams closed_form(double n) {
  if (!std::isfinite(n) || n < 1) throw Error(fmt::format("closed_form: n = {} is not >= 1", n));
  // SEED-NOTES.md: as printed, these two formulas carry each other's labels.
  return {(n + 5.6) / (n * (0.09 * n + 5.2)), (n + 65.0) / (5.0 * n + 31.7)};
}

QuadParams fit_least_squares(double n) {
  if (!(n >= 1 && n <= 10000)) {
    throw Error(fmt::format("fit_least_squares: n = {} is outside [1, 10000]", n));
  }
  return fit(n);
}

QuadParams least_squares(int n) {
  if (n < 1 || n > kMaxLeastSquaresN) {
    throw Error(fmt::format("least_squares: n = {} is outside 1..{}", n, kMaxLeastSquaresN));
  }
  // Fitted once per n, on first use (a renderer asks for the same few exponents per span).
  static std::mutex mutex;
  static std::vector<std::optional<QuadParams>> table(kMaxLeastSquaresN);
  const std::lock_guard lock(mutex);
  auto& entry = table[static_cast<std::size_t>(n - 1)];
  if (!entry) entry = fit(n);
  return *entry;
}

double max_error(QuadParams p, double n) {
  check_params(p);
  check_n(n);
  const auto err = [&](double theta) { return std::abs(quad(theta, p) - target(theta, n)); };
  // Beyond min(b, π/2) one of f, c is 0 and the other decreases, so |f - c| is largest at
  // the breakpoints there; interior maxima lie in [0, min(b, π/2)].
  double best = std::max({err(0), err(std::min(p.a, kPi)), err(std::min(p.b, kPi)), err(kHalfPi),
                          err(std::nextafter(kHalfPi, 0.0))});
  constexpr int kGrid = 4097;
  const double hi = std::min(p.b, kHalfPi);
  std::array<double, kGrid> e{};
  for (int i = 0; i < kGrid; ++i) e[i] = err(hi * i / (kGrid - 1));
  for (int i = 1; i + 1 < kGrid; ++i) {
    if (!(e[i] >= e[i - 1] && e[i] >= e[i + 1])) continue;
    // Golden-section search for the maximum in [θ_{i-1}, θ_{i+1}].
    constexpr double kInvPhi = 0.6180339887498949;
    double lo = hi * (i - 1) / (kGrid - 1);
    double up = hi * (i + 1) / (kGrid - 1);
    double x1 = up - kInvPhi * (up - lo);
    double x2 = lo + kInvPhi * (up - lo);
    double f1 = err(x1);
    double f2 = err(x2);
    while (up - lo > 1e-13) {
      if (f1 < f2) {
        lo = x1;
        x1 = x2;
        f1 = f2;
        x2 = lo + kInvPhi * (up - lo);
        f2 = err(x2);
      } else {
        up = x2;
        x2 = x1;
        f2 = f1;
        x1 = up - kInvPhi * (up - lo);
        f1 = err(x1);
      }
    }
    best = std::max({best, e[i], f1, f2});
  }
  return best;
}

double rms_error(QuadParams p, double n) {
  check_params(p);
  check_n(n);
  return std::sqrt(objective(p, n) / kPi);
}

// ---- angular interpolation ----

double angle(Vec3 u, Vec3 v) { return std::atan2(length(cross(u, v)), dot(u, v)); }

Vec3 slerp(Vec3 u, Vec3 v, double t) {
  u = unit(u, "slerp: u");
  v = unit(v, "slerp: v");
  const Vec3 k = pole(u, v);
  if (k == Vec3{}) {
    if (dot(u, v) < 0) throw Error("slerp: opposite directions have no great circle");
    return u;
  }
  // Rotating u about the pole by t·angle(u, v); k × u is the unit tangent towards v.
  const double w = t * angle(u, v);
  return u * std::cos(w) + cross(k, u) * std::sin(w);
}

double cos_exact(Vec3 n1, Vec3 n2, Vec3 l1, Vec3 l2, double t) {
  return dot(slerp(n1, n2, t), slerp(l1, l2, t));
}

// Eq. (2), the decomposition method. Construction (the paper's Figure 7, made precise):
//  - P, the pole of N's great circle, oriented so that N turns positively about it:
//    P = N1 × N2 / |N1 × N2|, ω_N = angle(N1, N2). Frame: e1 = N1, e2 = P × e1; a vector X has
//    longitude lon X = atan2(X·e2, X·e1) and latitude lat X = atan2(X·P, |X - (X·P)P|).
//  - N moves along the equator from longitude 0 to ω_N. L's rotation is split into a rotation
//    about P by Δ (the "angle a between the two great circles through L1 and L2 perpendicular
//    to N's plane", i.e. the longitude change of L) and a meridian motion. Rotating N2 and L2 by
//    -Δ about P (N2', L2') leaves every angle between them unchanged and puts L2' on the
//    meridian circle of L1, which meets the equator at S' (longitude λ1 = lon L1).
//  - In the frame (S', E = P × S', P), N = cos φ S' + sin φ E and L = cos λ S' + sin λ P, so
//    N·L = cos φ cos λ (the right angle at S'). Hence eq. (2) with
//      n1 = -λ1,  n2 = ω_N - λ1 - Δ,  l1 = lat L1,  l2 = the angle from S' to L2' along the
//    meridian circle (towards P positive).
//  - Exactness: at t = 0, N1 = cos n1 S' + sin n1 E and L1 = cos l1 S' + sin l1 P, so eq. (2)
//    gives N1·L1. At t = 1 it gives N2'·L2' = N2·L2 (a common rotation keeps the angle).
//  - Δ is the longitude change wrap(lon L2 - lon L1) (option A: l2 = lat L2), or that minus
//    ±π with L carried over the pole (option B: L2' on the far half of the meridian circle,
//    l2 = ±π - lat L2, the branch nearer l1). Both are exact at the ends; we take the one with
//    the shorter total motion |Δ| + |l2 - l1|. B is what a path passing near P needs (there
//    the longitude jumps by ~π); A is right for everything else, notably paths along the
//    equator, whose longitude may change by more than π/2.
//  - Degenerate cases. N1 = N2: P is any axis perpendicular to N1; we take it on L's great
//    circle (P = N1 × (L1 × L2), normalized), which makes L's path a meridian, Δ = 0 and (2)
//    exact for all t; if L does not move either, or moves about N1, any perpendicular serves.
//    L1 (or L2) on the pole: its longitude is undefined; it takes the other one's (or 0 if
//    both are), so Δ = 0 and l = ±π/2 there.
Decomposition decompose(Vec3 n1, Vec3 n2, Vec3 l1, Vec3 l2) {
  n1 = unit(n1, "decompose: N1");
  n2 = unit(n2, "decompose: N2");
  l1 = unit(l1, "decompose: L1");
  l2 = unit(l2, "decompose: L2");
  if (dot(n1, n2) < 0 && pole(n1, n2) == Vec3{}) {
    throw Error("decompose: opposite normals have no great circle");
  }
  Vec3 p = pole(n1, n2);
  const double omega_n = angle(n1, n2);
  if (p == Vec3{}) {
    p = pole(n1, pole(l1, l2));
    if (p == Vec3{}) p = any_perpendicular(n1);
  }
  const Vec3 e1 = n1;
  const Vec3 e2 = cross(p, e1);
  const auto horizontal = [&](Vec3 x) { return std::hypot(dot(x, e1), dot(x, e2)); };
  const auto lon = [&](Vec3 x) { return std::atan2(dot(x, e2), dot(x, e1)); };
  const auto lat = [&](Vec3 x) { return std::atan2(dot(x, p), horizontal(x)); };
  double lambda1 = horizontal(l1) > 0 ? lon(l1) : (horizontal(l2) > 0 ? lon(l2) : 0.0);
  double lambda2 = horizontal(l2) > 0 ? lon(l2) : lambda1;
  const double delta_a = wrap(lambda2 - lambda1);
  const double lat1 = lat(l1);
  const double lat2 = lat(l2);
  // Option A: no pole crossing.
  const double l2_a = lat2;
  // Option B: over the pole; Δ shifted by π towards 0, L2' on the other half of the circle.
  const double delta_b = delta_a > 0 ? delta_a - kPi : delta_a + kPi;
  const double l2_b =
      std::abs(kPi - lat2 - lat1) <= std::abs(-kPi - lat2 - lat1) ? kPi - lat2 : -kPi - lat2;
  const double cost_a = std::abs(delta_a) + std::abs(l2_a - lat1);
  const double cost_b = std::abs(delta_b) + std::abs(l2_b - lat1);
  const bool over_pole = cost_b < cost_a;
  const double delta = over_pole ? delta_b : delta_a;
  const double l2_angle = over_pole ? l2_b : l2_a;
  Decomposition d;
  d.n = {-lambda1, omega_n - delta, 1.0};  // n1 = -λ1, n2 - n1 = ω_N - Δ
  d.l = {lat1, l2_angle - lat1, 1.0};
  return d;
}

Vec3 align_to_o(Vec3 n, Vec3 l) {
  n = unit(n, "align_to_o: N");
  l = unit(l, "align_to_o: L");
  const Vec3 k = pole(n, kO);
  if (k == Vec3{}) {
    if (dot(n, kO) > 0) return l;  // N = O: no rotation
    return {l.x, -l.y, -l.z};      // N = -O: half turn about x
  }
  return rotate(l, k, angle(n, kO));
}

ScanlineAngles one_vector_from_v(Vec3 v1, Vec3 v2) {
  v1 = unit(v1, "one_vector: V1");
  v2 = unit(v2, "one_vector: V2");
  Vec3 k = pole(v1, v2);
  double omega = angle(v1, v2);
  if (k == Vec3{}) {
    if (dot(v1, v2) < 0) throw Error("one_vector: opposite V1, V2 have no great circle");
    // V1 = V2: V stands still; any great circle through V1 serves. The one through O makes
    // s = 0 and theta0 = angle(O, V1).
    omega = 0;
    k = pole(v1, kO);
    if (k == Vec3{}) k = any_perpendicular(v1);
  }
  // Foot of the perpendicular from O on the great circle: O without its component along k.
  const Vec3 foot = kO - k * dot(kO, k);
  const double cos_s = length(foot);
  if (cos_s == 0) return {0.0, omega, 0.0};  // O is the pole: V ⟂ O all along
  const Vec3 s = foot * (1 / cos_s);
  // ν: signed angle from S to V1, positive along the travel direction k × S.
  const double nu = std::atan2(dot(v1, cross(k, s)), dot(v1, s));
  return {nu, omega, cos_s};
}

ScanlineAngles one_vector(Vec3 n1, Vec3 n2, Vec3 l1, Vec3 l2) {
  return one_vector_from_v(align_to_o(n1, l1), align_to_o(n2, l2));
}

}  // namespace phongsim::kb
