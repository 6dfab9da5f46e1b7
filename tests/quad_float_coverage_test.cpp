// Tests for the exact top-left coverage rule of the quadratic-shading reference
// (ref/quad_float.*), shared with the hardware setup: hand-built cases and whole meshes. The
// shading equations: quad_float_coeffs_test.cpp.
//
// Independent references used here: the symbolic perturbation the top-left rule is equivalent to
// (the point P + (ε, ε²), evaluated exactly in __int128 with ε = 1/K), and point-in-polygon
// against the outline of a mesh (its edges used by one triangle only).
#include "ref/quad_float.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "base/error.h"

namespace {

namespace quad = phongsim::quad;
using phongsim::Error;
using quad::SubpixelTri;
using quad::Vertex2;

// ---- helpers ----

SubpixelTri tri_px(Vertex2 a, Vertex2 b, Vertex2 c, int S = 4) {
  return quad::quantize(a, b, c, S);
}

std::vector<std::pair<int, int>> brute_force(const SubpixelTri& t, int x0, int y0, int x1, int y1) {
  std::vector<std::pair<int, int>> out;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      if (quad::covers(t, x, y)) out.emplace_back(x, y);
    }
  }
  return out;
}

// The top-left rule as a symbolic perturbation: P is inside iff P + (ε, ε²) is strictly inside,
// for all small enough ε > 0. With ε = 1/K and everything scaled by M = K², the perturbed edge
// function is M²·E(P) + M·(dx - K·dy): for K > |dx| + |dy| its sign is that of E(P) when
// E(P) != 0, else that of -dy, else that of dx. K = 2^20 is exact in __int128 for |coordinates| <
// 2^15 (|M²E| >= 2^80 dominates |M(dx - K·dy)| < 2^77).
bool covers_perturbed(const SubpixelTri& in, int x, int y) {
  using i128 = __int128;
  const std::int64_t o = quad::orientation(in);
  if (o == 0) return false;
  const SubpixelTri t = o > 0 ? in : quad::reversed(in);
  const i128 K = i128{1} << 20;
  const i128 M = K * K;
  const i128 px = M * quad::pixel_centre(x, t.S) + K;
  const i128 py = M * quad::pixel_centre(y, t.S) + 1;
  for (int e = 0; e < 3; ++e) {
    const int i = e, j = (e + 1) % 3;
    const i128 xi = M * t.X[i], yi = M * t.Y[i], xj = M * t.X[j], yj = M * t.Y[j];
    if ((xj - xi) * (py - yi) - (yj - yi) * (px - xi) <= 0) return false;
  }
  return true;
}

// ---- mesh outline (edges used by exactly one triangle) ----

struct Seg {
  std::int64_t ax, ay, bx, by;
};

// Undirected edge -> number of triangles using it; also checks shared edges are traversed in
// opposite directions once every triangle is made positive.
std::map<std::array<std::int64_t, 4>, int> edge_uses(const std::vector<SubpixelTri>& tris) {
  std::map<std::array<std::int64_t, 4>, int> uses;
  std::set<std::array<std::int64_t, 4>> directed;
  for (const auto& in : tris) {
    const SubpixelTri t = quad::orientation(in) > 0 ? in : quad::reversed(in);
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      std::array<std::int64_t, 4> key{t.X[i], t.Y[i], t.X[j], t.Y[j]};
      EXPECT_TRUE(directed.insert(key).second) << "directed edge used twice";
      if (std::make_pair(key[0], key[1]) > std::make_pair(key[2], key[3])) {
        key = {key[2], key[3], key[0], key[1]};
      }
      ++uses[key];
    }
  }
  return uses;
}

std::vector<Seg> outline(const std::vector<SubpixelTri>& tris) {
  std::vector<Seg> segs;
  for (const auto& [k, n] : edge_uses(tris)) {
    EXPECT_LE(n, 2) << "an edge is shared by more than two triangles";
    if (n == 1) segs.push_back({k[0], k[1], k[2], k[3]});
  }
  return segs;
}

bool on_segment(const Seg& s, std::int64_t px, std::int64_t py) {
  const std::int64_t cross = (s.bx - s.ax) * (py - s.ay) - (s.by - s.ay) * (px - s.ax);
  return cross == 0 && px >= std::min(s.ax, s.bx) && px <= std::max(s.ax, s.bx) &&
         py >= std::min(s.ay, s.by) && py <= std::max(s.ay, s.by);
}

enum class Where { inside, boundary, outside };

// Exact crossing-number test against the outline segments (no ordering needed for parity).
Where locate(const std::vector<Seg>& segs, std::int64_t px, std::int64_t py) {
  bool in = false;
  for (const auto& s : segs) {
    if (on_segment(s, px, py)) return Where::boundary;
    if ((s.ay > py) != (s.by > py)) {
      // Crossing of the horizontal line y = py at x = ax + (py - ay)(bx - ax)/(by - ay): count
      // it when that is right of px.
      const std::int64_t lhs = (px - s.ax) * (s.by - s.ay);
      const std::int64_t rhs = (py - s.ay) * (s.bx - s.ax);
      if (s.by > s.ay ? lhs < rhs : lhs > rhs) in = !in;
    }
  }
  return in ? Where::inside : Where::outside;
}

struct MeshReport {
  int inside = 0;     // centres strictly inside the outline (each must be covered once)
  int boundary = 0;   // centres on the outline (covered at most once)
  int on_vertex = 0;  // centres exactly on a mesh vertex
  int on_edge = 0;    // centres exactly on an edge, between its ends
  int covered = 0;    // pixels covered (once)
};

// Rasterizes every triangle over a width x height screen and checks the coverage counts against
// the outline: strictly inside -> exactly 1, on the outline -> at most 1, outside -> 0. Also
// cross-checks raster() against the perturbation reference on every triangle's bounding box when
// the coordinates are small enough for it.
MeshReport check_mesh(const std::vector<SubpixelTri>& tris, int width, int height,
                      const char* label) {
  SCOPED_TRACE(label);
  MeshReport rep;
  std::vector<int> count(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  std::set<std::pair<std::int64_t, std::int64_t>> vertices;
  for (const auto& t : tris) {
    for (const auto& [x, y] : quad::raster(t, width, height)) {
      ++count[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
              static_cast<std::size_t>(x)];
    }
    for (int k = 0; k < 3; ++k) vertices.insert({t.X[k], t.Y[k]});
  }
  const std::vector<Seg> segs = outline(tris);
  EXPECT_FALSE(segs.empty());
  std::set<std::pair<int, int>> edge_hits;
  const int S = tris.front().S;
  for (const auto& t : tris) {
    const std::int64_t unit = std::int64_t{1} << S;
    bool small = true;  // within covers_perturbed()'s range
    for (int k = 0; k < 3; ++k)
      small = small && std::abs(t.X[k]) < 32768 && std::abs(t.Y[k]) < 32768;
    const int x_lo = std::max<int>(0, static_cast<int>(std::min({t.X[0], t.X[1], t.X[2]}) / unit));
    const int x_hi =
        std::min<int>(width - 1, static_cast<int>(std::max({t.X[0], t.X[1], t.X[2]}) / unit));
    const int y_lo = std::max<int>(0, static_cast<int>(std::min({t.Y[0], t.Y[1], t.Y[2]}) / unit));
    const int y_hi =
        std::min<int>(height - 1, static_cast<int>(std::max({t.Y[0], t.Y[1], t.Y[2]}) / unit));
    for (int y = y_lo; y <= y_hi; ++y) {
      for (int x = x_lo; x <= x_hi; ++x) {
        const std::int64_t px = quad::pixel_centre(x, S), py = quad::pixel_centre(y, S);
        for (int e = 0; e < 3; ++e) {
          const int i = e, j = (e + 1) % 3;
          if (on_segment({t.X[i], t.Y[i], t.X[j], t.Y[j]}, px, py) &&
              !vertices.contains({px, py})) {
            edge_hits.insert({x, y});
          }
        }
        if (small && std::abs(px) < 32768 && std::abs(py) < 32768) {
          EXPECT_EQ(quad::covers(t, x, y), covers_perturbed(t, x, y)) << x << "," << y;
        }
      }
    }
  }
  rep.on_edge = static_cast<int>(edge_hits.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::int64_t px = quad::pixel_centre(x, S), py = quad::pixel_centre(y, S);
      const int n = count[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)];
      EXPECT_LE(n, 1) << "pixel " << x << "," << y << " covered twice";
      rep.covered += n;
      if (vertices.contains({px, py})) ++rep.on_vertex;
      switch (locate(segs, px, py)) {
        case Where::inside:
          ++rep.inside;
          EXPECT_EQ(n, 1) << "pixel " << x << "," << y << " inside the outline";
          break;
        case Where::boundary:
          ++rep.boundary;
          break;
        case Where::outside:
          EXPECT_EQ(n, 0) << "pixel " << x << "," << y << " outside the outline";
          break;
      }
    }
  }
  EXPECT_GT(rep.inside, 0);
  return rep;
}

// ---- coverage: hand-built cases ----

TEST(QuadCoverage, TopLeftRuleOnARightTriangle) {
  // Legs through pixel centres: top edge y = 0.5 (centres (0..3, 0)), left edge x = 0.5 (centres
  // (0, 0..3)), hypotenuse x + y = 5 through centres with i + j = 4. Top and left are in, the
  // hypotenuse (a bottom-right edge here) is out: pixels i, j >= 0 with i + j < 4, i.e. 10.
  for (int S : {1, 2, 4, 8}) {
    const SubpixelTri t = tri_px({0.5, 0.5}, {4.5, 0.5}, {0.5, 4.5}, S);
    EXPECT_GT(quad::orientation(t), 0);
    std::vector<std::pair<int, int>> expect;
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i + j < 4; ++i) expect.emplace_back(i, j);
    }
    EXPECT_EQ(quad::raster(t, 10, 10), expect) << S;
    EXPECT_EQ(quad::raster(quad::reversed(t), 10, 10), expect) << S;
    // Its mirror across the hypotenuse has the hypotenuse as its top-left edge and a right edge
    // x = 4.5 and a bottom edge y = 4.5 (both out): pixels i, j <= 3 with i + j >= 4.
    const SubpixelTri m = tri_px({4.5, 0.5}, {4.5, 4.5}, {0.5, 4.5}, S);
    EXPECT_GT(quad::orientation(m), 0);
    std::vector<std::pair<int, int>> expect_m;
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 4; ++i) {
        if (i + j >= 4) expect_m.emplace_back(i, j);
      }
    }
    EXPECT_EQ(quad::raster(m, 10, 10), expect_m) << S;
  }
}

TEST(QuadCoverage, FlatAndSlopedEdgesThroughCentres) {
  using Px = std::vector<std::pair<int, int>>;
  for (int S : {1, 4}) {
    // Flat top through centres (y = 1.5) is in, except its right end (also on a right edge);
    // the bottom vertex lies on a left and a right edge: out.
    const SubpixelTri top = tri_px({2.5, 1.5}, {8.5, 1.5}, {5.5, 4.5}, S);
    for (int x = 2; x <= 7; ++x) EXPECT_TRUE(quad::covers(top, x, 1)) << x;
    EXPECT_FALSE(quad::covers(top, 8, 1));
    EXPECT_FALSE(quad::covers(top, 5, 4));
    // Flat bottom through centres (y = 5.5) is out, vertices included. The apex (5.5, 2.5) is on
    // the left edge (dy < 0) and the right edge (dy > 0): out. (3.5, 4.5) is on the left edge.
    const SubpixelTri bottom = tri_px({5.5, 2.5}, {8.5, 5.5}, {2.5, 5.5}, S);
    for (int x = 0; x <= 10; ++x) EXPECT_FALSE(quad::covers(bottom, x, 5)) << x;
    EXPECT_FALSE(quad::covers(bottom, 5, 2));
    EXPECT_TRUE(quad::covers(bottom, 3, 4));
    EXPECT_FALSE(quad::covers(bottom, 7, 4));  // (7.5, 4.5) on the right edge
    // Pointing right: edge (2.5,2.5)->(6.5,4.5) bounds the interior from above but is sloped, so
    // it is a right edge (a scanline leaves the triangle there); x = 2.5 is the left edge.
    const SubpixelTri right = tri_px({2.5, 2.5}, {6.5, 4.5}, {2.5, 6.5}, S);
    EXPECT_EQ(quad::raster(right, 10, 10),
              (Px{{2, 3}, {3, 3}, {2, 4}, {3, 4}, {4, 4}, {5, 4}, {2, 5}, {3, 5}}));
    // Pointing left: both sloped edges are left edges, so the leftmost vertex (2.5, 4.5) is in;
    // x = 6.5 is a right edge.
    const SubpixelTri left = tri_px({6.5, 2.5}, {6.5, 6.5}, {2.5, 4.5}, S);
    EXPECT_EQ(quad::raster(left, 10, 10),
              (Px{{4, 3}, {5, 3}, {2, 4}, {3, 4}, {4, 4}, {5, 4}, {4, 5}, {5, 5}}));
    EXPECT_EQ(quad::raster(quad::reversed(left), 10, 10), quad::raster(left, 10, 10));
  }
}

TEST(QuadCoverage, OnePixelTriangles) {
  // Vertices on three neighbouring centres: only the top-left one (on a top and a left edge).
  for (int S : {1, 3, 8}) {
    const SubpixelTri t = tri_px({0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}, S);
    EXPECT_EQ(quad::raster(t, 4, 4), (std::vector<std::pair<int, int>>{{0, 0}})) << S;
    EXPECT_EQ(quad::raster(quad::reversed(t), 4, 4), (std::vector<std::pair<int, int>>{{0, 0}}));
  }
  // A tiny triangle around the centre of pixel (7, 3), and one between centres.
  const SubpixelTri around = tri_px({7.25, 3.25}, {7.875, 3.375}, {7.375, 3.875});
  EXPECT_EQ(quad::raster(around, 16, 16), (std::vector<std::pair<int, int>>{{7, 3}}));
  const SubpixelTri between = tri_px({7.625, 3.625}, {7.875, 3.75}, {7.75, 3.9375});
  EXPECT_TRUE(quad::raster(between, 16, 16).empty());
  // Random triangles of diameter < 1 cover at most one pixel, and agree with the perturbation.
  std::mt19937_64 gen(5);
  std::uniform_int_distribution<int> base(0, 20 * 16);
  std::uniform_int_distribution<int> off(0, 11);  // < 0.75 px at S = 4: diameter < 1
  int hits = 0;
  for (int n = 0; n < 20000; ++n) {
    SubpixelTri t;
    t.S = 4;
    const int bx = base(gen), by = base(gen);
    for (int k = 0; k < 3; ++k) {
      t.X[k] = bx + off(gen);
      t.Y[k] = by + off(gen);
    }
    const auto px = quad::raster(t, 32, 32);
    EXPECT_LE(px.size(), 1u);
    hits += static_cast<int>(px.size());
    for (int y = by / 16 - 1; y <= by / 16 + 2; ++y) {
      for (int x = bx / 16 - 1; x <= bx / 16 + 2; ++x) {
        EXPECT_EQ(quad::covers(t, x, y), covers_perturbed(t, x, y));
      }
    }
  }
  EXPECT_GT(hits, 100);
}

TEST(QuadCoverage, DegenerateTrianglesCoverNothing) {
  for (int S : {1, 4}) {
    // Collinear through pixel centres, a repeated vertex, and all three equal.
    const std::vector<SubpixelTri> tris{tri_px({0.5, 0.5}, {2.5, 2.5}, {5.5, 5.5}, S),
                                        tri_px({1.5, 1.5}, {4.5, 1.5}, {1.5, 1.5}, S),
                                        tri_px({3.5, 3.5}, {3.5, 3.5}, {3.5, 3.5}, S),
                                        tri_px({0.5, 2.5}, {6.5, 2.5}, {3.5, 2.5}, S)};
    for (const auto& t : tris) {
      EXPECT_EQ(quad::orientation(t), 0);
      EXPECT_TRUE(quad::raster(t, 10, 10).empty());
      for (int y = 0; y < 10; ++y) {
        for (int x = 0; x < 10; ++x) EXPECT_FALSE(quad::covers(t, x, y));
      }
    }
  }
}

TEST(QuadCoverage, VertexOrderDoesNotMatter) {
  // All six orders of the vertices (both windings, every starting vertex) cover the same pixels,
  // and raster() equals covers() over the whole screen, including triangles partly off screen.
  std::mt19937_64 gen(6);
  std::uniform_int_distribution<int> coord(-8 * 4, 40 * 4);  // S = 2, many exact coincidences
  for (int n = 0; n < 400; ++n) {
    Vertex2 v[3];
    for (auto& p : v) p = {coord(gen) / 4.0, coord(gen) / 4.0};
    const SubpixelTri t = tri_px(v[0], v[1], v[2], 2);
    const auto expect = brute_force(t, 0, 0, 32, 32);
    EXPECT_EQ(quad::raster(t, 32, 32), expect);
    std::array<int, 3> perm{0, 1, 2};
    do {
      const SubpixelTri p = tri_px(v[perm[0]], v[perm[1]], v[perm[2]], 2);
      EXPECT_EQ(quad::raster(p, 32, 32), expect);
    } while (std::next_permutation(perm.begin(), perm.end()));
    for (int y = -3; y < 40; ++y) {
      for (int x = -3; x < 40; ++x) EXPECT_EQ(quad::covers(t, x, y), covers_perturbed(t, x, y));
    }
  }
}

TEST(QuadCoverage, InteriorMatchesBarycentricSigns) {
  // Away from the edges (no E == 0), covered <=> s > 0, t > 0, s + t < 1 by eq. 3.5 in double
  // (exact signs here: small integer coordinates).
  std::mt19937_64 gen(7);
  std::uniform_int_distribution<int> coord(0, 24 * 8);
  for (int n = 0; n < 300; ++n) {
    SubpixelTri t;
    t.S = 3;
    for (int k = 0; k < 3; ++k) {
      t.X[k] = coord(gen);
      t.Y[k] = coord(gen);
    }
    if (quad::orientation(t) == 0) continue;
    const auto v = quad::to_pixels(t);
    for (int y = 0; y < 24; ++y) {
      for (int x = 0; x < 24; ++x) {
        const std::int64_t px = quad::pixel_centre(x, 3), py = quad::pixel_centre(y, 3);
        if (quad::edge_function(t, 0, 1, px, py) == 0 ||
            quad::edge_function(t, 1, 2, px, py) == 0 ||
            quad::edge_function(t, 2, 0, px, py) == 0) {
          continue;
        }
        const auto st = quad::st_at(v[0], v[1], v[2], {x + 0.5, y + 0.5});
        EXPECT_EQ(quad::covers(t, x, y), st.s > 0 && st.t > 0 && st.s + st.t < 1);
      }
    }
  }
}

TEST(QuadCoverage, PixelSquareSplitEitherWay) {
  // A 4x4-pixel square with corners on centres, split along either diagonal, in either winding:
  // its 16 pixels (0..3)^2, corners and diagonals included, once each; nothing else.
  for (int S : {1, 2, 4, 8}) {
    for (bool main : {false, true}) {
      std::vector<SubpixelTri> tris;
      const Vertex2 a{0.5, 0.5}, b{4.5, 0.5}, c{4.5, 4.5}, d{0.5, 4.5};
      if (main) {
        tris = {tri_px(a, b, c, S), quad::reversed(tri_px(a, c, d, S))};
      } else {
        tris = {quad::reversed(tri_px(a, b, d, S)), tri_px(b, c, d, S)};
      }
      std::vector<int> count(64, 0);
      for (const auto& t : tris) {
        for (const auto& [x, y] : quad::raster(t, 8, 8))
          ++count[static_cast<std::size_t>(y * 8 + x)];
      }
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
          EXPECT_EQ(count[static_cast<std::size_t>(y * 8 + x)], x < 4 && y < 4 ? 1 : 0)
              << S << " " << main << " " << x << "," << y;
        }
      }
    }
  }
}

TEST(QuadCoverage, ExtremeCoordinatesDoNotOverflow) {
  // Vertices at +-2^29 subpixel units (+-2^25 pixels at S = 4): edge functions reach ~2^61.
  // Compare with the same rule evaluated in __int128 at pixels along the edges and corners.
  const std::int64_t L = quad::kMaxCoord;
  const SubpixelTri t{{-L, L, -L}, {-L, -L + 7, L}, 4};
  ASSERT_GT(quad::orientation(t), 0);
  const auto ref = [&](int x, int y) {
    using i128 = __int128;
    const i128 px = quad::pixel_centre(x, 4), py = quad::pixel_centre(y, 4);
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      const i128 dx = t.X[j] - t.X[i], dy = t.Y[j] - t.Y[i];
      const i128 v = dx * (py - t.Y[i]) - dy * (px - t.X[i]);
      if (v < 0 || (v == 0 && !(dy < 0 || (dy == 0 && dx > 0)))) return false;
    }
    return true;
  };
  const int P = static_cast<int>(L >> 4);
  int in = 0;
  for (int a = -3; a <= 3; ++a) {
    for (int b = -3; b <= 3; ++b) {
      for (const auto& [x, y] :
           {std::pair{-P + a, -P + b}, std::pair{P + a, -P + b}, std::pair{-P + a, P + b},
            std::pair{a, b}, std::pair{a, -P + b}, std::pair{-P + a, b}}) {
        EXPECT_EQ(quad::covers(t, x, y), ref(x, y)) << x << "," << y;
        in += ref(x, y);
      }
    }
  }
  EXPECT_GT(in, 20);
  // Far-away pixels (centres beyond +-2^29) are simply outside.
  EXPECT_FALSE(quad::covers(t, std::numeric_limits<int>::max(), 0));
  EXPECT_FALSE(quad::covers(t, 0, std::numeric_limits<int>::min()));
}

TEST(QuadCoverage, RejectsBadInput) {
  SubpixelTri t{{0, 16, 0}, {0, 0, 16}, 4};
  EXPECT_NO_THROW(quad::check(t));
  t.S = 0;
  EXPECT_THROW((void)quad::covers(t, 0, 0), Error);
  t.S = quad::kMaxSubpixelBits + 1;
  EXPECT_THROW((void)quad::raster(t, 4, 4), Error);
  t.S = 4;
  t.X[1] = quad::kMaxCoord + 1;
  EXPECT_THROW(quad::check(t), Error);
  t.X[1] = 16;
  EXPECT_THROW((void)quad::raster(t, -1, 4), Error);
  EXPECT_TRUE(quad::raster(t, 0, 4).empty());
  EXPECT_THROW((void)quad::quantize({0, 0}, {1e30, 0}, {0, 1}, 4), Error);
  EXPECT_THROW((void)quad::quantize({0, 0}, {std::nan(""), 0}, {0, 1}, 4), Error);
}

TEST(QuadCoverage, QuantizeAndBack) {
  const SubpixelTri t = quad::quantize({1.5, 2.25}, {-3.0625, 7}, {0.03, 0.97}, 4);
  EXPECT_EQ(t.X, (std::array<std::int64_t, 3>{24, -49, 0}));
  EXPECT_EQ(t.Y, (std::array<std::int64_t, 3>{36, 112, 16}));
  const auto v = quad::to_pixels(t);
  EXPECT_EQ(v[0], (Vertex2{1.5, 2.25}));
  EXPECT_EQ(v[1], (Vertex2{-3.0625, 7}));
  EXPECT_EQ(v[2], (Vertex2{0, 1}));
  EXPECT_EQ(quad::pixel_centre(0, 4), 8);
  EXPECT_EQ(quad::pixel_centre(-1, 1), -1);
}

// ---- coverage: meshes ----

TEST(QuadMesh, GridsCoverEachInteriorPixelExactlyOnce) {
  struct Case {
    int cols, rows;
    double x0, y0, w, h, jitter;
    bool random_diagonals;
  };
  const std::vector<Case> cases{
      {6, 5, 3.0, 2.0, 7.0, 6.0, 1.2, false},      // jittered, corners anywhere
      {9, 7, 1.3, 2.7, 4.3, 5.1, 0.9, true},       // random diagonals
      {20, 15, 0.0, 0.0, 2.5, 3.0, 0.5, true},     // small cells, partly off the origin edge
      {3, 3, 4.0, 4.0, 13.0, 11.0, 2.5, false},    // large cells
      {12, 10, 0.25, 0.75, 1.5, 1.75, 0.2, true},  // cells near one pixel
  };
  for (int S : {1, 2, 4, 8}) {
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Case& c = cases[k];
      const auto mesh =
          quad::grid_mesh(c.cols, c.rows, c.x0, c.y0, c.w, c.h, c.jitter,
                          1000 * static_cast<std::uint64_t>(S) + k, S, c.random_diagonals);
      ASSERT_EQ(mesh.size(), static_cast<std::size_t>(2 * c.cols * c.rows));
      const auto uses = edge_uses(mesh);
      int boundary = 0;
      for (const auto& [e, n] : uses) boundary += n == 1;
      EXPECT_EQ(boundary, 2 * (c.cols + c.rows));  // every inner edge shared exactly
      int reversed = 0;
      for (const auto& t : mesh) reversed += quad::orientation(t) < 0;
      EXPECT_GT(reversed, 0);
      EXPECT_LT(reversed, static_cast<int>(mesh.size()));
      const int width = static_cast<int>(c.x0 + c.cols * c.w + c.jitter) + 3;
      const int height = static_cast<int>(c.y0 + c.rows * c.h + c.jitter) + 3;
      const auto label = "S=" + std::to_string(S) + " case " + std::to_string(k);
      (void)check_mesh(mesh, width, height, label.c_str());
    }
  }
}

TEST(QuadMesh, CentresExactlyOnEdgesAndVerticesAreCoveredOnce) {
  // Grid vertices on pixel centres: axis-aligned edges run along rows and columns of centres,
  // diagonals of square cells (slope +-1) and of 2x3 cells (every 2nd column) hit centres too.
  struct Case {
    int cols, rows;
    double x0, y0, w, h;
    bool random_diagonals;
  };
  const std::vector<Case> cases{
      {6, 5, 2.5, 3.5, 4, 4, false},  {8, 6, 1.5, 0.5, 4, 4, true}, {9, 7, 0.5, 0.5, 2, 3, true},
      {10, 10, 1.5, 2.5, 1, 1, true},  // one-pixel cells: every centre is a vertex
      {7, 6, 0.5, 0.0, 3, 2, false},   // vertical edges through centres, horizontal between
      {5, 5, 0.0, 0.0, 3, 3, true},    // vertices on pixel corners
  };
  for (int S : {1, 2, 4, 8}) {
    int on_vertex = 0, on_edge = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Case& c = cases[k];
      const auto mesh =
          quad::grid_mesh(c.cols, c.rows, c.x0, c.y0, c.w, c.h, 0, 77 + k, S, c.random_diagonals);
      const int width = static_cast<int>(c.x0 + c.cols * c.w) + 3;
      const int height = static_cast<int>(c.y0 + c.rows * c.h) + 3;
      const auto label = "S=" + std::to_string(S) + " exact case " + std::to_string(k);
      const MeshReport rep = check_mesh(mesh, width, height, label.c_str());
      on_vertex += rep.on_vertex;
      on_edge += rep.on_edge;
      if (k < 4) {
        EXPECT_GT(rep.on_vertex, 0) << label;
        EXPECT_GT(rep.boundary, 0) << label;  // outline through centres too
      }
      if (k < 3) {  // (1x1 cells have no centre between two vertices)
        EXPECT_GT(rep.on_edge, 0) << label;
      }
    }
    EXPECT_GT(on_vertex, 200);
    EXPECT_GT(on_edge, 300);
  }
}

TEST(QuadMesh, FansCoverEachInteriorPixelExactlyOnce) {
  for (int S : {1, 2, 4, 8}) {
    // Diamond with its centre and rim on pixel centres: axis-aligned spokes and diagonal rim
    // edges through centres, and a vertex (the hub) of four triangles on a centre.
    {
      const auto fan = quad::fan_mesh(10.5, 10.5, 6, 4, 0, 0, 11, S);
      const MeshReport rep = check_mesh(fan, 24, 24, "diamond");
      EXPECT_GE(rep.on_vertex, 1);
      EXPECT_GT(rep.on_edge, 10);
      EXPECT_EQ(rep.inside + rep.boundary, 2 * 6 * 6 + 2 * 6 + 1);  // |i| + |j| <= 6
      // Rim: the two left sides (dy < 0) are in, the two right ones out; of the four corners only
      // the leftmost (on two left edges) is in: 2·5 + 1 centres.
      EXPECT_EQ(rep.covered, rep.inside + 2 * 5 + 1);
    }
    // Octagon around a pixel centre, many-sided fans (thin triangles), jittered rims.
    (void)check_mesh(quad::fan_mesh(12.5, 9.5, 8, 8, 0, 0, 12, S), 26, 20, "octagon");
    (void)check_mesh(quad::fan_mesh(20.3, 18.8, 15, 64, 0.3, 0, 13, S), 40, 40, "64-gon");
    if (S >= 4) {  // 0.53-pixel rim steps: coarser grids collapse some triangles
      (void)check_mesh(quad::fan_mesh(20.0, 20.0, 17, 200, 0.0, 0, 14, S), 40, 40, "200-gon");
    }
    (void)check_mesh(quad::fan_mesh(16.5, 16.5, 12, 24, 0.1, 1.0, 15, S), 32, 32, "jittered");
    // A fan of six tiny triangles whose hub is the centre of pixel (3, 3): covered once.
    const auto tiny = quad::fan_mesh(3.5, 3.5, 0.4, 6, 0.2, 0, 16, std::max(S, 4));
    int n = 0;
    for (const auto& t : tiny) n += static_cast<int>(quad::raster(t, 8, 8).size());
    EXPECT_EQ(n, 1);
  }
}

TEST(QuadMesh, SliversCoverEachInteriorPixelExactlyOnce) {
  for (int S : {2, 4, 8}) {
    // Apex far below and above a base through a row of centres (y = 3.5).
    (void)check_mesh(quad::sliver_fan(17.3, 38.6, 1.5, 30.5, 3.5, 40, 21, S), 34, 42, "below");
    (void)check_mesh(quad::sliver_fan(2.5, 0.5, 0.5, 31.5, 36.5, 50, 22, S), 34, 40, "above");
    // Thin, nearly horizontal slivers.
    (void)check_mesh(quad::sliver_fan(60.5, 6.5, 0.5, 12.5, 4.25, 20, 23, S), 64, 10, "horizontal");
  }
}

TEST(QuadMesh, GeneratorsAreDeterministicAndValidateTheirInput) {
  EXPECT_EQ(quad::grid_mesh(4, 3, 0, 0, 5, 5, 1, 9, 4, true),
            quad::grid_mesh(4, 3, 0, 0, 5, 5, 1, 9, 4, true));
  EXPECT_NE(quad::grid_mesh(4, 3, 0, 0, 5, 5, 1, 9, 4, true),
            quad::grid_mesh(4, 3, 0, 0, 5, 5, 1, 10, 4, true));
  EXPECT_EQ(quad::fan_mesh(5, 5, 3, 7, 0, 0.2, 1, 4), quad::fan_mesh(5, 5, 3, 7, 0, 0.2, 1, 4));
  EXPECT_THROW((void)quad::grid_mesh(0, 3, 0, 0, 5, 5, 0, 1, 4, false), Error);
  EXPECT_THROW((void)quad::grid_mesh(3, 3, 0, 0, 4, 5, 1, 1, 4, false), Error);  // jitter >= w/4
  EXPECT_THROW((void)quad::grid_mesh(3, 3, 0, 0, -4, 5, 0, 1, 4, false), Error);
  EXPECT_THROW((void)quad::grid_mesh(3, 3, 0, 0, 4, 5, 0, 1, 0, false), Error);
  EXPECT_THROW((void)quad::grid_mesh(3, 3, 0, 0, 0.25, 0.25, 0, 1, 1, false), Error);  // degenerate
  EXPECT_THROW((void)quad::fan_mesh(5, 5, 3, 2, 0, 0, 1, 4), Error);
  EXPECT_THROW((void)quad::fan_mesh(5, 5, 0, 6, 0, 0, 1, 4), Error);
  EXPECT_THROW((void)quad::fan_mesh(5, 5, 0.1, 64, 0, 0, 1, 1), Error);  // rim collapses
  EXPECT_THROW((void)quad::sliver_fan(5, 5, 3, 1, 0, 4, 1, 4), Error);
  EXPECT_THROW((void)quad::sliver_fan(5, 0, 1, 3, 0, 4, 1, 4), Error);
  EXPECT_THROW((void)quad::sliver_fan(5, 5, 1, 3, 0, 100, 1, 4), Error);
}

}  // namespace
