#include "ref/texture_maps.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace phongsim::texmap {

Uv sphere_map_uv(Vec3 w) {
  const double m = std::sqrt(w.x * w.x + w.y * w.y + (w.z + 1) * (w.z + 1));
  if (m < 1e-12) return {1, 0.5};
  return {0.5 + 0.5 * w.x / m, 0.5 + 0.5 * w.y / m};
}

bool sphere_map_direction(Uv uv, Vec3& w) {
  const double x = 2 * uv.u - 1, y = 2 * uv.v - 1;
  const double r2 = x * x + y * y;
  if (r2 > 1) return false;
  const double z = std::sqrt(1 - r2);
  w = {2 * z * x, 2 * z * y, 2 * z * z - 1};
  return true;
}

Uv blinn_uv(Vec3 n, Vec3 p, Vec3 axis, Vec3 fallback) {
  Vec3 a = axis - dot(axis, p) * p;
  if (length(a) < 1e-6) a = fallback - dot(fallback, p) * p;
  const Vec3 u_hat = normalized(a);
  const Vec3 v_hat = cross(p, u_hat);
  const double np = dot(n, p);
  const Vec3 q = n - np * p;
  Uv uv{dot(u_hat, q), dot(v_hat, q)};
  if (np < 0) {
    const double r = std::hypot(uv.u, uv.v);
    if (r < 1e-12) return {2, 0};
    const double scale = (2 - r) / r;
    uv = {uv.u * scale, uv.v * scale};
  }
  return uv;
}

double blinn_diffuse(double x, double y) {
  const double r2 = x * x + y * y;
  return r2 < 1 ? std::sqrt(1 - r2) : 0.0;
}

double blinn_specular(double x, double y, double exponent) {
  const double r2 = x * x + y * y;
  return r2 < 1 ? std::pow(1 - r2, exponent / 2) : 0.0;
}

std::string_view filter_name(Filter f) { return f == Filter::nearest ? "nearest" : "bilinear"; }

Filter parse_filter(std::string_view name) {
  for (const Filter f : {Filter::nearest, Filter::bilinear}) {
    if (filter_name(f) == name) return f;
  }
  throw Error(fmt::format("unknown texture filter '{}' (known: nearest, bilinear)", name));
}

Texture::Texture(Function fn, double lo, double hi, int size)
    : fn_(std::move(fn)), lo_(lo), hi_(hi), size_(size) {
  if (size < 0 || size > kMaxTextureSize) {
    throw Error(fmt::format("texture size {} is out of range (0..{}; 0: the exact function)", size,
                            kMaxTextureSize));
  }
  if (!(lo < hi)) throw Error(fmt::format("texture range [{}, {}] is empty", lo, hi));
  if (size == 0) return;
  const double h = (hi - lo) / size;
  texels_.resize(static_cast<std::size_t>(size) * size);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      texels_[static_cast<std::size_t>(j) * size + i] =
          static_cast<float>(fn_(lo + (i + 0.5) * h, lo + (j + 0.5) * h));
    }
  }
}

double Texture::texel(int i, int j) const {
  if (i < 0 || j < 0 || i >= size_ || j >= size_) return 0;
  return texels_[static_cast<std::size_t>(j) * size_ + i];
}

double Texture::sample(double x, double y, Filter filter) const {
  if (size_ == 0) return x >= lo_ && x <= hi_ && y >= lo_ && y <= hi_ ? fn_(x, y) : 0.0;
  // Continuous texel coordinates: texel i covers [i, i + 1).
  const double fx = (x - lo_) / (hi_ - lo_) * size_;
  const double fy = (y - lo_) / (hi_ - lo_) * size_;
  if (!(fx >= 0 && fy >= 0 && fx <= size_ && fy <= size_)) return 0;  // also NaN
  if (filter == Filter::nearest) {
    return texel(std::min(static_cast<int>(fx), size_ - 1),
                 std::min(static_cast<int>(fy), size_ - 1));
  }
  // Bilinear between texel centres (i + 1/2).
  const double gx = fx - 0.5, gy = fy - 0.5;
  const int i0 = static_cast<int>(std::floor(gx)), j0 = static_cast<int>(std::floor(gy));
  const double wx = gx - i0, wy = gy - j0;
  return (1 - wy) * ((1 - wx) * texel(i0, j0) + wx * texel(i0 + 1, j0)) +
         wy * ((1 - wx) * texel(i0, j0 + 1) + wx * texel(i0 + 1, j0 + 1));
}

}  // namespace phongsim::texmap
