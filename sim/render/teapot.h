// The Utah teapot as Vlasic renders it (seed 000, Fig. 6.1a): bicubic Bézier patches read from
// the .bpt format and tessellated into a mesh (sim/render/mesh.h, with its conventions).
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include "base/vec3.h"
#include "sim/render/mesh.h"

namespace phongsim {

// One bicubic patch: control points row by row, p[4 * row + column]. u runs along a row
// (column index), v across rows; the front (outward) side is the one cross(∂S/∂u, ∂S/∂v)
// points to.
struct BezierPatch {
  std::array<Vec3, 16> p;
};

// Reads the .bpt format (../shared/data/README.md): the patch count, then per patch "3 3" and
// 16 lines "x y z". Throws Error("<file>:<line>: <what>") for malformed input (only bicubic
// patches are accepted).
[[nodiscard]] std::vector<BezierPatch> read_bpt_patches(const std::filesystem::path& path);

// Tessellates patches: each is evaluated on a (resolution + 1)² grid of (u, v) and every grid
// cell becomes 2 triangles, those of zero area (at collapsed control rows) dropped. Normals are
// cross(∂S/∂u, ∂S/∂v) from the analytic partial derivatives; where that vanishes (a collapsed
// row: the lid's knob top, the bottom's centre) the normal is taken at a point 10^-5 further
// into the patch (in both u and v). Coincident positions (within 10^-9 of the model's size)
// become one vertex with the normalized mean of their normals, unless those normals differ by
// more than 60° (a crease, which keeps one vertex per side). Coordinates are kept as they are:
// no rotation, no scaling. resolution in [1, 256].
[[nodiscard]] Mesh tessellate(const std::vector<BezierPatch>& patches, int resolution);

// read_bpt_patches + tessellate, then rotated from the .bpt convention (z up) to ours (+y up):
// (x, y, z) -> (x, z, -y), a proper rotation about x, so windings stay counter-clockwise.
[[nodiscard]] Mesh read_teapot_bpt(const std::filesystem::path& path, int resolution);

// The default teapot resolution: 8 gives 32 patches · 8² cells · 2 = 4096 triangles minus the
// 8 · 8 degenerate ones at the collapsed rows of the 4 lid-top and 4 bottom patches = 4032
// facets, the closest to Vlasic's "3750 facets" of all resolutions (7 gives 3080).
inline constexpr int kTeapotDefaultResolution = 8;

// The Utah teapot of data/teapot.bpt (in the repository), read_teapot_bpt(): +y up, spout
// towards +x, resting on y = 0, about 6.4 units long. resolution 0 means the default.
[[nodiscard]] Mesh teapot(int resolution = 0);

}  // namespace phongsim
