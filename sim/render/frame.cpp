#include "sim/render/frame.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/error.h"
#include "model/kb_setup.h"
#include "ref/lyon_float.h"

namespace phongsim::shading {

Frame shinyballs(int m) {
  Frame f;
  f.scene = std::string(kShinyballs);
  f.width = 6 * m + 1;
  f.height = 2 * m + 1;
  f.background = {255, 255, 255};
  for (const double n : {1, 4, 16, 64, 256}) {
    f.regions.emplace_back(fmt::format("n={}", n),
                           std::vector<bool>(static_cast<std::size_t>(f.width) * f.height));
  }
  f.lighting.lights = {{normalized({1, 1, -1}), true, {1, 1, 1}},
                       {normalized({1, -1, 1}), true, {1, 1, 1}}};
  f.owner.assign(static_cast<std::size_t>(f.width) * f.height, -1);
  const double ns[] = {1, 4, 16, 64, 256};
  for (int py = 0; py < f.height; ++py) {
    for (int px = 0; px < f.width; ++px) {
      const double xx = (0.5 + (px - m)) / m;
      const double y = -(0.5 + (py - m)) / m;  // MATLAB's y, pointing up
      for (int ni = 0; ni < 5; ++ni) {
        const double x = xx - ni;
        const double z = 1 - x * x - y * y;
        if (z < 0) continue;
        Fragment fr;
        fr.x = px;
        fr.y = py;
        fr.n = {x, y, std::sqrt(z)};
        fr.p = fr.n;
        fr.shininess = ns[ni];
        const double specf = 400.0 * std::pow(ns[ni] / 256.0, 0.25);
        fr.kd = Vec3{35, 35, 35} * (1.0 / 255);
        fr.ks = Vec3{specf, specf, specf} * (1.0 / 255);
        const std::size_t at = static_cast<std::size_t>(py) * f.width + px;
        f.owner[at] = static_cast<int>(f.fragments.size());
        f.regions[static_cast<std::size_t>(ni)].second[at] = true;
        f.fragments.push_back(fr);
        break;
      }
    }
  }
  return f;
}

Frame mesh_frame(const Scene& sc, int width_override) {
  Frame f;
  f.scene = sc.name;
  f.mesh = true;
  f.width = sc.width;
  f.height = sc.height;
  if (width_override > 0) {
    f.height = std::max(1, static_cast<int>(std::lround(static_cast<double>(sc.height) *
                                                        width_override / sc.width)));
    f.width = width_override;
  }
  if (f.width > 2048 || f.height > 2048) {
    throw Error(fmt::format("image {} x {} exceeds the 2048 x 2048 screen", f.width, f.height));
  }
  const auto byte = [](double c) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255));
  };
  f.background = {byte(sc.background.x), byte(sc.background.y), byte(sc.background.z)};
  f.geometry = sc.mesh;
  f.material = sc.material;
  f.lighting.lights = sc.lights;
  const Camera& cam = sc.camera;
  const Vec3 w = normalized(cam.eye - cam.target);
  const Vec3 u = normalized(cross(cam.up, w));
  const Vec3 v = cross(w, u);
  const bool ortho = cam.fov_deg <= 0;
  f.lighting.view_at_infinity = ortho;
  f.lighting.view_dir = w;
  f.lighting.eye = cam.eye;
  f.cam_right = u;
  f.cam_up = v;
  const Box box = bounding_box(sc.mesh);
  f.centre = (box.lo + box.hi) * 0.5;
  const double half_h = f.height / 2.0;
  const double focal = ortho ? half_h / (cam.ortho_height / 2)
                             : half_h / std::tan(cam.fov_deg * 3.14159265358979323846 / 360);
  const std::size_t nv = sc.mesh.positions.size();
  std::vector<quad::Vertex2> sv(nv);
  std::vector<double> depth(nv);
  std::vector<bool> in_front(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const Vec3 d = sc.mesh.positions[i] - cam.eye;
    const double cx = dot(d, u), cy = dot(d, v), cz = -dot(d, w);  // cz: distance ahead
    in_front[i] = ortho || cz > 1e-6;
    const double scale = ortho ? focal : focal / cz;
    sv[i] = {f.width / 2.0 + cx * scale, half_h - cy * scale};
    depth[i] = cz;
  }
  std::vector<double> zbuf(static_cast<std::size_t>(f.width) * f.height,
                           std::numeric_limits<double>::infinity());
  struct Hit {
    int tri = -1;
    quad::St st;
  };
  std::vector<Hit> hits(zbuf.size());
  const double limit = 2048;
  for (std::size_t t = 0; t < sc.mesh.triangles.size(); ++t) {
    const auto& idx = sc.mesh.triangles[t];
    quad::SubpixelTri tri;
    bool usable = true;
    for (int k = 0; k < 3; ++k) {
      const quad::Vertex2 p = sv[static_cast<std::size_t>(idx[k])];
      if (!in_front[static_cast<std::size_t>(idx[k])] || p.x < 0 || p.y < 0 || p.x > limit ||
          p.y > limit) {
        usable = false;
      }
    }
    if (!usable) {
      throw Error(fmt::format(
          "scene '{}': triangle {} leaves the 2048 x 2048 screen or the space in front of the "
          "camera (move the camera back or shrink the mesh)",
          sc.name, t));
    }
    tri = quad::quantize(sv[idx[0]], sv[idx[1]], sv[idx[2]], kSubBits);
    f.screen.push_back(tri);
    f.coverage.push_back(quad::raster(tri, f.width, f.height));
    if (quad::orientation(tri) == 0) continue;
    const auto pv = quad::to_pixels(tri);
    for (const auto& [x, y] : f.coverage.back()) {
      const quad::St st = quad::st_at(pv[0], pv[1], pv[2], {x + 0.5, y + 0.5});
      const double z =
          (1 - st.s - st.t) * depth[idx[0]] + st.s * depth[idx[1]] + st.t * depth[idx[2]];
      const std::size_t at = static_cast<std::size_t>(y) * f.width + x;
      if (z < zbuf[at]) {
        zbuf[at] = z;
        hits[at] = {static_cast<int>(t), st};
      }
    }
  }
  f.owner.assign(zbuf.size(), -1);
  f.seen.resize(zbuf.size());
  f.visible.resize(sc.mesh.triangles.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    f.seen[i] = hits[i].tri;
    if (hits[i].tri >= 0) f.visible[static_cast<std::size_t>(hits[i].tri)] = true;
  }
  for (int y = 0; y < f.height; ++y) {
    for (int x = 0; x < f.width; ++x) {
      const std::size_t at = static_cast<std::size_t>(y) * f.width + x;
      const Hit& h = hits[at];
      if (h.tri < 0) continue;
      const auto& idx = sc.mesh.triangles[static_cast<std::size_t>(h.tri)];
      const auto lerp = [&](const std::vector<Vec3>& a) {
        return (1 - h.st.s - h.st.t) * a[idx[0]] + h.st.s * a[idx[1]] + h.st.t * a[idx[2]];
      };
      Fragment fr;
      fr.x = x;
      fr.y = y;
      fr.tri = h.tri;
      fr.st = h.st;
      fr.n = lerp(sc.mesh.normals);
      fr.p = lerp(sc.mesh.positions);
      fr.shininess = sc.material.shininess;
      fr.kd = sc.material.diffuse;
      fr.ks = sc.material.specular;
      fr.ka = sc.material.ambient;
      f.owner[at] = static_cast<int>(f.fragments.size());
      f.fragments.push_back(fr);
    }
  }
  return f;
}

Vec3 combine(const Fragment& fr, const std::vector<Light>& lights,
             const std::vector<Amounts>& amounts) {
  Vec3 c = fr.ka;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    c = c + mul(lights[i].colour, fr.kd * amounts[i].diff + fr.ks * amounts[i].spec);
  }
  return c;
}

Fragment material_fragment(const Frame& f) {
  Fragment fr;
  fr.shininess = f.material.shininess;
  fr.kd = f.material.diffuse;
  fr.ks = f.material.specular;
  fr.ka = f.material.ambient;
  return fr;
}

SamplePoints sample_points(const Frame& f, int t, bool midpoints) {
  const auto& idx = f.geometry.triangles[static_cast<std::size_t>(t)];
  const Vec3 p[3] = {f.geometry.positions[idx[0]], f.geometry.positions[idx[1]],
                     f.geometry.positions[idx[2]]};
  const Vec3 n[3] = {f.geometry.normals[idx[0]], f.geometry.normals[idx[1]],
                     f.geometry.normals[idx[2]]};
  if (!midpoints) {
    return {{p[0], {}, p[1], {}, p[2], {}},
            {normalized(n[0]), {}, normalized(n[1]), {}, normalized(n[2]), {}}};
  }
  return {{p[0], (p[0] + p[1]) * 0.5, p[1], (p[1] + p[2]) * 0.5, p[2], (p[2] + p[0]) * 0.5},
          quad::sample_normals(n[0], n[1], n[2])};
}

std::array<Vec3, 6> sample_colours(const Frame& f, int t) {
  const SamplePoints sp = sample_points(f, t);
  const Fragment fr = material_fragment(f);
  std::array<Vec3, 6> c;
  for (int k = 0; k < 6; ++k) c[k] = clamp01(shade(f, fr, sp.n[k], sp.p[k], lyon::phong));
  return c;
}

Surface surface_at(const Frame& f, std::size_t t, const std::array<quad::Vertex2, 3>& pv, int x,
                   int y) {
  const auto& idx = f.geometry.triangles[t];
  const quad::St st = quad::st_at(pv[0], pv[1], pv[2], {x + 0.5, y + 0.5});
  const auto at = [&](const std::vector<Vec3>& a) {
    return (1 - st.s - st.t) * a[idx[0]] + st.s * a[idx[1]] + st.t * a[idx[2]];
  };
  return {at(f.geometry.normals), at(f.geometry.positions)};
}

std::vector<Span> spans_of(const Frame& f, std::size_t t) {
  std::vector<Span> spans;
  const auto& cov = f.coverage[t];
  if (!cov.empty())
    spans.reserve(static_cast<std::size_t>(cov.back().second - cov.front().second + 1));
  for (const auto& [x, y] : cov) {
    if (spans.empty() || spans.back().y != y) spans.push_back({y, x, x, {}, {}, {}, {}});
    spans.back().x1 = x;
  }
  const auto pv = quad::to_pixels(f.screen[t]);
  const auto end = [&](int x, int y) {  // the fragment's, when the triangle is visible there
    if (!f.shows(t, x, y)) return surface_at(f, t, pv, x, y);
    const Fragment& fr =
        f.fragments[static_cast<std::size_t>(f.owner[static_cast<std::size_t>(y) * f.width + x])];
    return Surface{fr.n, fr.p};
  };
  for (Span& e : spans) {
    e.s1 = end(e.x0, e.y);
    e.s2 = end(e.x1, e.y);
    e.n1 = normalized(e.s1.n);
    e.n2 = normalized(e.s2.n);
  }
  return spans;
}

kb::QuadParams kb_ab(double n) {
  // The least-squares fit for every exponent (the closed forms degrade fast beyond 125).
  return kb_params(std::max(1.0, std::round(n)), KbAbSource::least_squares);
}

KbLightEnds kb_light_ends(const Frame& f, const Light& l, const Span& e) {
  const Vec3 l1 = Lighting::l_at(l, e.s1.p), l2 = Lighting::l_at(l, e.s2.p);
  return {l1, l2, normalized(l1 + f.lighting.v_at(e.s1.p)),
          normalized(l2 + f.lighting.v_at(e.s2.p))};
}

}  // namespace phongsim::shading
