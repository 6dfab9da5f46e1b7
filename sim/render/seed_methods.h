// The seeds' other shading methods, in float (docs/methods.md): Vlasic's texturing approaches
// (seed 000, chapter 5), Bishop and Weimer's Fast Phong (as seeds 000 and 003 describe it) and
// Lai and Tai's Fence and highlight-track shading (seed 003, section 2). Each shades the frame's
// visible pixels (sim/render/frame.h) with the frame's material and lights; the formulas are in
// ref/texture_maps.h, ref/fast_phong.h and ref/highlight_track.h.
#pragma once

#include "ref/texture_maps.h"
#include "sim/render/frame.h"
#include "sim/render/image.h"

namespace phongsim::shading {

// ---- Vlasic's texturing approaches ----
// Texture coordinates at each triangle's sample points, interpolated in (s, t) per pixel:
// linearly from the vertices (environment map, Blinn map) or by eq. 4.1 from the six samples
// (quadratic Blinn map); the textures are looked up per pixel (texmap::Texture).
//  env_map: one sphere map per light holding (W·L)^n for the light's direction seen from the
//    mesh's bounding-box centre (a point light becomes a light at infinity: the map cannot hold
//    more), indexed by the reflected view vector (eqs. 5.1-5.3); diffuse and ambient Gouraud.
//  blinn_map: the diffuse and specular textures of eqs. 5.4-5.5 (shared by all lights),
//    indexed per light by eqs. 5.6-5.7 with the camera's up vector as the global axis.
//  quad_blinn_map: the same coordinates from the six samples (§5.3).
enum class TextureMethod { env_map, blinn_map, quad_blinn_map };
struct TextureOptions {
  int size = 256;  // texels per side; 0: the exact texture function
  texmap::Filter filter = texmap::Filter::bilinear;
};
[[nodiscard]] Image texture_image(TextureMethod method, const Frame& f, const TextureOptions& to);

// ---- Bishop-Weimer Fast Phong ----
// Per triangle and light, N·L/|N| and N·H/|N| as their Taylor quadratics about the centroid
// (fast_phong::taylor), with L and H fixed at the centroid (Bishop and Weimer put light and eye
// at infinity); diffuse max(T_L, 0), specular max(T_H, 0)^(4n) (their table lookup). Throws
// Error naming the triangle whose normals cancel at the centroid.
[[nodiscard]] Image fast_phong_image(const Frame& f);

// ---- Lai-Tai Fence and highlight-track shading ----
// Per span: Phong (lyon::phong, clamped like every sample colour) at exact normals on the
// sample pixels — the span's two ends (Fence: the triangle's edges) and, for the highlight
// track, the pixel nearest each light's track point — and the colour interpolated linearly
// between neighbouring samples. Lai and Tai put light and eye at infinity, so H is one vector
// per triangle; for a local light or viewer H starts at the centroid's and moves to the track
// point found, twice (with H constant that changes nothing).
[[nodiscard]] Image fence_image(const Frame& f, bool highlight_track);

}  // namespace phongsim::shading
