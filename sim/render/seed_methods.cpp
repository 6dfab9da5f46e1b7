#include "sim/render/seed_methods.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "base/error.h"
#include "ref/fast_phong.h"
#include "ref/highlight_track.h"
#include "ref/lyon_float.h"
#include "ref/texture_maps.h"

namespace phongsim::shading {
namespace {

// v in eye coordinates (x right, y up, z towards the viewer).
Vec3 to_eye(const Frame& f, Vec3 v) {
  return {dot(v, f.cam_right), dot(v, f.cam_up), dot(v, f.lighting.view_dir)};
}

// Interpolants of one triangle: per quantity the eq. 4.1 coefficients through its sample values.
struct Interpolants {
  std::vector<quad::Coeffs> c;
  void add(const std::array<double, 6>& r, bool quadratic) {
    c.push_back(quadratic ? quad::coefficients(r) : quad::linear_coefficients(r[0], r[2], r[4]));
  }
  [[nodiscard]] double at(std::size_t k, quad::St st) const { return quad::eval_st(c[k], st); }
};

}  // namespace

Image texture_image(TextureMethod method, const Frame& f, const TextureOptions& to) {
  const std::vector<Light>& lights = f.lighting.lights;
  const bool env = method == TextureMethod::env_map;
  const bool quadratic = method == TextureMethod::quad_blinn_map;
  const double n = f.material.shininess;
  // The environment map: one sphere map per light, (W·L)^n for the light's direction seen from
  // the object's centre (a point light becomes a light at infinity: the map cannot hold more).
  // The Blinn maps: the diffuse and the specular texture, shared by all lights.
  std::vector<texmap::Texture> tex;
  if (env) {
    for (const Light& l : lights) {
      const Vec3 d =
          to_eye(f, l.at_infinity ? normalized(l.position) : normalized(l.position - f.centre));
      tex.emplace_back(
          [d, n](double u, double v) {
            Vec3 w;
            if (!texmap::sphere_map_direction({u, v}, w)) return 0.0;
            const double c = dot(w, d);
            return c > 0 ? std::pow(c, n) : 0.0;
          },
          0, 1, to.size);
    }
  } else {
    tex.emplace_back(texmap::blinn_diffuse, -1, 1, to.size);
    tex.emplace_back([n4 = 4 * n](double x, double y) { return texmap::blinn_specular(x, y, n4); },
                     -1, 1, to.size);
  }
  const Fragment material = material_fragment(f);
  std::vector<Interpolants> tri(f.geometry.triangles.size());
  std::vector<bool> done(tri.size());
  std::vector<Amounts> a(lights.size());
  Image img = blank(f);
  for (const Fragment& fr : f.fragments) {
    const auto t = static_cast<std::size_t>(fr.tri);
    Interpolants& ip = tri[t];
    if (!done[t]) {
      done[t] = true;
      const SamplePoints sp = sample_points(f, fr.tri, quadratic);
      const int step = quadratic ? 1 : 2;  // linear: the vertices (samples 0, 2, 4) only
      if (env) {
        // (u, v) of the reflected view vector, and the Gouraud diffuse colour per channel.
        std::array<double, 6> u{}, v{}, d[3]{};
        for (int k = 0; k < 6; k += step) {
          const Vec3 nv = sp.n[k], view = f.lighting.v_at(sp.p[k]);
          const texmap::Uv uv = texmap::sphere_map_uv(to_eye(f, 2 * dot(nv, view) * nv - view));
          u[k] = uv.u;
          v[k] = uv.v;
          std::vector<Amounts> diffuse;
          for (const Light& l : lights) {
            diffuse.push_back({std::max(0.0, dot(nv, Lighting::l_at(l, sp.p[k]))), 0});
          }
          const Vec3 c = clamp01(combine(material, lights, diffuse));
          for (int ch = 0; ch < 3; ++ch) d[ch][k] = channel(c, ch);
        }
        ip.add(u, quadratic);
        ip.add(v, quadratic);
        for (const auto& dc : d) ip.add(dc, quadratic);
      } else {
        // Per light: (u, v) in the diffuse plane (normal L) and in the specular one (normal H).
        for (const Light& l : lights) {
          std::array<double, 6> q[4]{};
          for (int k = 0; k < 6; k += step) {
            const Vec3 ld = Lighting::l_at(l, sp.p[k]);
            const Vec3 h = normalized(ld + f.lighting.v_at(sp.p[k]));
            const texmap::Uv du = texmap::blinn_uv(sp.n[k], ld, f.cam_up, f.cam_right);
            const texmap::Uv su = texmap::blinn_uv(sp.n[k], h, f.cam_up, f.cam_right);
            q[0][k] = du.u;
            q[1][k] = du.v;
            q[2][k] = su.u;
            q[3][k] = su.v;
          }
          for (const auto& r : q) ip.add(r, quadratic);
        }
      }
    }
    Vec3 c;
    if (env) {
      c = {ip.at(2, fr.st), ip.at(3, fr.st), ip.at(4, fr.st)};
      const texmap::Uv uv{ip.at(0, fr.st), ip.at(1, fr.st)};
      for (std::size_t k = 0; k < lights.size(); ++k) {
        c = c + mul(lights[k].colour, fr.ks * tex[k].sample(uv, to.filter));
      }
    } else {
      for (std::size_t k = 0; k < lights.size(); ++k) {
        a[k] = {tex[0].sample(ip.at(4 * k, fr.st), ip.at(4 * k + 1, fr.st), to.filter),
                tex[1].sample(ip.at(4 * k + 2, fr.st), ip.at(4 * k + 3, fr.st), to.filter)};
      }
      c = combine(fr, lights, a);
    }
    img.at(fr.x, fr.y) = to_rgb8(c);
  }
  return img;
}

Image fast_phong_image(const Frame& f) {
  const std::vector<Light>& lights = f.lighting.lights;
  const double n4 = 4 * f.material.shininess;
  std::vector<std::vector<std::pair<quad::Coeffs, quad::Coeffs>>> tri(f.geometry.triangles.size());
  std::vector<Amounts> a(lights.size());
  Image img = blank(f);
  for (const Fragment& fr : f.fragments) {
    auto& terms = tri[static_cast<std::size_t>(fr.tri)];
    if (terms.empty()) {
      const auto& idx = f.geometry.triangles[static_cast<std::size_t>(fr.tri)];
      const Vec3 n0 = f.geometry.normals[idx[0]], n1 = f.geometry.normals[idx[1]],
                 n2 = f.geometry.normals[idx[2]];
      const Vec3 pc = centroid(f, static_cast<std::size_t>(fr.tri));
      try {
        for (const Light& l : lights) {
          const Vec3 ld = Lighting::l_at(l, pc);
          terms.emplace_back(fast_phong::taylor(n0, n1, n2, ld),
                             fast_phong::taylor(n0, n1, n2, normalized(ld + f.lighting.v_at(pc))));
        }
      } catch (const Error& e) {
        throw Error(fmt::format("scene '{}', triangle {}: {}", f.scene, fr.tri, e.what()));
      }
    }
    for (std::size_t k = 0; k < lights.size(); ++k) {
      const double d = quad::eval_st(terms[k].first, fr.st);
      const double h = quad::eval_st(terms[k].second, fr.st);
      a[k] = {std::max(0.0, d), h > 0 ? std::pow(h, n4) : 0.0};
    }
    img.at(fr.x, fr.y) = to_rgb8(combine(fr, lights, a));
  }
  return img;
}

Image fence_image(const Frame& f, bool highlight_track) {
  const Fragment material = material_fragment(f);
  bool local = !f.lighting.view_at_infinity;
  for (const Light& l : f.lighting.lights) local = local || !l.at_infinity;
  // Per triangle, built when its first pixel comes (like every per-triangle set-up here): per
  // row y0.. the sample pixels and their colours, in the shared arrays xs and colours.
  struct Row {
    std::uint32_t begin = 0, count = 0;
  };
  struct Samples {
    bool done = false;
    int y0 = 0;
    std::size_t rows = 0;  // its first Row
  };
  std::vector<Samples> tri(f.geometry.triangles.size());
  std::vector<Row> rows;
  std::vector<int> xs;
  std::vector<Vec3> colours;
  std::vector<Vec3> h(f.lighting.lights.size());  // per light
  const auto build = [&](std::size_t t) {
    if (highlight_track) {
      const Vec3 pc = centroid(f, t);
      for (std::size_t k = 0; k < h.size(); ++k) h[k] = f.lighting.h_at(f.lighting.lights[k], pc);
    }
    const auto pv = quad::to_pixels(f.screen[t]);
    const std::vector<Span> spans = spans_of(f, t);
    tri[t] = {true, spans.front().y, rows.size()};
    rows.resize(rows.size() + static_cast<std::size_t>(spans.back().y - spans.front().y + 1));
    for (const Span& e : spans) {
      const auto begin = static_cast<std::uint32_t>(xs.size());
      xs.push_back(e.x0);
      if (highlight_track && e.x1 > e.x0) {
        const double per_pixel = 1.0 / (e.x1 - e.x0);
        const Vec3 dn = (e.s2.n - e.s1.n) * per_pixel;
        for (std::size_t k = 0; k < h.size(); ++k) {
          double off = highlight_track_offset(e.s1.n, dn, h[k]);
          for (int refine = 0; refine < 2 && std::isfinite(off) && local; ++refine) {
            const Vec3 p = e.s1.p + (off * per_pixel) * (e.s2.p - e.s1.p);  // affine along rows
            off = highlight_track_offset(e.s1.n, dn, f.lighting.h_at(f.lighting.lights[k], p));
          }
          if (!std::isfinite(off)) continue;
          const long x = e.x0 + std::lround(off);
          if (x > e.x0 && x < e.x1) xs.push_back(static_cast<int>(x));
        }
      }
      if (e.x1 != e.x0) xs.push_back(e.x1);
      std::sort(xs.begin() + begin, xs.end());
      xs.erase(std::unique(xs.begin() + begin, xs.end()), xs.end());
      for (std::size_t k = begin; k < xs.size(); ++k) {
        const int x = xs[k];
        const Surface sf = x == e.x0 ? e.s1 : x == e.x1 ? e.s2 : surface_at(f, t, pv, x, e.y);
        colours.push_back(clamp01(shade(f, material, normalized(sf.n), sf.p, lyon::phong)));
      }
      rows[tri[t].rows + static_cast<std::size_t>(e.y - spans.front().y)] = {
          begin, static_cast<std::uint32_t>(xs.size() - begin)};
    }
  };
  Image img = blank(f);
  for (const Fragment& fr : f.fragments) {
    const auto t = static_cast<std::size_t>(fr.tri);
    if (!tri[t].done) build(t);
    const Row& r = rows[tri[t].rows + static_cast<std::size_t>(fr.y - tri[t].y0)];
    // The last sample at or left of the pixel: its own colour there, a linear step beyond.
    std::size_t k = r.begin;
    while (k + 1 < r.begin + r.count && xs[k + 1] <= fr.x) ++k;
    Vec3 c = colours[k];
    if (fr.x > xs[k]) {
      c = c + (fr.x - xs[k]) * ((colours[k + 1] - colours[k]) * (1.0 / (xs[k + 1] - xs[k])));
    }
    img.at(fr.x, fr.y) = to_rgb8(c);
  }
  return img;
}

}  // namespace phongsim::shading
