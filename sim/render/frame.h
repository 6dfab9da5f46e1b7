// What every shading method of the renderer sees (sim/render/render.cpp,
// sim/render/seed_methods.cpp): the frame — image size, the visible fragment of each object pixel,
// lights and camera, the mesh in screen space with each triangle's coverage — built for a scene,
// and the pieces of lighting and interpolation the methods share. Internal to the renderer;
// docs/render.md describes what a user sees.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/vec3.h"
#include "ref/kb_float.h"
#include "ref/quad_float.h"
#include "sim/render/image.h"
#include "sim/render/mesh.h"
#include "sim/render/scene.h"

namespace phongsim::shading {

// Subpixel bits of projected vertices (the quad configurations' sub_bits).
inline constexpr int kSubBits = 4;
inline constexpr std::string_view kShinyballs = "shinyballs";

// ---- The frame: fragments (the visible surface point of each object pixel) ----

struct Fragment {
  int x = 0, y = 0;
  int tri = -1;  // mesh triangle (-1: analytic sphere)
  quad::St st;   // (s, t) in the triangle (eq. 4.3 at the pixel centre)
  Vec3 n;        // interpolated normal (not normalized)
  Vec3 p;        // surface point (world)
  double shininess = 1;
  Vec3 kd, ks, ka;  // material
};

struct Lighting {
  std::vector<Light> lights;
  bool view_at_infinity = true;
  Vec3 view_dir{0, 0, 1};  // towards the viewer (orthographic)
  Vec3 eye;                // perspective

  [[nodiscard]] Vec3 v_at(Vec3 p) const {
    return view_at_infinity ? view_dir : normalized(eye - p);
  }
  [[nodiscard]] static Vec3 l_at(const Light& l, Vec3 p) {
    return l.at_infinity ? normalized(l.position) : normalized(l.position - p);
  }
  // The halfway vector (L + V)/|L + V| of light l at p.
  [[nodiscard]] Vec3 h_at(const Light& l, Vec3 p) const { return normalized(l_at(l, p) + v_at(p)); }
};

// Everything a method needs: the image frame, the fragments, the mesh in screen space.
struct Frame {
  std::string scene;
  int width = 0, height = 0;
  Rgb8 background;
  std::vector<Fragment> fragments;
  std::vector<int> owner;     // per pixel: fragment index or -1
  std::vector<int> seen;      // per pixel: the triangle visible there or -1 (mesh scenes)
  std::vector<bool> visible;  // per triangle: visible at some pixel (mesh scenes)
  Lighting lighting;
  bool mesh = false;
  Mesh geometry;                          // world positions and normals
  std::vector<quad::SubpixelTri> screen;  // projected triangles (mesh scenes)
  // Each triangle's covered pixels within the image, row-major (quad::raster): every method
  // and the hardware units cover exactly these.
  std::vector<std::vector<std::pair<int, int>>> coverage;
  Material material;
  std::vector<std::pair<std::string, std::vector<bool>>> regions;  // RenderResult::regions
  // The camera's right and up axes in world space (with lighting.view_dir: eye coordinates x,
  // y, z), and the mesh's bounding-box centre (where the environment map is seen from).
  Vec3 cam_right{1, 0, 0}, cam_up{0, 1, 0};
  Vec3 centre;

  // Whether triangle t is the surface visible at pixel (x, y) (mesh scenes; a compact array:
  // the scanline methods ask for every pixel of their spans).
  [[nodiscard]] bool shows(std::size_t t, int x, int y) const {
    return seen[static_cast<std::size_t>(y) * width + x] == static_cast<int>(t);
  }
};

// Lyon's specular.m (seed 002, appendix): spheres of radius m pixels for n = 1, 4, 16, 64, 256,
// each offset by one radius to the right (the earlier one in front), viewpoint [0, 0, 1], lights
// at infinity along [1, 1, -1] and [1, -1, 1], diffuse factor 35, specular factor 400·(n/256)^¼,
// on a bright (255) background. One strip per method instead of the MATLAB's overlapped rows.
[[nodiscard]] Frame shinyballs(int m);

// Projects the scene's mesh (orthographic or perspective camera), rasterizes every triangle with
// the quad unit's coverage rule (quad::raster, top-left) and keeps the nearest surface per pixel
// (depth interpolated affinely in screen space, like every attribute here: no perspective
// correction, as in the hardware). width_override > 0 sets the image width (the height keeps
// the scene's aspect). Throws Error for an image beyond 2048 x 2048 or a triangle outside the
// screen or behind the camera.
[[nodiscard]] Frame mesh_frame(const Scene& sc, int width_override);

// ---- Lighting ----

[[nodiscard]] inline Vec3 mul(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

// The lighting model with per-light diffuse and specular amounts:
// colour = ka + Σ light ⊙ (kd·diff + ks·spec).
struct Amounts {
  double diff = 0;
  double spec = 0;
};
[[nodiscard]] Vec3 combine(const Fragment& fr, const std::vector<Light>& lights,
                           const std::vector<Amounts>& amounts);

// A specular model: the amount for unit N, L, V and Phong shininess n (lyon::phong, ...).
using SpecularFn = double (*)(Vec3 n, Vec3 l, Vec3 v, double shininess);

// The lighting at a point with unit normal n: combine() with diff = max(N·L, 0) and spec's
// amount for each light, summed in the same order (inline and without allocation: this is the
// per-pixel path of the Phong reference that `phongsim bench methods` times).
[[nodiscard]] inline Vec3 shade(const Frame& f, const Fragment& fr, Vec3 n, Vec3 p,
                                SpecularFn spec) {
  const Vec3 v = f.lighting.v_at(p);
  Vec3 c = fr.ka;
  for (const Light& l : f.lighting.lights) {
    const Vec3 ld = Lighting::l_at(l, p);
    c = c + mul(l.colour, fr.kd * std::max(0.0, dot(n, ld)) + fr.ks * spec(n, ld, v, fr.shininess));
  }
  return c;
}

// round(255·c) per channel after clamping to [0, 1]. Round half up; x + 0.5 truncated is
// llround for the non-negative values here (and a third of the cost of three calls per pixel).
[[nodiscard]] inline Rgb8 to_rgb8(Vec3 c) {
  const auto byte = [](double x) {
    return static_cast<std::uint8_t>(std::clamp(x, 0.0, 1.0) * 255 + 0.5);
  };
  return {byte(c.x), byte(c.y), byte(c.z)};
}

[[nodiscard]] inline Vec3 clamp01(Vec3 c) {
  return {std::clamp(c.x, 0.0, 1.0), std::clamp(c.y, 0.0, 1.0), std::clamp(c.z, 0.0, 1.0)};
}

[[nodiscard]] inline double channel(Vec3 c, int ch) {
  return ch == 0 ? c.x : (ch == 1 ? c.y : c.z);
}

// The frame's size filled with its background.
[[nodiscard]] inline Image blank(const Frame& f) { return Image(f.width, f.height, f.background); }

// A fragment that carries only the frame's material: for lighting points that are not the
// visible pixels (samples, span ends, track points).
[[nodiscard]] Fragment material_fragment(const Frame& f);

// ---- Per-triangle samples and spans ----

// The six sample points of triangle t in eq. 4.2 order: positions (vertices and edge
// midpoints) and unit normals (Vlasic §4.3 step 1: midpoint normals are the normalized
// bisectors of their vertices' normals). With midpoints false only the vertices (samples 0, 2,
// 4) are filled in. Throws Error (quad::sample_normals) for opposite vertex normals.
struct SamplePoints {
  std::array<Vec3, 6> p, n;
};
[[nodiscard]] SamplePoints sample_points(const Frame& f, int t, bool midpoints = true);

// Phong's lighting (lyon::phong) at the six sample points of triangle t, clamped to [0, 1]: the
// colours the vertex methods interpolate (in float and through the quadratic unit).
[[nodiscard]] std::array<Vec3, 6> sample_colours(const Frame& f, int t);

// Triangle t's centroid (world), (p0 + p1 + p2)/3.
[[nodiscard]] inline Vec3 centroid(const Frame& f, std::size_t t) {
  const auto& idx = f.geometry.triangles[t];
  return (f.geometry.positions[idx[0]] + f.geometry.positions[idx[1]] +
          f.geometry.positions[idx[2]]) *
         (1.0 / 3);
}

// Triangle t's surface at pixel (x, y)'s centre: the interpolated normal (not normalized) and
// position, computed exactly as the fragments' (mesh_frame).
struct Surface {
  Vec3 n, p;
};
[[nodiscard]] Surface surface_at(const Frame& f, std::size_t t,
                                 const std::array<quad::Vertex2, 3>& pv, int x, int y);

struct Span {
  int y = 0, x0 = 0, x1 = 0;  // pixels x0..x1 of row y
  Surface s1, s2;             // at the end pixels
  Vec3 n1, n2;                // their normals normalized
};

// Spans of triangle t in row order: from the first to the last covered pixel of each row (the
// scanline methods: Kuijk-Blake, Fence, highlight track).
[[nodiscard]] std::vector<Span> spans_of(const Frame& f, std::size_t t);

// ---- Kuijk-Blake angular interpolation (seed 001, section 1.2) ----
// Diffuse cos α(N, L) and specular cos^n β(N, H) through the three-piece quadratic (n for the
// diffuse term 1; the specular exponent 4n, the halfway form of Phong's n as in Lyon's
// specfuns.m), in float and through the engine.

// The quadratic's (a, b) for exponent n: the least-squares fit, for every exponent (the closed
// forms degrade fast beyond Kuijk-Blake's range 1..125).
[[nodiscard]] kb::QuadParams kb_ab(double n);

// One light along one span: the light and halfway directions at the two ends.
struct KbLightEnds {
  Vec3 l1, l2, h1, h2;
};
[[nodiscard]] KbLightEnds kb_light_ends(const Frame& f, const Light& l, const Span& e);

}  // namespace phongsim::shading
