#include "sim/render/render.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <map>
#include <memory>
#include <set>

#include "base/error.h"
#include "base/paths.h"
#include "model/config.h"
#include "ref/kb_float.h"
#include "ref/lyon_float.h"
#include "ref/quad_float.h"
#include "sim/render/frame.h"
#include "sim/render/scene.h"
#include "sim/render/seed_methods.h"
#include "sim/render/unit_methods.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;
using namespace shading;  // the frame and what the methods share (sim/render/frame.h)

// ---- Methods ----

enum class Kind {
  flat,
  gouraud,
  gouraud4,
  quadratic,
  pixel,
  triangle_lyon,
  kb_exact,
  kb_decompose,
  kb_one_vector,
  env_map,
  blinn_map,
  quad_blinn_map,
  fast_phong,
  fence,
  highlight_track
};

struct Method {
  MethodInfo info;
  Kind kind;
  // Per-pixel specular amount for unit N, L, V and Phong shininess n (Kind::pixel).
  SpecularFn spec = nullptr;
};

double row(lyon::Spec s, Vec3 n, Vec3 l, Vec3 v, double shin) {
  return lyon::specfuns(n, l, v, shin)[lyon::index(s)];
}

const std::vector<Method>& methods() {
  using lyon::Spec;
  static const std::vector<Method> table{
      {{"flat", "one colour per triangle: the lighting model at the centroid, face normal", "",
        true},
       Kind::flat},
      {{"gouraud",
        "lighting at the vertices, colour interpolated linearly (unit: shade_quad/linear)",
        "shade_quad/linear", true, "quad"},
       Kind::gouraud},
      {{"gouraud4", "Gouraud on the 4x-subdivided mesh (vertices and edge midpoints)", "", true},
       Kind::gouraud4},
      {{"quadratic",
        "Vlasic 4.3: lighting at vertices and edge midpoints, eq. 4.1 per pixel "
        "(unit: shade_quad/default)",
        "shade_quad/default", true, "quad"},
       Kind::quadratic},
      {{"phong", "Phong (R.L)^n, normal normalized per pixel (Figure 9 row 1)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::phong(n, l, v, s); }},
      {{"lyon-k0", "Lyon f_0((n/2)|L-R|^2) (row 2; unit: Fig. 7, g2)", "lyon/fig7_k0", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_reflect(n, l, v, s, 0); }},
      {{"lyon-k1", "Lyon f_1 (row 3; unit: Fig. 7, g2)", "lyon/fig7_k1", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_reflect(n, l, v, s, 1); }},
      {{"lyon-k2", "Lyon f_2 (row 4; unit: Fig. 7, g2)", "lyon/default", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_reflect(n, l, v, s, 2); }},
      {{"lyon-k2-tri",
        "Lyon f_2 from triangle to pixels: the walker interpolates the normal, V and L per "
        "triangle (unit: shade_lyon/default)",
        "shade_lyon/default", true},
       Kind::triangle_lyon,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_reflect(n, l, v, s, 2); }},
      {{"lyon-k3", "Lyon f_3 (unit: Fig. 7, g2)", "lyon/fig7_k3", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_reflect(n, l, v, s, 3); }},
      {{"lyon-fig8-k1", "Lyon f_1, root shininess m = round(sqrt(n)) as the unit (Fig. 8)",
        "lyon/fig8_k1", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) {
         return lyon::lyon_reflect(n, l, v, root_shininess(s) * root_shininess(s), 1);
       }},
      {{"lyon-fig8-k2", "Lyon f_2, root shininess m = round(sqrt(n)) as the unit (Fig. 8)",
        "lyon/fig8_k2", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) {
         return lyon::lyon_reflect(n, l, v, root_shininess(s) * root_shininess(s), 2);
       }},
      {{"blinn", "Blinn-Phong (H*.N)^(4n) (row 5)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::blinn(n, l, v, s); }},
      {{"halfway-unit-k2", "D = H* - N, f_2 (row 6)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return row(Spec::halfway_unit_k2, n, l, v, s); }},
      {{"halfway-proj-k2", "D = H - (H.N)N, f_2 (row 7)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_halfway(n, l, v, s, 2, 0); }},
      {{"halfway-g2-proj-k2", "D = Hg2 - (Hg2.N)N, f_2 (row 8; unit: halfway)", "lyon/halfway",
        false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_halfway(n, l, v, s, 2, 2); }},
      {{"halfway-g2-proj-k1", "as row 8 with f_1 (row 9)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return lyon::lyon_halfway(n, l, v, s, 1, 2); }},
      {{"halfway-g2-k2", "D = Hg2 - N, f_2 (row 10)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return row(Spec::halfway_g2_k2, n, l, v, s); }},
      {{"halfway-proj-k1-fig8",
        "D = H - (H.N)N, f_1, root shininess m = round(sqrt(n)) as the unit (halfway_fig8)",
        "lyon/halfway_fig8", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) {
         return lyon::lyon_halfway(n, l, v, root_shininess(s) * root_shininess(s), 1, 0);
       }},
      {{"kb-exact",
        "Kuijk-Blake eq. 1: N, L, H rotated along each span, exact angles, quadratic cos^n", "",
        true},
       Kind::kb_exact},
      {{"kb-decomp", "Kuijk-Blake eq. 2: angle decomposed into two linear angles, quadratic cos^n",
        "", true},
       Kind::kb_decompose},
      {{"kb-onevec",
        "Kuijk-Blake eq. 4: one linear angle per span, quadratic cos^n (unit: shade_kb, an "
        "engine per channel)",
        "shade_kb/default", true, "kb"},
       Kind::kb_one_vector},
      {{"env-map",
        "Vlasic 5.1: spherical environment map of the lights (eqs. 5.1-5.3), coordinates "
        "linear; diffuse Gouraud",
        "", true},
       Kind::env_map},
      {{"blinn-map",
        "Vlasic 5.2: diffuse and specular Blinn textures (eqs. 5.4-5.7), coordinates linear", "",
        true},
       Kind::blinn_map},
      {{"quad-blinn-map", "Vlasic 5.3: Blinn map, coordinates quadratic from six points", "", true},
       Kind::quad_blinn_map},
      {{"fast-phong", "Bishop-Weimer: N.L and N.H by 2nd-order Taylor expansion about the centroid",
        "", true},
       Kind::fast_phong},
      {{"fence", "Lai-Tai: Phong at each span's end pixels, intensity linear between", "", true},
       Kind::fence},
      {{"highlight-track",
        "Lai-Tai: Fence plus Phong on each light's highlight track, piecewise linear", "", true},
       Kind::highlight_track},
      {{"torrance-sparrow", "exp(-(4n/2) acos(H*.N)^2), Blinn's D2 (row 11)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return row(Spec::torrance_sparrow, n, l, v, s); }},
      {{"trowbridge-reitz", "(1/(1 + (1 - (H*.N)^2) n))^2, Blinn's D3 (row 12)", "", false},
       Kind::pixel,
       [](Vec3 n, Vec3 l, Vec3 v, double s) { return row(Spec::trowbridge_reitz, n, l, v, s); }},
  };
  return table;
}

const Method& method(std::string_view name) {
  for (const Method& m : methods()) {
    if (m.info.name == name) return m;
  }
  std::string known;
  for (const Method& m : methods())
    known += fmt::format("{}{}", known.empty() ? "" : ", ", m.info.name);
  throw Error(fmt::format("unknown method '{}' (known: {})", name, known));
}

const Method& phong() {
  static const Method& m = method("phong");
  return m;
}

// Figure 9's twelve rows.
const std::vector<std::string> kShinyballsMethods{"phong",
                                                  "lyon-k0",
                                                  "lyon-k1",
                                                  "lyon-k2",
                                                  "blinn",
                                                  "halfway-unit-k2",
                                                  "halfway-proj-k2",
                                                  "halfway-g2-proj-k2",
                                                  "halfway-g2-proj-k1",
                                                  "halfway-g2-k2",
                                                  "torrance-sparrow",
                                                  "trowbridge-reitz"};
const std::vector<std::string> kMeshMethods{"flat",  "gouraud", "gouraud4", "quadratic",
                                            "phong", "blinn",   "lyon-k2"};

// Method m's lighting in float (the vertex methods light by Phong).
Vec3 shade_float(const Method& m, const Frame& f, const Fragment& fr, Vec3 n, Vec3 p) {
  return shade(f, fr, n, p, m.spec != nullptr ? m.spec : lyon::phong);
}

// Per-pixel methods in float.
Image pixel_float(const Method& m, const Frame& f) {
  Image img = blank(f);
  for (const Fragment& fr : f.fragments) {
    img.at(fr.x, fr.y) = to_rgb8(shade_float(m, f, fr, normalized(fr.n), fr.p));
  }
  return img;
}

// Vertex methods (flat, Gouraud, subdivided Gouraud, quadratic) in float.
// Each lighting evaluation is done once: flat per triangle, Gouraud per mesh vertex (shared
// by its triangles, as a renderer lights vertices), the others per triangle's six samples.
Image vertex_float(const Method& m, const Frame& f) {
  const Fragment material = material_fragment(f);
  std::vector<std::array<Vec3, 6>> cache(f.geometry.triangles.size());
  std::vector<bool> done(cache.size());
  std::vector<Vec3> vertex(f.geometry.positions.size());
  std::vector<bool> vertex_done(vertex.size());
  Image img = blank(f);
  for (const Fragment& fr : f.fragments) {
    const auto t = static_cast<std::size_t>(fr.tri);
    const auto& idx = f.geometry.triangles[t];
    if (m.kind == Kind::flat) {
      if (!done[t]) {
        const Vec3 a = f.geometry.positions[idx[0]], b = f.geometry.positions[idx[1]],
                   c = f.geometry.positions[idx[2]];
        const Vec3 n = normalized(cross(b - a, c - a));
        cache[t][0] = shade_float(phong(), f, material, n, (a + b + c) * (1.0 / 3));
        done[t] = true;
      }
      img.at(fr.x, fr.y) = to_rgb8(cache[t][0]);
      continue;
    }
    const double s = fr.st.s, tt = fr.st.t;
    if (m.kind == Kind::gouraud) {
      for (const int i : idx) {
        const auto k = static_cast<std::size_t>(i);
        if (vertex_done[k]) continue;
        vertex[k] = clamp01(shade_float(phong(), f, material, normalized(f.geometry.normals[k]),
                                        f.geometry.positions[k]));
        vertex_done[k] = true;
      }
      img.at(fr.x, fr.y) =
          to_rgb8((1 - s - tt) * vertex[idx[0]] + s * vertex[idx[1]] + tt * vertex[idx[2]]);
      continue;
    }
    if (!done[t]) {
      cache[t] = sample_colours(f, fr.tri);
      done[t] = true;
    }
    const auto& c = cache[t];
    Vec3 col;
    if (m.kind == Kind::gouraud4) {
      // Sub-triangles of the midpoint split, each interpolated linearly in (s, t).
      if (s >= 0.5) {
        // corner v1: vertices m01 (s=.5,t=0), v1 (1,0), m12 (.5,.5)
        const double a = 2 * (s - 0.5), b = 2 * tt;
        col = (1 - a - b) * c[1] + a * c[2] + b * c[3];
      } else if (tt >= 0.5) {  // corner v2: m20 (0,.5), m12 (.5,.5), v2 (0,1)
        const double a = 2 * s, b = 2 * (tt - 0.5);
        col = (1 - a - b) * c[5] + a * c[3] + b * c[4];
      } else if (s + tt <= 0.5) {  // corner v0: v0, m01, m20
        const double a = 2 * s, b = 2 * tt;
        col = (1 - a - b) * c[0] + a * c[1] + b * c[5];
      } else {                                       // middle: m12 (.5,.5), m20 (0,.5), m01 (.5,0)
        const double a = 1 - 2 * s, b = 1 - 2 * tt;  // weights of m20 and m01
        col = (1 - a - b) * c[3] + a * c[5] + b * c[1];
      }
    } else {  // quadratic: eq. 4.1 per channel
      quad::Samples r[3];
      for (int k = 0; k < 6; ++k) {
        for (int ch = 0; ch < 3; ++ch) r[ch][k] = channel(c[k], ch);
      }
      col = {quad::eval_st(quad::coefficients(r[0]), fr.st),
             quad::eval_st(quad::coefficients(r[1]), fr.st),
             quad::eval_st(quad::coefficients(r[2]), fr.st)};
    }
    img.at(fr.x, fr.y) = to_rgb8(col);
  }
  return img;
}

// ---- Kuijk-Blake angular interpolation (seed 001, section 1.2) ----
// Per span: N, the light direction L and the halfway vector H = (L + V)/|L + V| at the two end
// pixels' centres; along the span N, L, H rotate at constant rates (t = 0 .. 1) (frame.h:
// kb_light_ends, kb_ab).

// One light's diffuse (N, L) and specular (N, H) amounts along a span by the method's variant,
// with the per-span work (the decompositions, the one-vector angles) done once.
class KbLightTerms {
 public:
  KbLightTerms(Kind kind, const Span& e, const KbLightEnds& le, double shininess)
      : kind_(kind),
        n1_(e.n1),
        n2_(e.n2),
        le_(le),
        ab1_(kb_ab(1)),
        abn_(kb_ab(4 * shininess)),
        n4_(4 * shininess) {
    if (kind == Kind::kb_decompose) {
      diff_d_ = kb::decompose(n1_, n2_, le.l1, le.l2);
      spec_d_ = kb::decompose(n1_, n2_, le.h1, le.h2);
    } else if (kind == Kind::kb_one_vector) {
      diff_a_ = kb::one_vector(n1_, n2_, le.l1, le.l2);
      spec_a_ = kb::one_vector(n1_, n2_, le.h1, le.h2);
    }
  }

  [[nodiscard]] Amounts at(double t) const {
    switch (kind_) {
      case Kind::kb_exact:
        return {exact(le_.l1, le_.l2, ab1_, t), exact(le_.h1, le_.h2, abn_, t)};
      case Kind::kb_decompose:
        return {decomposed(diff_d_, ab1_, t), decomposed(spec_d_, abn_, t)};
      default:
        return {one(diff_a_, ab1_, 1, t), one(spec_a_, abn_, n4_, t)};
    }
  }

 private:
  [[nodiscard]] double exact(Vec3 v1, Vec3 v2, const kb::QuadParams& ab, double t) const {
    return kb::quad(std::acos(std::clamp(kb::cos_exact(n1_, n2_, v1, v2, t), -1.0, 1.0)), ab);
  }
  static double decomposed(const kb::Decomposition& d, const kb::QuadParams& ab, double t) {
    return kb::quad(d.n.theta0 + t * d.n.dtheta, ab) * kb::quad(d.l.theta0 + t * d.l.dtheta, ab);
  }
  static double one(const kb::ScanlineAngles& a, const kb::QuadParams& ab, double n, double t) {
    return std::pow(std::max(a.scale, 0.0), n) * kb::quad(a.theta0 + t * a.dtheta, ab);
  }

  Kind kind_;
  Vec3 n1_, n2_;
  KbLightEnds le_;
  kb::QuadParams ab1_, abn_;
  double n4_;
  kb::Decomposition diff_d_, spec_d_;
  kb::ScanlineAngles diff_a_, spec_a_;
};

// Kuijk-Blake methods in float.
Image kb_float(const Method& m, const Frame& f) {
  const std::vector<bool>& visible = f.visible;
  Image img = blank(f);
  std::vector<Amounts> a(f.lighting.lights.size());
  for (std::size_t t = 0; t < visible.size(); ++t) {
    if (!visible[t]) continue;
    for (const Span& e : spans_of(f, t)) {
      std::vector<KbLightTerms> terms;
      for (const Light& l : f.lighting.lights) {
        terms.emplace_back(m.kind, e, kb_light_ends(f, l, e), f.material.shininess);
      }
      for (int x = e.x0; x <= e.x1; ++x) {
        const int o = f.owner[static_cast<std::size_t>(e.y) * f.width + x];
        if (o < 0 || f.fragments[static_cast<std::size_t>(o)].tri != static_cast<int>(t)) continue;
        const double u = e.x1 == e.x0 ? 0.0 : static_cast<double>(x - e.x0) / (e.x1 - e.x0);
        for (std::size_t k = 0; k < a.size(); ++k) a[k] = terms[k].at(u);
        img.at(x, e.y) =
            to_rgb8(combine(f.fragments[static_cast<std::size_t>(o)], f.lighting.lights, a));
      }
    }
  }
  return img;
}

Backend resolve(const Method& m, Backend asked) {
  if (asked == Backend::automatic) return m.info.config.empty() ? Backend::float_ref : Backend::rtl;
  if (asked != Backend::float_ref && m.info.config.empty()) {
    throw Error(
        fmt::format("method '{}' has no hardware unit: --backend {} is not available "
                    "(use float or auto)",
                    m.info.name, backend_name(asked)));
  }
  return asked;
}

// method_runs_on (render.h).
bool runs_on(const Method& m, std::string_view pipeline) {
  const std::string own = fs::path(std::string(m.info.config)).parent_path().string();
  return !own.empty() && (pipeline == own || (!m.info.alone.empty() && pipeline == m.info.alone));
}

std::vector<bool> mask_of(const Frame& f) {
  std::vector<bool> mask(f.owner.size());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = f.owner[i] >= 0;
  return mask;
}

}  // namespace

std::string_view backend_name(Backend b) {
  switch (b) {
    case Backend::automatic:
      return "auto";
    case Backend::float_ref:
      return "float";
    case Backend::model:
      return "model";
    case Backend::rtl:
      return "rtl";
  }
  return "?";
}

Backend parse_backend(std::string_view name) {
  for (const Backend b : {Backend::automatic, Backend::float_ref, Backend::model, Backend::rtl}) {
    if (backend_name(b) == name) return b;
  }
  throw Error(fmt::format("unknown backend '{}' (known: auto, float, model, rtl)", name));
}

std::string_view terms_name(Terms t) { return t == Terms::all ? "all" : "specular"; }

Terms parse_terms(std::string_view name) {
  for (const Terms t : {Terms::all, Terms::specular}) {
    if (terms_name(t) == name) return t;
  }
  throw Error(fmt::format("unknown terms '{}' (known: all, specular)", name));
}

const std::vector<MethodInfo>& render_methods() {
  static const std::vector<MethodInfo> infos = [] {
    std::vector<MethodInfo> v;
    for (const Method& m : methods()) v.push_back(m.info);
    return v;
  }();
  return infos;
}

const MethodInfo& find_method(std::string_view name) { return method(name).info; }

bool method_runs_on(std::string_view name, std::string_view pipeline) {
  return runs_on(method(name), pipeline);
}

RenderResult render(const RenderOptions& o, const RenderProgress& progress) {
  // Validate before any work.
  const bool analytic = o.scene == kShinyballs;
  if (o.size < 0 || o.size > 2048) {
    throw Error(fmt::format("--size {} is out of range (1..2048)", o.size));
  }
  if (analytic && o.size > 340) {
    throw Error(
        fmt::format("--size {}: shinyballs is 6 radii wide, at most 340 pixels of radius "
                    "fit the 2048-pixel screen",
                    o.size));
  }
  if (o.texture_size < 0 || o.texture_size > texmap::kMaxTextureSize) {
    throw Error(fmt::format("--texture-size {} is out of range (0..{}; 0: the exact texture)",
                            o.texture_size, texmap::kMaxTextureSize));
  }
  if (o.repeats < 1 || o.repeats > 1000) {
    throw Error(fmt::format("repeats {} is out of range (1..1000)", o.repeats));
  }
  std::vector<std::string> names =
      o.methods.empty() ? (analytic ? kShinyballsMethods : kMeshMethods) : o.methods;
  if (names.size() > 1 && std::find(names.begin(), names.end(), "all") != names.end()) {
    throw Error("--method all stands for every method: give it alone");
  }
  if (names.size() == 1 && names.front() == "all") {
    // Every method the scene and the backend can use.
    names.clear();
    for (const Method& m : methods()) {
      if ((analytic && m.info.mesh_only) ||
          (o.backend != Backend::automatic && o.backend != Backend::float_ref &&
           m.info.config.empty())) {
        continue;
      }
      names.emplace_back(m.info.name);
    }
  }
  const std::string ref_name = o.reference.empty() ? "phong" : o.reference;
  const Method& ref = method(ref_name);
  std::vector<const Method*> chosen;
  std::vector<Backend> backends;
  for (const std::string& n : names) {
    const Method& m = method(n);
    if (analytic && m.info.mesh_only) {
      throw Error(
          fmt::format("method '{}' interpolates over triangles; scene '{}' has none "
                      "(use a mesh scene)",
                      n, o.scene));
    }
    chosen.push_back(&m);
    backends.push_back(resolve(m, o.backend));
  }
  if (analytic && ref.info.mesh_only) {
    throw Error(fmt::format("reference '{}' needs a mesh scene", ref_name));
  }
  // Units (loading them finds or builds the plugins before rendering starts). A method's unit
  // is its built-in configuration, or options.unit_config when the method runs on its pipeline.
  std::string override_pipeline;
  if (!o.unit_config.empty()) {
    override_pipeline = Config::load(o.unit_config).pipeline();
    // A configuration no chosen method would run is a mistake, not something to ignore.
    bool used = false;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      used = used || (backends[i] != Backend::float_ref && runs_on(*chosen[i], override_pipeline));
    }
    if (!used) {
      throw Error(fmt::format(
          "--unit-config {} is a {} configuration, but no method chosen here runs on a {} unit "
          "(through --backend model, rtl or auto)",
          o.unit_config, override_pipeline, override_pipeline));
    }
  }
  const auto unit_path = [&](const Method& m) {
    const fs::path built_in = data_root() / "configs" / (std::string(m.info.config) + ".toml");
    const bool replace = !override_pipeline.empty() && runs_on(m, override_pipeline);
    return (replace ? fs::path(o.unit_config) : built_in).string();
  };
  // Units of the user's RTL: those whose configuration is of its pipeline, through RTL.
  const auto runs_user_rtl = [&](std::size_t i) {
    return !o.rtl_pipeline.empty() && backends[i] == Backend::rtl &&
           Config::load(unit_path(*chosen[i])).pipeline() == o.rtl_pipeline;
  };
  if (!o.rtl_pipeline.empty()) {
    bool used = false;
    for (std::size_t i = 0; i < chosen.size(); ++i) used = used || runs_user_rtl(i);
    if (!used) {
      throw Error(fmt::format(
          "--rtl: no method chosen here runs on a {} unit through the RTL backend (--method "
          "names one, --backend rtl; `phongsim render --list-methods`)",
          o.rtl_pipeline));
    }
  }
  if (!o.no_build) {  // the RTL units' plugins first, in one parallel build
    std::vector<RtlUnit> rtl_units;
    std::set<std::string> seen;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      if (backends[i] != Backend::rtl || !seen.insert(unit_path(*chosen[i])).second) continue;
      rtl_units.push_back({unit_path(*chosen[i]), runs_user_rtl(i) ? &o.rtl : nullptr, o.rtl_top});
    }
    build_unit_plugins(rtl_units);
  }
  std::map<std::pair<std::string, Backend>, std::unique_ptr<Unit>> units;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    if (backends[i] == Backend::float_ref) continue;
    auto key = std::make_pair(unit_path(*chosen[i]), backends[i]);
    if (!units.contains(key)) {
      units[key] = std::make_unique<Unit>(key.first, backends[i], o.no_build,
                                          runs_user_rtl(i) ? &o.rtl : nullptr, o.rtl_top);
    }
  }
  Frame f = analytic ? shinyballs(o.size == 0 ? 64 : o.size)
                     : mesh_frame(fs::path(o.scene).extension() == ".toml"
                                      ? load_scene(o.scene)
                                      : builtin_scene(o.scene, o.teapot_resolution),
                                  o.size);
  if (o.terms == Terms::specular) {
    f.material.ambient = f.material.diffuse = {};
    for (Fragment& fr : f.fragments) fr.ka = fr.kd = {};
  }
  const TextureOptions texture{o.texture_size, o.texture_filter};

  if (o.scanline < -1 || o.scanline >= f.height) {
    throw Error(
        fmt::format("--scanline {} is outside the image (0..{})", o.scanline, f.height - 1));
  }

  const auto float_image = [&](const Method& m) {
    switch (m.kind) {
      case Kind::pixel:
      case Kind::triangle_lyon:
        return pixel_float(m, f);
      case Kind::kb_exact:
      case Kind::kb_decompose:
      case Kind::kb_one_vector:
        return kb_float(m, f);
      case Kind::env_map:
        return texture_image(TextureMethod::env_map, f, texture);
      case Kind::blinn_map:
        return texture_image(TextureMethod::blinn_map, f, texture);
      case Kind::quad_blinn_map:
        return texture_image(TextureMethod::quad_blinn_map, f, texture);
      case Kind::fast_phong:
        return fast_phong_image(f);
      case Kind::fence:
      case Kind::highlight_track:
        return fence_image(f, m.kind == Kind::highlight_track);
      default:
        return vertex_float(m, f);
    }
  };
  const auto unit_image = [&](const Method& m, Backend b, std::string_view what) {
    Unit& unit = *units.at({unit_path(m), b});
    switch (m.kind) {
      case Kind::pixel:
        return pixel_unit(f, unit, progress, what);
      case Kind::triangle_lyon:
        return triangle_lyon_unit(f, unit, progress, what);
      case Kind::kb_one_vector:
        return kb_unit(f, unit, progress, what);
      default:
        return vertex_unit(m.kind == Kind::gouraud, f, unit, progress, what);
    }
  };
  // One shading pass, timed (wall clock and the process's CPU time).
  const auto render_once = [&](const Method& m, Backend b, MethodResult& r) {
    const std::string what = fmt::format("{} [{}]", m.info.name, backend_name(b));
    progress(what, 0, f.fragments.size());
    const std::clock_t cpu = std::clock();
    const auto start = std::chrono::steady_clock::now();
    if (b == Backend::float_ref) {
      r.image = float_image(m);
    } else {
      UnitImage u = unit_image(m, b, what);
      r.image = std::move(u.image);
      r.frame = u.frame;
      r.frame->config = unit_path(m);
    }
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.cpu_seconds = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
    progress(what, f.fragments.size(), f.fragments.size());
  };

  RenderResult result;
  result.scene = f.scene;
  result.mask = mask_of(f);
  result.regions = f.regions;
  result.scanline = o.scanline < 0 ? f.height / 2 : o.scanline;
  if (o.terms == Terms::specular) result.settings = ", specular term only";
  for (const Method* m : chosen) {
    if (m->kind == Kind::env_map || m->kind == Kind::blinn_map || m->kind == Kind::quad_blinn_map) {
      result.settings += o.texture_size == 0
                             ? std::string(", exact textures")
                             : fmt::format(", textures {} x {} {}", o.texture_size, o.texture_size,
                                           texmap::filter_name(o.texture_filter));
      break;
    }
  }
  const auto is_kb = [](const Method* m) {
    return m->kind == Kind::kb_exact || m->kind == Kind::kb_decompose ||
           m->kind == Kind::kb_one_vector;
  };
  if (std::any_of(chosen.begin(), chosen.end(), is_kb)) {
    result.settings += ", Kuijk-Blake (a, b): least-squares fit per exponent";
  }
  // Round by round every method once (the reference first), so that a drift of the machine's
  // speed during the run affects all methods alike; the medians are kept.
  std::vector<const Method*> all{&ref};
  std::vector<Backend> all_backends{Backend::float_ref};
  all.insert(all.end(), chosen.begin(), chosen.end());
  all_backends.insert(all_backends.end(), backends.begin(), backends.end());
  std::vector<MethodResult> rendered(all.size());
  std::vector<std::vector<double>> wall(all.size()), cpu(all.size());
  for (int round = 0; round < o.repeats; ++round) {
    for (std::size_t i = 0; i < all.size(); ++i) {
      MethodResult& r = rendered[i];
      r.method = std::string(all[i]->info.name);
      r.backend = all_backends[i];
      render_once(*all[i], all_backends[i], r);
      wall[i].push_back(r.seconds);
      cpu[i].push_back(r.cpu_seconds);
    }
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t h = v.size() / 2;
    return v.size() % 2 == 1 ? v[h] : (v[h - 1] + v[h]) / 2;
  };
  for (std::size_t i = 0; i < all.size(); ++i) {
    rendered[i].seconds = median(wall[i]);
    rendered[i].cpu_seconds = median(cpu[i]);
  }
  result.reference = std::move(rendered.front());
  result.reference.metrics = compare(result.reference.image, result.reference.image, result.mask);
  for (std::size_t i = 1; i < rendered.size(); ++i) {
    MethodResult& r = rendered[i];
    r.metrics = compare(result.reference.image, r.image, result.mask);
    for (const auto& region : result.regions) {
      r.region_metrics.push_back(compare(result.reference.image, r.image, region.second));
    }
    result.results.push_back(std::move(r));
  }
  return result;
}

}  // namespace phongsim
