// Lyon's LIRP (linear interpolation, Fig. 7a; seed 002 §4) in float: the value the fixed-point
// unit approximates. p = (1 - a)·p0 + a·p1, written as the unit computes it, p0 + a·(p1 - p0).
#pragma once

#include "base/vec3.h"

namespace phongsim::lirp {

[[nodiscard]] inline double lirp(double p0, double p1, double a) { return p0 + a * (p1 - p0); }

[[nodiscard]] inline Vec3 lirp(const Vec3& p0, const Vec3& p1, double a) {
  return {lirp(p0.x, p1.x, a), lirp(p0.y, p1.y, a), lirp(p0.z, p1.z, a)};
}

}  // namespace phongsim::lirp
