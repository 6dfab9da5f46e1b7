// Test helpers shared by the mesh and scene tests (mesh_test.cpp, scene_test.cpp): checks of a
// Mesh independent of phongsim::check() (well formed, closed and consistently wound, signed
// volume), and the per-test temporary directory of tests/temp_dir.h.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "base/vec3.h"
#include "sim/render/mesh.h"
#include "tests/temp_dir.h"

namespace phongsim::testing {

inline bool StartsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// Every normal finite and of unit length, every index in range (independent of check()).
inline void ExpectWellFormed(const Mesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const Vec3 p = m.positions[i], n = m.normals[i];
    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "vertex " << i;
    ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << "normal " << i;
    ASSERT_NEAR(length(n), 1.0, 1e-12) << "normal " << i;
  }
  for (const auto& t : m.triangles) {
    for (const int i : t) {
      ASSERT_GE(i, 0);
      ASSERT_LT(i, static_cast<int>(m.positions.size()));
    }
  }
  EXPECT_NO_THROW(phongsim::check(m));
}

// Directed edge -> how many triangles run it.
inline std::map<std::pair<int, int>, int> DirectedEdges(const Mesh& m) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  return edges;
}

// Closed and consistently oriented: every edge is shared by exactly two triangles, which run it
// in opposite directions.
inline void ExpectClosed(const Mesh& m) {
  const auto edges = DirectedEdges(m);
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1) << "edge " << e.first << "->" << e.second;
    const auto rev = edges.find({e.second, e.first});
    EXPECT_TRUE(rev != edges.end() && rev->second == 1)
        << "edge " << e.first << "->" << e.second << " has no opposite";
  }
}

inline double SignedVolume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    v += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]])) / 6;
  }
  return v;
}

}  // namespace phongsim::testing
