#include "ref/fast_phong.h"

#include <cmath>

#include "base/error.h"

namespace phongsim::fast_phong {

double cosine(Vec3 n0, Vec3 n1, Vec3 n2, Vec3 d, quad::St st) {
  const Vec3 n = n0 + st.s * (n1 - n0) + st.t * (n2 - n0);
  return dot(d, n) / length(n);
}

quad::Coeffs taylor(Vec3 n0, Vec3 n1, Vec3 n2, Vec3 d) {
  // About the centroid, with offsets (ds, dt): N = Nc + ds·As + dt·At, so f = g / sqrt(q) with
  // g = a + b·(ds, dt) linear and q = |N|² = c + 2e·(ds, dt) + (ds, dt)ᵀF(ds, dt). At the
  // centroid: f = a/√c, ∂f/∂i = b_i/√c - a·e_i/c^(3/2),
  // ∂²f/∂i∂j = -(b_i·e_j + b_j·e_i + a·F_ij)/c^(3/2) + 3a·e_i·e_j/c^(5/2).
  const Vec3 nc = (n0 + n1 + n2) * (1.0 / 3);
  const Vec3 as = n1 - n0, at = n2 - n0;
  const double c = dot(nc, nc);
  if (!(c > 1e-24)) throw Error("fast Phong: the interpolated normal vanishes at the centroid");
  const double a = dot(d, nc);
  const double b[2] = {dot(d, as), dot(d, at)};
  const double e[2] = {dot(nc, as), dot(nc, at)};
  const double f[2][2] = {{dot(as, as), dot(as, at)}, {dot(at, as), dot(at, at)}};
  const double rc = 1 / std::sqrt(c), rc3 = rc / c, rc5 = rc3 / c;
  double grad[2], hess[2][2];
  for (int i = 0; i < 2; ++i) {
    grad[i] = b[i] * rc - a * e[i] * rc3;
    for (int j = 0; j < 2; ++j) {
      hess[i][j] = -(b[i] * e[j] + b[j] * e[i] + a * f[i][j]) * rc3 + 3 * a * e[i] * e[j] * rc5;
    }
  }
  // T(s, t) = a/√c + grad·δ + δᵀ·hess·δ/2 with δ = (s - 1/3, t - 1/3), expanded in s and t.
  const double s0 = 1.0 / 3, t0 = 1.0 / 3;
  quad::Coeffs k{};
  k[3] = hess[0][0] / 2;
  k[4] = hess[0][1];
  k[5] = hess[1][1] / 2;
  k[1] = grad[0] - hess[0][0] * s0 - hess[0][1] * t0;
  k[2] = grad[1] - hess[1][1] * t0 - hess[0][1] * s0;
  k[0] = a * rc - grad[0] * s0 - grad[1] * t0 + k[3] * s0 * s0 + k[4] * s0 * t0 + k[5] * t0 * t0;
  return k;
}

}  // namespace phongsim::fast_phong
