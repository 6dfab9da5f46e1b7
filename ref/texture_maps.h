// Double-precision reference for Vlasic's texturing approaches to Phong shading (D. Vlasic,
// "Fake Phong Shading", MIT M.Eng. thesis 2002, seed 000, chapter 5): the spherical
// environment map (eqs. 5.1-5.3), the Blinn map (eqs. 5.4-5.7) and the textures they index,
// sampled at a chosen resolution with nearest or bilinear filtering. The renderer interpolates
// the coordinates over triangles (sim/render/render.cpp); docs/methods.md describes the methods.
#pragma once

#include <functional>
#include <string_view>
#include <vector>

#include "base/vec3.h"

namespace phongsim::texmap {

// Texture coordinates.
struct Uv {
  double u = 0;
  double v = 0;
};

// ---- Section 5.1: spherical environment map ----

// Eqs. 5.1-5.3: m = sqrt(Wx² + Wy² + (Wz + 1)²), u = 1/2 + Wx/(2m), v = 1/2 + Wy/(2m), for the
// reflected view vector W = 2(N·V)N - V in eye coordinates (x right, y up, z towards the
// viewer). W = (0, 0, -1), the one direction the map cannot place (m = 0), maps to the rim
// point (1, 1/2).
[[nodiscard]] Uv sphere_map_uv(Vec3 w_eye);

// The inverse of sphere_map_uv on the map's disc: the W that texel position (u, v) shows,
// W = 2 s_z s - (0, 0, 1) for the mirror-ball normal s = (2u - 1, 2v - 1, sqrt(1 - r²)),
// r² = (2u - 1)² + (2v - 1)² <= 1. Returns false (w untouched) outside the disc.
[[nodiscard]] bool sphere_map_direction(Uv uv, Vec3& w_eye);

// ---- Section 5.2: Blinn map ----

// Eqs. 5.6 and 5.7: the coordinates of the unit normal n in the shading-parameter plane whose
// normal is the unit vector p (L for the diffuse texture, H for the specular one):
// u = û·(n - (n·p)p), v = (p × û)·(n - (n·p)p), where û is the re-normalized projection of the
// global axis `axis` (the camera's up vector) onto the plane. Where `axis` is within 1e-6 of
// ±p (Figure 5.6's singularity: it projects to a point), `fallback` (the camera's right
// vector) is projected instead.
// phongsim's addition: a normal on the far side of the plane (n·p < 0) is unfolded outwards,
// to radius 2 - |q| along its projection q (the antipode -p to (2, 0)). The texture is zero
// beyond radius 1, so such a vertex gets max(n·p, 0) = 0 exactly, and coordinates
// interpolated between two far-side vertices stay outside the disc instead of crossing its
// lit centre (eqs. 5.6-5.7 alone would light them with |n·p|).
[[nodiscard]] Uv blinn_uv(Vec3 n, Vec3 p, Vec3 axis, Vec3 fallback);

// Eq. 5.4: the diffuse texture sqrt(1 - x² - y²) = (0, 0, 1)·(x, y, sqrt(1 - x² - y²)); 0 for
// x² + y² >= 1.
[[nodiscard]] double blinn_diffuse(double x, double y);

// Eq. 5.5: the specular texture (1 - x² - y²)^(exponent/2), so that at a vertex it equals
// (n·p)^exponent; 0 for x² + y² >= 1. phongsim's renderer uses exponent 4n (Blinn's halfway
// form of Phong's n, as lyon::blinn).
[[nodiscard]] double blinn_specular(double x, double y, double exponent);

// ---- Textures ----

enum class Filter { nearest, bilinear };
[[nodiscard]] std::string_view filter_name(Filter f);
[[nodiscard]] Filter parse_filter(std::string_view name);  // nearest|bilinear; Error else

inline constexpr int kMaxTextureSize = 4096;

// A square texture over [lo, hi]² (x = u, y = v): size × size texels, texel (i, j) holding
// fn at its centre (lo + (i + 1/2)·h, lo + (j + 1/2)·h), h = (hi - lo)/size. Outside the texels
// the texture is 0 (a zero border, GL_CLAMP_TO_BORDER), for both filters. Size 0 keeps fn
// and evaluates it exactly at every lookup (an infinitely fine texture), which separates the
// interpolation of coordinates from the sampling of the texture.
class Texture {
 public:
  using Function = std::function<double(double x, double y)>;
  // Throws Error unless 0 <= size <= kMaxTextureSize and lo < hi.
  Texture(Function fn, double lo, double hi, int size);

  // Nearest: the texel containing (x, y). Bilinear: the four texels around it weighted by
  // distance (texels outside count as 0).
  [[nodiscard]] double sample(double x, double y, Filter filter) const;
  [[nodiscard]] double sample(Uv uv, Filter filter) const { return sample(uv.u, uv.v, filter); }

  [[nodiscard]] int size() const { return size_; }

 private:
  [[nodiscard]] double texel(int i, int j) const;

  Function fn_;
  double lo_, hi_;
  int size_;
  std::vector<float> texels_;  // row j, column i at j * size + i
};

}  // namespace phongsim::texmap
