// Double-precision reference for Bishop and Weimer's "Fast Phong Shading" (SIGGRAPH 86) as the
// seeds describe it (Vlasic, seed 000, chapter 2; Lai and Tai, seed 003, section 1): the
// illumination's cosines over a triangle, D·N/|N| with the normal N interpolated linearly as
// in Phong shading, replaced by their two-dimensional second-order Taylor expansion about the
// triangle's centroid — a quadratic, so two additions per pixel by forward differencing.
#pragma once

#include "base/vec3.h"
#include "ref/quad_float.h"

namespace phongsim::fast_phong {

// f(s, t) = D·N(s, t)/|N(s, t)|, N(s, t) = n0 + s(n1 - n0) + t(n2 - n0) (the vertex normals
// interpolated in the triangle's (s, t) of eq. 3.5, not normalized), for a unit direction d
// (L for the diffuse term, H for Blinn's specular one).
[[nodiscard]] double cosine(Vec3 n0, Vec3 n1, Vec3 n2, Vec3 d, quad::St st);

// The second-order Taylor polynomial of cosine() about the centroid (s, t) = (1/3, 1/3), as
// eq. 4.1 coefficients (evaluate with quad::eval_st). Exact at the centroid, with the exact
// gradient and Hessian there. Throws Error when N vanishes at the centroid.
[[nodiscard]] quad::Coeffs taylor(Vec3 n0, Vec3 n1, Vec3 n2, Vec3 d);

}  // namespace phongsim::fast_phong
