// Triangle meshes for the renderer: the built-in test objects of the seeds (Kuijk–Blake's
// octahedron spheres, Vlasic's triangle, dodecahedron, 40-triangle sphere and Utah teapot) and
// readers for Wavefront OBJ (through tinyobjloader) and the Bézier-patch teapot format (.bpt).
//
// Conventions shared by everything here:
//  - right-handed coordinates, +y up; the viewer of the built-in scenes sits on +z;
//  - triangles are counter-clockwise seen from outside: the outward face normal is
//    cross(p1 - p0, p2 - p0), so a closed mesh has signed_volume() > 0;
//  - one unit normal per position (smooth vertex normals); a vertex that needs two normals
//    (a crease) is stored twice.
// Every function that builds or reads a mesh returns one that passes check().
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include "base/vec3.h"

namespace phongsim {

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;                  // unit, one per position
  std::vector<std::array<int, 3>> triangles;  // indices into positions, counter-clockwise
};

// Throws Error naming the first problem: normals.size() != positions.size(), an index outside
// [0, positions.size()), a non-finite coordinate, or a normal whose length is not 1 (± 1e-6).
void check(const Mesh& m);

// cross(p1 - p0, p2 - p0) of triangle t: the outward normal scaled by twice the area.
[[nodiscard]] Vec3 face_normal(const Mesh& m, int t);

// Σ over triangles of p0 · (p1 × p2) / 6: the enclosed volume of a closed mesh, positive when
// the triangles are counter-clockwise seen from outside.
[[nodiscard]] double signed_volume(const Mesh& m);

// Replaces every normal by the area-weighted average of the face normals of the triangles that
// use the position (a vertex no triangle uses, or whose faces cancel, gets (0, 1, 0)).
void compute_vertex_normals(Mesh& m);

// Every triangle gets its own 3 vertices carrying its face normal (for flat shading). Triangles
// of zero area get (0, 1, 0).
[[nodiscard]] Mesh flat_normals_split(const Mesh& m);

// ---- Built-in objects ----

// Unit sphere from an octahedron (vertices ±x, ±y, ±z), each triangle split into 4 at its edge
// midpoints `subdivisions` times, every vertex pushed out to the sphere: 8·4^s triangles and
// 4^(s+1) + 2 vertices, normals = positions. s = 1 gives Kuijk–Blake's 32-triangle sphere,
// s = 3 their 512-triangle one (seed 001, photographs 1-6). s in [0, 8].
[[nodiscard]] Mesh octahedron_sphere(int subdivisions);

// Regular dodecahedron with circumradius 1 (vertices (±1, ±1, ±1), (0, ±1/φ, ±φ),
// (±1/φ, ±φ, 0), (±φ, 0, ±1/φ), all / √3). Each pentagon is fan-triangulated from one of its
// corners into 3 triangles, so 12 pentagons give 36 triangles on 20 shared vertices. Vlasic's
// Fig. 6.15 caption says "30 triangles", which no triangulation of a dodecahedron's 12
// pentagons (each needs ≥ 3) gives; we build the 36-triangle one. Normals = positions
// (smooth: the dodecahedron stands for a coarse sphere, as Vlasic uses it).
[[nodiscard]] Mesh dodecahedron();

// Vlasic's 40-triangle sphere (Fig. 6.16), built as a UV sphere with 5 slices (longitude step
// 72°) and 5 stacks (latitude step 36°): poles at ±y, 4 rings of 5 vertices at polar angles
// 36°, 72°, 108°, 144°, the vertex of longitude 0 on each ring in the +z half-plane. 2·5 polar
// triangles + 3 bands · 5 quads · 2 = 40 triangles on 22 vertices; normals = positions.
[[nodiscard]] Mesh sphere40();

// Vlasic's single triangle (§6, Fig. 6.1b): equilateral, circumradius 1, in the plane z = 0,
// facing +z: p0 = (-√3/2, -1/2, 0), p1 = (√3/2, -1/2, 0), p2 = (0, 1, 0). Its vertex normals
// are those of a sphere patch centred at c = (0, 0, -2): n_i = normalize(p_i - c), tilted
// atan(1/2) ≈ 26.6° outwards, so interpolated normals sweep across the triangle and a point
// light in front of it makes a highlight inside (Gouraud shading cannot show it).
[[nodiscard]] Mesh single_triangle();

// ---- Bézier-patch teapot ----

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

// ---- Mesh files ----

// Wavefront OBJ, parsed by tinyobjloader: `v x y z` (anything after z ignored), `vn x y z`, `f`
// with corners `i`, `i/j`, `i//k` or `i/j/k` (1-based, negative = relative to the end of the
// list so far); polygons are fan-triangulated from their first corner. Everything else (vt, o,
// g, s, usemtl, mtllib, l, p, comments, unknown statements) is ignored; so is a malformed number,
// which tinyobjloader reads as 0. A corner with a normal gets it (normalized); corners without
// one get the area-weighted vertex normal of their position; vertices are the distinct
// (position, normal) pairs in order of first use. Throws Error("<file>:<line>: <what>") for a
// malformed `f`, `l` or `p` statement (an index that is 0 or no number), Error("<file>: <what>")
// for an index out of range, a face with fewer than 3 or more than 255 corners, and a file
// without faces.
[[nodiscard]] Mesh read_obj(const std::filesystem::path& path);

// By extension, case-insensitive: .obj -> read_obj, .bpt -> read_teapot_bpt at
// kTeapotDefaultResolution. Error otherwise (PLY is not read: docs/render.md says why).
[[nodiscard]] Mesh read_mesh(const std::filesystem::path& path);

// The axis-aligned bounding box of the positions. Error for an empty mesh.
struct Box {
  Vec3 lo, hi;
};
[[nodiscard]] Box bounding_box(const Mesh& m);

// Moves the bounding box's centre to the origin and scales uniformly so the largest extent is 2
// (the mesh fits [-1, 1]³). Normals are unchanged. Error for a mesh of zero extent.
void normalize_to_unit_box(Mesh& m);

}  // namespace phongsim
