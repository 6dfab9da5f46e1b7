// Triangle meshes for the renderer: the built-in test objects of the seeds (Kuijk–Blake's
// octahedron spheres, Vlasic's triangle, dodecahedron, 40-triangle sphere; the Utah teapot is
// sim/render/teapot.h) and readers for Wavefront OBJ (through tinyobjloader) and, by extension,
// the Bézier-patch teapot format (.bpt).
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

// Joins vertices whose positions lie within `eps` (max norm) of each other, drops triangles with
// two corners at one position (and of zero area), and merges each set of coincident vertices
// whose normals are within the crease angle (cos >= crease_cos) of the set's first one into a
// single vertex with the normalized mean normal. Zero normals (failed evaluations) take the
// area-weighted face normal afterwards; vertices no triangle uses are dropped.
[[nodiscard]] Mesh weld(const Mesh& in, double eps, double crease_cos);

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
