// Tests for meshes (sim/render/mesh.*, sim/render/teapot.*): the built-in objects' counts,
// closedness, winding and normals checked against independent geometric facts (Euler's formula,
// exact volumes, support points), the teapot's tessellation, reading OBJ files written here
// (through tinyobjloader) and their errors, and normalize_to_unit_box. Scenes: scene_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "base/vec3.h"
#include "sim/render/mesh.h"
#include "sim/render/teapot.h"
#include "tests/error_of.h"
#include "tests/mesh_helpers.h"

namespace {

namespace fs = std::filesystem;
using namespace phongsim::testing;  // tests/mesh_helpers.h, tests/error_of.h
using phongsim::Error;
using phongsim::Mesh;
using phongsim::Vec3;

constexpr double kPi = 3.14159265358979323846;

Vec3 Centroid(const Mesh& m, const std::array<int, 3>& t) {
  return (m.positions[t[0]] + m.positions[t[1]] + m.positions[t[2]]) * (1.0 / 3);
}

Vec3 FaceNormal(const Mesh& m, const std::array<int, 3>& t) {
  return cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
}

// Convex and centred on the origin: every face normal points away from the centre.
void ExpectOutwardConvex(const Mesh& m) {
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    EXPECT_GT(dot(FaceNormal(m, m.triangles[t]), Centroid(m, m.triangles[t])), 0)
        << "triangle " << t;
  }
  EXPECT_GT(SignedVolume(m), 0);
}

// Unit sphere approximations: vertices on the sphere, normal = position.
void ExpectOnUnitSphere(const Mesh& m) {
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    EXPECT_NEAR(length(m.positions[i]), 1.0, 1e-12) << i;
    EXPECT_NEAR(dot(m.normals[i], m.positions[i]), 1.0, 1e-12) << i;
  }
}

// No two vertices at the same position (a closed mesh with shared vertices).
void ExpectDistinctPositions(const Mesh& m) {
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    for (std::size_t j = i + 1; j < m.positions.size(); ++j) {
      EXPECT_GT(length(m.positions[i] - m.positions[j]), 1e-6) << i << " " << j;
    }
  }
}

// ---- Built-in objects ----

TEST(Sphere, OctahedronCountsFollowEulersFormula) {
  for (int s = 0; s <= 4; ++s) {
    const Mesh m = phongsim::octahedron_sphere(s);
    const int faces = 8 << (2 * s);  // 8·4^s
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(faces)) << s;
    // V - E + F = 2 with E = 3F/2.
    EXPECT_EQ(m.positions.size(), static_cast<std::size_t>(2 + faces / 2)) << s;
  }
  EXPECT_EQ(phongsim::octahedron_sphere(1).triangles.size(), 32u);
  EXPECT_EQ(phongsim::octahedron_sphere(3).triangles.size(), 512u);
  EXPECT_THROW((void)phongsim::octahedron_sphere(-1), Error);
}

TEST(Sphere, OctahedronClosedOutwardUnit) {
  for (int s : {0, 1, 3}) {
    SCOPED_TRACE(s);
    const Mesh m = phongsim::octahedron_sphere(s);
    ExpectWellFormed(m);
    ExpectClosed(m);
    ExpectOutwardConvex(m);
    ExpectOnUnitSphere(m);
    ExpectDistinctPositions(m);
  }
  // The plain octahedron |x| + |y| + |z| <= 1 has volume 4/3; finer ones approach 4π/3.
  EXPECT_NEAR(SignedVolume(phongsim::octahedron_sphere(0)), 4.0 / 3, 1e-12);
  const double v32 = SignedVolume(phongsim::octahedron_sphere(1));
  const double v512 = SignedVolume(phongsim::octahedron_sphere(3));
  EXPECT_LT(v32, v512);
  EXPECT_LT(v512, 4 * kPi / 3);
  EXPECT_GT(v512, 0.95 * 4 * kPi / 3);
}

TEST(Dodecahedron, ThirtySixTrianglesOnTwentyVertices) {
  const Mesh m = phongsim::dodecahedron();
  EXPECT_EQ(m.triangles.size(), 36u);
  EXPECT_EQ(m.positions.size(), 20u);
  ExpectWellFormed(m);
  ExpectClosed(m);
  ExpectOutwardConvex(m);
  ExpectOnUnitSphere(m);
  ExpectDistinctPositions(m);
  // Circumradius 1 gives edge a = 4 / (√3 (1 + √5)); a pentagon's diagonal is φ·a. Every fan
  // triangle has two sides that are edges or diagonals of its pentagon, nothing else.
  const double phi = (1 + std::sqrt(5.0)) / 2;
  const double a = 4 / (std::sqrt(3.0) * (1 + std::sqrt(5.0)));
  int edges = 0, diagonals = 0;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const double len = length(m.positions[t[(k + 1) % 3]] - m.positions[t[k]]);
      if (std::abs(len - a) < 1e-12) {
        ++edges;
      } else if (std::abs(len - phi * a) < 1e-12) {
        ++diagonals;
      } else {
        ADD_FAILURE() << "side of length " << len;
      }
    }
  }
  EXPECT_EQ(edges, 2 * 30);      // 30 edges, each in two triangles
  EXPECT_EQ(diagonals, 2 * 24);  // 2 fan diagonals per pentagon, each in two triangles
  // V = (15 + 7√5) / 4 · a³.
  EXPECT_NEAR(SignedVolume(m), (15 + 7 * std::sqrt(5.0)) / 4 * a * a * a, 1e-12);
}

TEST(Sphere40, FortyTrianglesClosedOutward) {
  const Mesh m = phongsim::sphere40();
  EXPECT_EQ(m.triangles.size(), 40u);
  EXPECT_EQ(m.positions.size(), 22u);
  ExpectWellFormed(m);
  ExpectClosed(m);
  ExpectOutwardConvex(m);
  ExpectOnUnitSphere(m);
  ExpectDistinctPositions(m);
  EXPECT_LT(SignedVolume(m), 4 * kPi / 3);
  // Poles at ±y; every other vertex on one of 4 rings at y = cos(36° k).
  for (const Vec3& p : m.positions) {
    bool on_ring = std::abs(std::abs(p.y) - 1) < 1e-12;
    for (int k = 1; k <= 4; ++k) on_ring = on_ring || std::abs(p.y - std::cos(kPi * k / 5)) < 1e-12;
    EXPECT_TRUE(on_ring) << p.y;
  }
}

TEST(Triangle, FacesViewerWithNormalsTiltedOutwards) {
  const Mesh m = phongsim::single_triangle();
  ExpectWellFormed(m);
  ASSERT_EQ(m.triangles.size(), 1u);
  const Vec3 fn = FaceNormal(m, m.triangles[0]);
  EXPECT_GT(fn.z, 0);
  EXPECT_NEAR(fn.x, 0, 1e-12);
  EXPECT_NEAR(fn.y, 0, 1e-12);
  const Vec3 c = Centroid(m, m.triangles[0]);
  for (int k = 0; k < 3; ++k) {
    const Vec3 p = m.positions[k], n = m.normals[k];
    EXPECT_NEAR(p.z, 0, 0);
    EXPECT_NEAR(length(p), 1.0, 1e-12);             // circumradius 1, centred on the origin
    EXPECT_NEAR(n.z, 2 / std::sqrt(5.0), 1e-12);    // tilted atan(1/2) from +z
    EXPECT_GT(dot(n - Vec3{0, 0, n.z}, p - c), 0);  // ... away from the centre
  }
}

TEST(FlatNormals, OneVertexTripletPerTriangle) {
  const Mesh m = phongsim::flat_normals_split(phongsim::octahedron_sphere(1));
  ExpectWellFormed(m);
  ASSERT_EQ(m.triangles.size(), 32u);
  ASSERT_EQ(m.positions.size(), 96u);
  for (const auto& t : m.triangles) {
    const Vec3 n = normalized(FaceNormal(m, t));
    for (const int i : t) EXPECT_NEAR(length(m.normals[i] - n), 0, 1e-12);
  }
}

TEST(Check, RejectsBrokenMeshes) {
  Mesh good = phongsim::single_triangle();
  EXPECT_NO_THROW(phongsim::check(good));
  Mesh m = good;
  m.triangles[0][2] = 3;
  EXPECT_NE(ErrorOf([&] { phongsim::check(m); }).find("vertex 3"), std::string::npos);
  m = good;
  m.triangles[0][0] = -1;
  EXPECT_THROW(phongsim::check(m), Error);
  m = good;
  m.positions[1].y = std::nan("");
  EXPECT_THROW(phongsim::check(m), Error);
  m = good;
  m.normals[2] = m.normals[2] * 2;
  EXPECT_THROW(phongsim::check(m), Error);
  m = good;
  m.normals.pop_back();
  EXPECT_THROW(phongsim::check(m), Error);
}

// ---- Teapot ----

TEST(Teapot, DefaultFacetCountNearVlasics3750) {
  const Mesh m = phongsim::teapot();
  ExpectWellFormed(m);
  // 32 patches · 8² cells · 2 triangles, minus one triangle per cell along the collapsed control
  // row of the 4 lid-top and 4 bottom patches (8 · 8).
  EXPECT_EQ(m.triangles.size(), 32u * 64 * 2 - 8 * 8);
  EXPECT_GE(m.triangles.size(), 3750 * 0.9);
  EXPECT_LE(m.triangles.size(), 3750 * 1.1);
  EXPECT_EQ(phongsim::teapot(4).triangles.size(), 32u * 16 * 2 - 8 * 4);
}

TEST(Teapot, UprightOutwardAndConsistentlyWound) {
  const Mesh m = phongsim::teapot();
  // The data is z-up with the spout on +x and the handle on -x; rotated: +y up, resting on y = 0,
  // lid knob at 3.15.
  Vec3 lo = m.positions[0], hi = m.positions[0];
  for (const Vec3& p : m.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  EXPECT_NEAR(lo.y, 0, 1e-12);
  EXPECT_NEAR(hi.y, 3.15, 1e-12);
  EXPECT_NEAR(lo.x, -3.0, 0.1);  // handle
  EXPECT_GT(hi.x, 3.2);          // spout
  EXPECT_NEAR(lo.z, -2.0, 1e-12);
  EXPECT_NEAR(hi.z, 2.0, 1e-12);

  EXPECT_GT(phongsim::signed_volume(m), 0);
  EXPECT_GT(SignedVolume(m), 0);
  // Across patch seams the triangles agree in orientation: no directed edge twice.
  for (const auto& [e, count] : DirectedEdges(m)) {
    EXPECT_EQ(count, 1) << "edge " << e.first << "->" << e.second;
  }
  // Vertex normals on the front side of every triangle that uses them.
  for (const auto& t : m.triangles) {
    const Vec3 fn = FaceNormal(m, t);
    for (const int i : t) EXPECT_GT(dot(m.normals[i], fn), 0) << "vertex " << i;
  }
  // Support points: the vertex farthest along d has a normal pointing along d (body sides,
  // lid knob, bottom, spout tip, handle, and diagonals).
  const std::vector<Vec3> dirs{{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},   {0, -1, 0}, {0, 0, 1},
                               {0, 0, -1}, {1, 1, 1},  {-1, 1, -1}, {1, -1, 1}, {-1, -1, 1}};
  for (const Vec3 d : dirs) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      if (dot(m.positions[i], d) > dot(m.positions[best], d)) best = i;
    }
    EXPECT_GT(dot(m.normals[best], normalized(d)), 0.5)
        << "d = (" << d.x << ", " << d.y << ", " << d.z << ")";
  }
}

TEST(Teapot, DegeneratePointsAndSeamsHaveOneNormal) {
  const Mesh m = phongsim::teapot();
  // Every pair of vertices at the same position: either a crease (normals > 60° apart) or the
  // tessellation failed to merge them.
  std::vector<int> order(m.positions.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const Vec3 p = m.positions[a], q = m.positions[b];
    return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
  });
  int coincident = 0;
  for (std::size_t a = 0; a < order.size(); ++a) {
    for (std::size_t b = a + 1;
         b < order.size() && m.positions[order[b]].x - m.positions[order[a]].x < 1e-6; ++b) {
      if (length(m.positions[order[b]] - m.positions[order[a]]) < 1e-6) {
        ++coincident;
        EXPECT_LT(dot(m.normals[order[a]], m.normals[order[b]]), 0.5)
            << "vertices " << order[a] << " and " << order[b] << " at one position";
      }
    }
  }
  // The only coincidence is where the handle's lower end touches the body, at (-2, 0.9, 0) in
  // our axes: two different surfaces, two normals (an unwelded tessellation has hundreds).
  EXPECT_LE(coincident, 1);
  // The lid knob's top and the bottom's centre, where control rows collapse to a point.
  int top = 0, bottom = 0;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i];
    if (length(p - Vec3{0, 3.15, 0}) < 1e-9) {
      ++top;
      EXPECT_NEAR(length(m.normals[i] - Vec3{0, 1, 0}), 0, 1e-4);
    }
    if (length(p) < 1e-9) {
      ++bottom;
      EXPECT_NEAR(length(m.normals[i] - Vec3{0, -1, 0}), 0, 1e-4);
    }
  }
  EXPECT_EQ(top, 1);
  EXPECT_EQ(bottom, 1);
}

TEST(Teapot, BptErrorsNameFileAndLine) {
  TempDir dir;
  const auto error = [&](const std::string& text) {
    const fs::path p = dir.Write("t.bpt", text);
    return ErrorOf([&] { (void)phongsim::read_teapot_bpt(p, 2); });
  };
  const std::string file = (dir.path() / "t.bpt").string();
  std::string patch = "3 3\n";
  for (int i = 0; i < 16; ++i) patch += fmt::format("{} {} 0\n", i % 4, i / 4);
  // A flat 3 x 3 square at z = 0: 2·2² triangles, cross(Su, Sv) = +z.
  const fs::path good = dir.Write("good.bpt", "1\n" + patch);
  const Mesh m = phongsim::read_teapot_bpt(good, 2);
  ExpectWellFormed(m);
  EXPECT_EQ(m.triangles.size(), 8u);
  EXPECT_EQ(m.positions.size(), 9u);
  for (const Vec3& n : m.normals) EXPECT_NEAR(length(n - Vec3{0, 1, 0}), 0, 1e-12);  // z -> y

  EXPECT_TRUE(StartsWith(error("x\n"), file + ":1: ")) << error("x\n");
  EXPECT_TRUE(StartsWith(error("1\n3 2\n"), file + ":2: ")) << error("1\n3 2\n");
  std::string bad = "1\n" + patch;
  bad.replace(bad.find("1 0 0"), 5, "1 zero 0");
  EXPECT_EQ(error(bad), file + ":4: malformed number 'zero'");
  EXPECT_TRUE(StartsWith(error("2\n" + patch), file + ":18: ")) << error("2\n" + patch);
  EXPECT_TRUE(StartsWith(error("1\n" + patch + "junk\n"), file + ":19: "));
}

// ---- OBJ ----

TEST(Obj, QuadBecomesTwoTrianglesWithComputedNormals) {
  TempDir dir;
  const fs::path p = dir.Write("quad.obj", R"(# a unit quad in z = 0
mtllib none.mtl
o quad
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vt 0 0
g group
s off
usemtl whatever
f 1 2 3 4
)");
  const Mesh m = phongsim::read_obj(p);
  ExpectWellFormed(m);
  ASSERT_EQ(m.triangles.size(), 2u);
  ASSERT_EQ(m.positions.size(), 4u);
  const std::vector<Vec3> expected{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const auto& t : m.triangles) {
    EXPECT_GT(FaceNormal(m, t).z, 0);
    for (const int i : t) EXPECT_EQ(m.normals[i], (Vec3{0, 0, 1}));
  }
  // Fan from corner 0: (0, 1, 2), (0, 2, 3), in the file's vertex positions.
  EXPECT_EQ(m.positions[m.triangles[0][0]], expected[0]);
  EXPECT_EQ(m.positions[m.triangles[0][1]], expected[1]);
  EXPECT_EQ(m.positions[m.triangles[0][2]], expected[2]);
  EXPECT_EQ(m.positions[m.triangles[1][0]], expected[0]);
  EXPECT_EQ(m.positions[m.triangles[1][1]], expected[2]);
  EXPECT_EQ(m.positions[m.triangles[1][2]], expected[3]);
}

TEST(Obj, NegativeIndicesAndCornerForms) {
  TempDir dir;
  // Negative indices count back from the vertices read so far; the second face uses i//k with
  // an unnormalized normal, the third i/j/k, the fourth i/j (computed normal).
  const fs::path p = dir.Write("forms.obj", R"(v 0 0 0
v 2 0 0
v 0 2 0
f -3 -2 -1
vn 0 0 4
v 0 0 1
v 2 0 1
v 0 2 1
f 4//1 5//1 6//-1
vt 0 0
vn 1 0 0
f 1/1/2 2/1/2 3/-1/2
f 4/1 5/1 6/1
)");
  const Mesh m = phongsim::read_obj(p);
  ExpectWellFormed(m);
  ASSERT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.positions[m.triangles[0][0]], (Vec3{0, 0, 0}));
  EXPECT_EQ(m.positions[m.triangles[0][2]], (Vec3{0, 2, 0}));
  EXPECT_EQ(m.normals[m.triangles[0][0]], (Vec3{0, 0, 1}));  // computed: +z face
  EXPECT_EQ(m.positions[m.triangles[1][1]], (Vec3{2, 0, 1}));
  EXPECT_EQ(m.normals[m.triangles[1][1]], (Vec3{0, 0, 1}));  // given (0, 0, 4), normalized
  EXPECT_EQ(m.normals[m.triangles[2][1]], (Vec3{1, 0, 0}));  // given
  EXPECT_EQ(m.normals[m.triangles[3][2]], (Vec3{0, 0, 1}));  // computed
  // (position, normal) pairs are vertices: 3 computed + 3 with vn 1 + 3 with vn 2 + 3 computed;
  // the last three share positions 4..6 with the second face but not its normal.
  EXPECT_EQ(m.positions.size(), 12u);
}

TEST(Obj, ErrorsNameFileAndLine) {
  TempDir dir;
  const auto error = [&](const std::string& text) {
    return ErrorOf([&] { (void)phongsim::read_obj(dir.Write("bad.obj", text)); });
  };
  const std::string f = (dir.path() / "bad.obj").string();
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  // tinyobjloader names the line of a malformed index; range and count checks name the file.
  EXPECT_EQ(error(v3 + "# c\nf 1 2 0\n"),
            f + ":5: malformed 'f' statement (an index that is 0, or no number)");
  EXPECT_EQ(error(v3 + "f 1/2/3/4 2 3\n"),
            f + ":4: malformed 'f' statement (an index that is 0, or no number)");
  EXPECT_EQ(error(v3 + "l 1 0\n"),
            f + ":4: malformed 'l' statement (an index that is 0, or no number)");
  EXPECT_EQ(error(v3 + "f 1 2 4\n"), f + ": vertex index 4 out of range (there are 3 vertices)");
  EXPECT_EQ(error(v3 + "f 1 2 -4\n"),
            f + ": a negative (relative) index reaches before the first vertex or normal");
  EXPECT_EQ(error(v3 + "vn 0 0 1\nf 1//-3 2//1 3//1\n"),
            f + ": a negative (relative) index reaches before the first vertex or normal");
  EXPECT_EQ(error(v3 + "f 1//1 2//1 3//1\n"),
            f + ": normal index 1 out of range (there are 0 normals)");
  EXPECT_EQ(error(v3 + "f 1 2\n"), f + ": a face with fewer than 3 vertices");
  std::string big = "f";
  for (int i = 0; i < 256; ++i) big += i % 2 == 0 ? " 1" : " 2";
  EXPECT_EQ(error(v3 + big + "\n"), f + ": a face with more than 255 vertices");
  EXPECT_EQ(error(v3 + "o nothing\n"), f + ": no triangles (no 'f' statements)");
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::read_obj(dir.path() / "missing.obj"); }),
            (dir.path() / "missing.obj").string() + ": cannot read file");
  // PLY files are refused by name (docs/render.md: no Debian library reads them safely).
  EXPECT_EQ(
      ErrorOf([&] { (void)phongsim::read_mesh(dir.Write("m.ply", "ply\n")); }),
      (dir.path() / "m.ply").string() + ": PLY is not read (convert it to OBJ, e.g. with MeshLab)");
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::read_mesh(dir.Write("m.stl", "solid\n")); }),
            (dir.path() / "m.stl").string() + ": unknown mesh format (expected .obj or .bpt)");
}

TEST(Obj, ReadMeshDispatchesByExtensionCaseInsensitively) {
  TempDir dir;
  const Mesh m = phongsim::read_mesh(dir.Write("TRI.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ExpectWellFormed(m);
  EXPECT_EQ(m.triangles, (std::vector<std::array<int, 3>>{{0, 1, 2}}));
}

// ---- normalize_to_unit_box ----

TEST(Normalize, LargestExtentBecomesTwoCentredOnOrigin) {
  Mesh m = phongsim::single_triangle();
  for (Vec3& p : m.positions) p = p * 3 + Vec3{10, -4, 7};
  phongsim::normalize_to_unit_box(m);
  // The triangle's box is √3 x 1.5 x 0 (circumradius 1): x spans [-1, 1], y ±1.5/√3.
  const double hy = 1.5 / std::sqrt(3.0);
  EXPECT_NEAR(m.positions[0].x, -1, 1e-12);
  EXPECT_NEAR(m.positions[1].x, 1, 1e-12);
  EXPECT_NEAR(m.positions[0].y, -hy, 1e-12);
  EXPECT_NEAR(m.positions[2].y, hy, 1e-12);
  for (const Vec3& p : m.positions) EXPECT_NEAR(p.z, 0, 1e-12);
  Mesh flat;
  flat.positions = {{1, 1, 1}};
  flat.normals = {{0, 1, 0}};
  EXPECT_THROW(phongsim::normalize_to_unit_box(flat), Error);
}

}  // namespace
