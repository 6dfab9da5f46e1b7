// Minimal double-precision 3-vector for the float reference models (ref/lyon_float.*) and
// the renderer. Deliberately plain: a value type, element-wise + and -, scaling, dot and cross
// products.
#pragma once

#include <cmath>

namespace phongsim {

struct Vec3 {
  double x = 0;
  double y = 0;
  double z = 0;

  bool operator==(const Vec3&) const = default;
};

[[nodiscard]] constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
[[nodiscard]] constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
[[nodiscard]] constexpr Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
[[nodiscard]] constexpr Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
[[nodiscard]] constexpr Vec3 operator*(double s, Vec3 a) { return a * s; }

// Summed x, y, z in that order, as MATLAB's a*b' does (keeps results comparable to Lyon's code).
[[nodiscard]] constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Right-handed: cross({1, 0, 0}, {0, 1, 0}) == {0, 0, 1}.
[[nodiscard]] constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

[[nodiscard]] inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }

// a * (1/|a|), reciprocal first like MATLAB's `1/sqrt(hl)*hv`. A zero vector gives NaNs: the
// caller decides what a degenerate direction means.
[[nodiscard]] inline Vec3 normalized(Vec3 a) { return a * (1.0 / length(a)); }

}  // namespace phongsim
