// Lai and Tai, "Highlight-Track Shading" (seed 003, section 2): along a scanline the normal is
// N(x) = N0 + x·dN (Phong's linear interpolation, not normalized). The highlight-track point of
// the line is the foot of the perpendicular from the halfway vector H, the point where
// |N(x) - H| is smallest and, for N close to unit length, H·N/|N| largest; since the scanlines'
// normal lines are parallel, these points lie on one straight line across the triangle (the
// highlight track).
#pragma once

#include <limits>

#include "base/vec3.h"

namespace phongsim {

// x of the foot: -(N0 - H)·dN / (dN·dN). NaN when dN is zero (a constant normal along the line:
// no point is special).
[[nodiscard]] inline double highlight_track_offset(Vec3 n0, Vec3 dn, Vec3 h) {
  const double dd = dot(dn, dn);
  if (!(dd > 0)) return std::numeric_limits<double>::quiet_NaN();
  return -dot(n0 - h, dn) / dd;
}

}  // namespace phongsim
