#include "sim/render/mesh.h"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <regex>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include "base/error.h"
#include "base/file_util.h"
#include "base/paths.h"
#include "base/text.h"
#include "sim/render/teapot.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

constexpr Vec3 kUp{0, 1, 0};  // the normal of last resort (never NaN)

[[noreturn]] void fail_at(const fs::path& file, int line, const std::string& what) {
  throw Error(fmt::format("{}:{}: {}", file.string(), line, what));
}

[[noreturn]] void fail_file(const fs::path& file, const std::string& what) {
  throw Error(fmt::format("{}: {}", file.string(), what));
}

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// normalized(v), or `fallback` when v has no usable direction (zero, tiny or not finite).
Vec3 normalized_or(Vec3 v, Vec3 fallback) {
  const double len = length(v);
  if (!(len > 0) || !std::isfinite(len) || !std::isfinite(1.0 / len)) return fallback;
  const Vec3 n = normalized(v);
  return finite(n) ? n : fallback;
}

// Area-weighted vertex normals of `positions` under `tris` (kUp where no face contributes).
std::vector<Vec3> area_weighted_normals(const std::vector<Vec3>& positions,
                                        const std::vector<std::array<int, 3>>& tris) {
  std::vector<Vec3> sum(positions.size());
  for (const auto& t : tris) {
    const Vec3 n = cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
    for (const int i : t) sum[i] = sum[i] + n;
  }
  for (Vec3& n : sum) n = normalized_or(n, kUp);
  return sum;
}

// Appends polygon `corners` (indices into the output vertices) fan-triangulated from corner 0.
void fan(const std::vector<int>& corners, std::vector<std::array<int, 3>>& out) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    out.push_back({corners[0], corners[k], corners[k + 1]});
  }
}

// Drops vertices no triangle uses (keeping the order of the others).
void remove_unreferenced(Mesh& m) {
  std::vector<int> remap(m.positions.size(), -1);
  for (const auto& t : m.triangles) {
    for (const int i : t) remap[i] = 0;
  }
  Mesh out;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (remap[i] < 0) continue;
    remap[i] = static_cast<int>(out.positions.size());
    out.positions.push_back(m.positions[i]);
    out.normals.push_back(m.normals[i]);
  }
  out.triangles = m.triangles;
  for (auto& t : out.triangles) {
    for (int& i : t) i = remap[i];
  }
  m = std::move(out);
}

}  // namespace

// ---- Mesh helpers ----

void check(const Mesh& m) {
  if (m.normals.size() != m.positions.size()) {
    throw Error(
        fmt::format("mesh: {} normals for {} positions", m.normals.size(), m.positions.size()));
  }
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (!finite(m.positions[i])) throw Error(fmt::format("mesh: position {} is not finite", i));
    const double len = length(m.normals[i]);
    if (!std::isfinite(len) || std::abs(len - 1) > 1e-6) {
      throw Error(fmt::format("mesh: normal {} has length {} (must be 1)", i, len));
    }
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (const int i : m.triangles[t]) {
      if (i < 0 || static_cast<std::size_t>(i) >= m.positions.size()) {
        throw Error(fmt::format("mesh: triangle {} uses vertex {} (there are {})", t, i,
                                m.positions.size()));
      }
    }
  }
}

Vec3 face_normal(const Mesh& m, int t) {
  const auto& idx = m.triangles[static_cast<std::size_t>(t)];
  const Vec3 p0 = m.positions[idx[0]];
  return cross(m.positions[idx[1]] - p0, m.positions[idx[2]] - p0);
}

double signed_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) {
    v += dot(m.positions[t[0]], cross(m.positions[t[1]], m.positions[t[2]]));
  }
  return v / 6;
}

void compute_vertex_normals(Mesh& m) {
  m.normals = area_weighted_normals(m.positions, m.triangles);
}

Mesh flat_normals_split(const Mesh& m) {
  Mesh out;
  out.positions.reserve(3 * m.triangles.size());
  out.normals.reserve(3 * m.triangles.size());
  out.triangles.reserve(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Vec3 n = normalized_or(face_normal(m, static_cast<int>(t)), kUp);
    const int base = static_cast<int>(out.positions.size());
    for (const int i : m.triangles[t]) {
      out.positions.push_back(m.positions[i]);
      out.normals.push_back(n);
    }
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

Mesh weld(const Mesh& in, double eps, double crease_cos) {
  const std::size_t n = in.positions.size();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return in.positions[a].x < in.positions[b].x; });
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3 pa = in.positions[order[a]];
    for (std::size_t b = a + 1; b < n && in.positions[order[b]].x - pa.x <= eps; ++b) {
      const Vec3 pb = in.positions[order[b]];
      if (std::abs(pb.y - pa.y) <= eps && std::abs(pb.z - pa.z) <= eps) {
        const int ra = find(order[a]), rb = find(order[b]);
        if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
      }
    }
  }

  // Clusters: per position group, one output vertex per normal direction.
  struct Cluster {
    Vec3 direction;  // the first non-zero member normal (unit)
    Vec3 sum;
    int out = -1;
  };
  std::map<int, std::vector<Cluster>> groups;
  std::vector<int> vertex_out(n);
  Mesh out;
  for (std::size_t i = 0; i < n; ++i) {
    auto& clusters = groups[find(static_cast<int>(i))];
    const Vec3 nrm = normalized_or(in.normals[i], {});
    Cluster* hit = nullptr;
    for (Cluster& c : clusters) {
      if (nrm == Vec3{} || c.direction == Vec3{} || dot(c.direction, nrm) >= crease_cos) {
        hit = &c;
        break;
      }
    }
    if (hit == nullptr) {
      clusters.push_back({nrm, {}, static_cast<int>(out.positions.size())});
      out.positions.push_back(in.positions[i]);
      hit = &clusters.back();
    }
    if (hit->direction == Vec3{}) hit->direction = nrm;
    hit->sum = hit->sum + nrm;
    vertex_out[i] = hit->out;
  }
  out.normals.assign(out.positions.size(), {});
  for (const auto& [root, clusters] : groups) {
    for (const Cluster& c : clusters) out.normals[c.out] = normalized_or(c.sum, {});
  }
  for (const auto& t : in.triangles) {
    const int g0 = find(t[0]), g1 = find(t[1]), g2 = find(t[2]);
    if (g0 == g1 || g1 == g2 || g2 == g0) continue;
    const std::array<int, 3> tri{vertex_out[t[0]], vertex_out[t[1]], vertex_out[t[2]]};
    const Vec3 fn = cross(out.positions[tri[1]] - out.positions[tri[0]],
                          out.positions[tri[2]] - out.positions[tri[0]]);
    if (fn == Vec3{}) continue;
    out.triangles.push_back(tri);
  }
  remove_unreferenced(out);
  const std::vector<Vec3> faces = area_weighted_normals(out.positions, out.triangles);
  for (std::size_t i = 0; i < out.normals.size(); ++i) {
    if (out.normals[i] == Vec3{}) out.normals[i] = faces[i];
  }
  return out;
}

// ---- Built-in objects ----

Mesh octahedron_sphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 8) {
    throw Error(fmt::format("octahedron sphere: subdivisions {} outside [0, 8]", subdivisions));
  }
  Mesh m;
  // 0: +x, 1: -x, 2: +y, 3: -y, 4: +z, 5: -z.
  m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // One face per octant (sx, sy, sz): (X, Y, Z) is counter-clockwise from outside in the
  // (+, +, +) octant; every sign flip is a reflection, so an odd number of them reverses it.
  for (int octant = 0; octant < 8; ++octant) {
    const int x = (octant & 1) ? 1 : 0, y = (octant & 2) ? 3 : 2, z = (octant & 4) ? 5 : 4;
    const int flips = (octant & 1) + ((octant >> 1) & 1) + ((octant >> 2) & 1);
    if (flips % 2 == 0) {
      m.triangles.push_back({x, y, z});
    } else {
      m.triangles.push_back({x, z, y});
    }
  }
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    const auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      const int i = static_cast<int>(m.positions.size());
      m.positions.push_back(normalized(0.5 * (m.positions[a] + m.positions[b])));
      midpoint.emplace(key, i);
      return i;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(4 * m.triangles.size());
    for (const auto& [a, b, c] : m.triangles) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.push_back({a, ab, ca});
      next.push_back({ab, b, bc});
      next.push_back({ca, bc, c});
      next.push_back({ab, bc, ca});
    }
    m.triangles = std::move(next);
  }
  m.normals = m.positions;
  return m;
}

Mesh dodecahedron() {
  const double phi = (1 + std::sqrt(5.0)) / 2, iphi = 1 / phi;
  Mesh m;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      for (const double sz : {-1.0, 1.0}) m.positions.push_back({sx, sy, sz});
    }
  }
  for (const double a : {-1.0, 1.0}) {
    for (const double b : {-1.0, 1.0}) {
      m.positions.push_back({0, a * iphi, b * phi});
      m.positions.push_back({a * iphi, b * phi, 0});
      m.positions.push_back({a * phi, 0, b * iphi});
    }
  }
  for (Vec3& p : m.positions) p = p * (1 / std::sqrt(3.0));
  // Each face is centred on a vertex direction of the dual icosahedron, (0, ±φ, ±1),
  // (±1, 0, ±φ), (±φ, ±1, 0): its 5 corners are the vertices farthest along that axis.
  std::vector<Vec3> axes;
  for (const double a : {-1.0, 1.0}) {
    for (const double b : {-1.0, 1.0}) {
      axes.push_back({0, a * phi, b});
      axes.push_back({a, 0, b * phi});
      axes.push_back({a * phi, b, 0});
    }
  }
  for (const Vec3 axis : axes) {
    const Vec3 d = normalized(axis);
    double best = -2;
    for (const Vec3& p : m.positions) best = std::max(best, dot(p, d));
    std::vector<int> face;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      if (dot(m.positions[i], d) > best - 1e-9) face.push_back(static_cast<int>(i));
    }
    if (face.size() != 5) throw Error("dodecahedron: internal error (face is not a pentagon)");
    // Counter-clockwise about the outward axis d: increasing angle in the frame (e1, e2, d).
    const Vec3 centre = best * d;
    const Vec3 e1 = normalized(m.positions[face[0]] - centre);
    const Vec3 e2 = cross(d, e1);
    const auto angle = [&](int i) {
      const Vec3 r = m.positions[i] - centre;
      return std::atan2(dot(r, e2), dot(r, e1));
    };
    std::sort(face.begin(), face.end(), [&](int a, int b) { return angle(a) < angle(b); });
    fan(face, m.triangles);
  }
  m.normals = m.positions;
  for (Vec3& n : m.normals) n = normalized(n);
  return m;
}

Mesh sphere40() {
  constexpr int kSlices = 5, kRings = 4;  // 5 stacks: 4 rings between the poles
  constexpr double kPi = 3.14159265358979323846;
  Mesh m;
  m.positions.push_back({0, 1, 0});  // north pole: 0
  for (int k = 1; k <= kRings; ++k) {
    const double theta = kPi * k / (kRings + 1);
    for (int j = 0; j < kSlices; ++j) {
      const double lon = 2 * kPi * j / kSlices;
      m.positions.push_back(
          {std::sin(theta) * std::sin(lon), std::cos(theta), std::sin(theta) * std::cos(lon)});
    }
  }
  m.positions.push_back({0, -1, 0});  // south pole: 1 + 5·4 = 21
  const int south = static_cast<int>(m.positions.size()) - 1;
  const auto ring = [&](int k, int j) { return 1 + (k - 1) * kSlices + (j % kSlices); };
  // Seen from outside with +y up, longitude grows to the right and rings go down.
  for (int j = 0; j < kSlices; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int k = 1; k < kRings; ++k) {
    for (int j = 0; j < kSlices; ++j) {
      const int ul = ring(k, j), ur = ring(k, j + 1), ll = ring(k + 1, j), lr = ring(k + 1, j + 1);
      m.triangles.push_back({ul, ll, lr});
      m.triangles.push_back({ul, lr, ur});
    }
  }
  for (int j = 0; j < kSlices; ++j) {
    m.triangles.push_back({ring(kRings, j), south, ring(kRings, j + 1)});
  }
  m.normals = m.positions;
  return m;
}

Mesh single_triangle() {
  const double h = std::sqrt(3.0) / 2;
  const Vec3 centre{0, 0, -2};
  Mesh m;
  m.positions = {{-h, -0.5, 0}, {h, -0.5, 0}, {0, 1, 0}};
  for (const Vec3& p : m.positions) m.normals.push_back(normalized(p - centre));
  m.triangles = {{0, 1, 2}};
  return m;
}

// ---- Mesh files ----

namespace {

// tinyobjloader's error as one line, "<file>:<line>: <what>" where it names the line.
[[noreturn]] void fail_obj(const fs::path& path, std::string_view err) {
  err = trim(err.substr(0, err.find('\n')));
  static const std::regex kFailedParse(R"(Failed parse `(\w+)' line.* line (\d+)\.\)$)");
  std::cmatch m;
  if (std::regex_search(err.begin(), err.end(), m, kFailedParse)) {
    fail_at(path, std::stoi(m[2].str()),
            fmt::format("malformed '{}' statement (an index that is 0, or no number)", m[1].str()));
  }
  fail_file(path, std::string(err));
}

// tinyobjloader reads an index into an int and would wrap one beyond its range onto another
// vertex (f 4294967297 ... names vertex 1): such an index is refused here, naming its line.
void check_index_range(const fs::path& path, const std::string& text) {
  std::istringstream lines(text);
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    const std::string_view l = trim(line);
    if (!l.starts_with("f ") && !l.starts_with("f\t") && !l.starts_with("l ") &&
        !l.starts_with("p ")) {
      continue;
    }
    std::size_t at = 2;
    while (at < l.size()) {
      const std::size_t end = l.find_first_of(" \t/", at);
      const std::string_view n = l.substr(at, end == std::string_view::npos ? end : end - at);
      const std::string_view digits = n.starts_with('-') || n.starts_with('+') ? n.substr(1) : n;
      const bool is_number =
          !digits.empty() && digits.find_first_not_of("0123456789") == std::string_view::npos;
      if (is_number && (digits.size() > 10 || std::stoll(std::string(digits)) > 2147483647LL)) {
        fail_at(path, number, fmt::format("index {} is out of range", n));
      }
      if (end == std::string_view::npos) break;
      at = end + 1;
    }
  }
}

}  // namespace

Mesh read_obj(const fs::path& path) {
  const std::string bytes = read_file(path, "file");
  check_index_range(path, bytes);
  std::istringstream text(bytes);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  // No material reader (mtllib is ignored) and no triangulation: polygons are fanned below.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &text, nullptr, false)) {
    fail_obj(path, err);
  }
  if (warn.find("Degenerated face") != std::string::npos) {
    fail_file(path, "a face with fewer than 3 vertices");
  }
  const auto vec = [](const std::vector<tinyobj::real_t>& xyz, std::size_t i) {
    return Vec3{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  };
  const std::size_t n_positions = attrib.vertices.size() / 3;
  const std::size_t n_normals = attrib.normals.size() / 3;
  struct Corner {
    int v = 0;   // 0-based
    int n = -1;  // 0-based, -1: none
  };
  std::vector<std::vector<Corner>> faces;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    std::size_t at = 0;
    for (const unsigned char count : mesh.num_face_vertices) {
      std::vector<Corner>& face = faces.emplace_back();
      for (std::size_t k = 0; k < count && at < mesh.indices.size(); ++k, ++at) {
        const tinyobj::index_t& c = mesh.indices[at];
        if (c.vertex_index < 0 || c.normal_index < -1) {
          fail_file(path, "a negative (relative) index reaches before the first vertex or normal");
        }
        if (static_cast<std::size_t>(c.vertex_index) >= n_positions) {
          fail_file(path, fmt::format("vertex index {} out of range (there are {} vertices)",
                                      c.vertex_index + 1, n_positions));
        }
        if (c.normal_index >= 0 && static_cast<std::size_t>(c.normal_index) >= n_normals) {
          fail_file(path, fmt::format("normal index {} out of range (there are {} normals)",
                                      c.normal_index + 1, n_normals));
        }
        face.push_back({c.vertex_index, c.normal_index});
      }
    }
    // tinyobjloader counts a face's corners in an unsigned char.
    if (at != mesh.indices.size()) fail_file(path, "a face with more than 255 vertices");
  }
  if (faces.empty()) fail_file(path, "no triangles (no 'f' statements)");

  std::vector<Vec3> positions(n_positions);
  for (std::size_t i = 0; i < n_positions; ++i) positions[i] = vec(attrib.vertices, i);
  // Area-weighted normals per position, for corners without a (usable) normal.
  std::vector<std::array<int, 3>> position_tris;
  for (const auto& face : faces) {
    std::vector<int> poly;
    for (const Corner& c : face) poly.push_back(c.v);
    fan(poly, position_tris);
  }
  const std::vector<Vec3> computed = area_weighted_normals(positions, position_tris);
  Mesh m;
  std::map<std::pair<int, int>, int> vertex_of;  // (position, normal) -> vertex
  for (const auto& face : faces) {
    std::vector<int> poly;
    for (Corner c : face) {
      const Vec3 given = c.n >= 0 ? normalized_or(vec(attrib.normals, c.n), {}) : Vec3{};
      if (given == Vec3{}) c.n = -1;
      const auto [it, added] =
          vertex_of.emplace(std::pair{c.v, c.n}, static_cast<int>(m.positions.size()));
      if (added) {
        m.positions.push_back(positions[c.v]);
        m.normals.push_back(c.n >= 0 ? given : computed[c.v]);
      }
      poly.push_back(it->second);
    }
    fan(poly, m.triangles);
  }
  return m;
}

Mesh read_mesh(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".obj") return read_obj(path);
  if (ext == ".bpt") return read_teapot_bpt(path, kTeapotDefaultResolution);
  if (ext == ".ply") fail_file(path, "PLY is not read (convert it to OBJ, e.g. with MeshLab)");
  fail_file(path, "unknown mesh format (expected .obj or .bpt)");
}

Box bounding_box(const Mesh& m) {
  if (m.positions.empty()) throw Error("an empty mesh has no bounding box");
  Box b{m.positions[0], m.positions[0]};
  for (const Vec3& p : m.positions) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  }
  return b;
}

void normalize_to_unit_box(Mesh& m) {
  if (m.positions.empty()) throw Error("cannot normalize an empty mesh");
  const auto [lo, hi] = bounding_box(m);
  const Vec3 extent = hi - lo;
  const double largest = std::max({extent.x, extent.y, extent.z});
  if (!(largest > 0)) throw Error("cannot normalize a mesh of zero extent");
  const Vec3 centre = 0.5 * (lo + hi);
  const double scale = 2 / largest;
  for (Vec3& p : m.positions) p = (p - centre) * scale;
}

}  // namespace phongsim
