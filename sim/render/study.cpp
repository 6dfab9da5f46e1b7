#include "sim/render/study.h"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <thread>

#include "base/error.h"
#include "base/rng.h"
#include "base/temporaries.h"
#include "base/vec3.h"
#include "sim/render/plot.h"
#include "sim/render/render.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

constexpr std::uint64_t kStudyStream = 0x5354554459;  // "STUDY": the scenes' random stream
// The glancing variants' lights: a stream of their own, so the scenes themselves do not change.
constexpr std::uint64_t kGlancingStream = 0x474c414e4345;  // "GLANCE"

// Triangle, dodecahedron and the 32-triangle sphere: the meshes whose normals vary a lot over a
// triangle, where the seeds make their coarse-mesh claims.
const std::vector<std::string> kMeshes{"triangle", "dodecahedron", "kbsphere32",
                                       "sphere40", "kbsphere512",  "teapot"};
bool coarse(const std::string& mesh) {
  return mesh == "triangle" || mesh == "dodecahedron" || mesh == "kbsphere32";
}

// The methods of each protocol; a claim reads their colour correctness.
const std::string kFullMethods =
    "gouraud,gouraud4,quadratic,kb-exact,kb-onevec,lyon-k0,lyon-k1,lyon-k2,fence,highlight-track,"
    "fast-phong";
const std::string kSpecularMethods = "gouraud,gouraud4,quadratic,env-map,blinn-map,quad-blinn-map";
// Lyon's Figure 9 halfway rows 6 and 10, rendered in the glancing variant of each scene. (Row 8,
// his projection, is no measure of a highlight kept there: its short D brightens glancing
// highlights far beyond Blinn's, the "feature or bug" of his section on halfway vectors.)
const std::string kGlancingMethods = "halfway-unit-k2,halfway-g2-k2";
constexpr double kOneVectorTolerance = 0.005;  // "close to exact", in colour correctness

using Scores = std::map<std::string, double, std::less<>>;  // method -> colour correctness

// A scene's three renders: full colour against Phong, specular only against Blinn, and its
// glancing variant's specular term against Blinn (empty when the scene has none).
struct Renders {
  Scores full, specular, glancing;
};

struct Judgement {
  bool applies = true;
  double difference = 0;  // > 0: the claim holds
};

struct ClaimRule {
  StudyClaim claim;
  Judgement (*judge)(const StudyScene& s, const Renders& r);
};

double at(const Scores& s, std::string_view method) { return s.find(method)->second; }

const std::vector<ClaimRule>& rules() {
  static const std::vector<ClaimRule> all{
      {{"vlasic-order",
        "Vlasic, Table 6.1: quadratic > Gouraud subdivided > Gouraud (full colour, against "
        "Phong)",
        "min(quadratic - gouraud4, gouraud4 - gouraud)"},
       [](const StudyScene&, const Renders& r) {
         const Scores& f = r.full;
         return Judgement{true, std::min(at(f, "quadratic") - at(f, "gouraud4"),
                                         at(f, "gouraud4") - at(f, "gouraud"))};
       }},
      {{"vlasic-order-specular",
        "Vlasic, Table 6.1 under his protocol: quadratic > Gouraud subdivided > Gouraud "
        "(specular only, against Blinn)",
        "min(quadratic - gouraud4, gouraud4 - gouraud)"},
       [](const StudyScene&, const Renders& r) {
         const Scores& s = r.specular;
         return Judgement{true, std::min(at(s, "quadratic") - at(s, "gouraud4"),
                                         at(s, "gouraud4") - at(s, "gouraud"))};
       }},
      {{"quad-blinn-map-best-coarse",
        "Vlasic, section 6: on coarse meshes the quadratic Blinn map beats the Blinn map, the "
        "environment map and quadratic shading (specular only, against Blinn)",
        "quad-blinn-map - max(blinn-map, env-map, quadratic)"},
       [](const StudyScene& sc, const Renders& r) {
         const Scores& s = r.specular;
         const double best = std::max({at(s, "blinn-map"), at(s, "env-map"), at(s, "quadratic")});
         return Judgement{coarse(sc.mesh), at(s, "quad-blinn-map") - best};
       }},
      {{"lyon-shape-order",
        "Lyon: more squarings approach cos^n, f_2 > f_1 > f_0, for shininess n >= 16 (full "
        "colour, against Phong)",
        "min(lyon-k2 - lyon-k1, lyon-k1 - lyon-k0)"},
       [](const StudyScene& sc, const Renders& r) {
         const Scores& f = r.full;
         return Judgement{sc.shininess >= 16, std::min(at(f, "lyon-k2") - at(f, "lyon-k1"),
                                                       at(f, "lyon-k1") - at(f, "lyon-k0"))};
       }},
      {{"kb-removes-facets",
        "Kuijk-Blake: angular interpolation beats Gouraud on coarse meshes (kb-exact, full "
        "colour, against Phong)",
        "kb-exact - gouraud"},
       [](const StudyScene& sc, const Renders& r) {
         const Scores& f = r.full;
         return Judgement{coarse(sc.mesh), at(f, "kb-exact") - at(f, "gouraud")};
       }},
      {{"kb-onevec-close",
        "Kuijk-Blake: the one-vector method stays close to exact evaluation (colour "
        "correctness within 0.005 of kb-exact)",
        "0.005 - |kb-onevec - kb-exact|"},
       [](const StudyScene&, const Renders& r) {
         const Scores& f = r.full;
         return Judgement{true,
                          kOneVectorTolerance - std::abs(at(f, "kb-onevec") - at(f, "kb-exact"))};
       }},
      {{"highlight-track-beats-fence",
        "Lai-Tai: the highlight track beats Fence and Gouraud shading (full colour, against "
        "Phong)",
        "highlight-track - max(fence, gouraud)"},
       [](const StudyScene&, const Renders& r) {
         const Scores& f = r.full;
         return Judgement{true,
                          at(f, "highlight-track") - std::max(at(f, "fence"), at(f, "gouraud"))};
       }},
      {{"lyon-row10-loses-glancing",
        "Lyon, Figure 9: for n > 4 the row-10 halfway form (D = Hg2 - N) loses the glancing "
        "highlight, scoring below row 6 (H normalized, his excellent approximation to Blinn) "
        "(glancing variant: one light behind the object, 130-160 degrees from the view; "
        "specular only, against Blinn)",
        "halfway-unit-k2 - halfway-g2-k2"},
       [](const StudyScene& sc, const Renders& r) {
         if (r.glancing.empty() || sc.shininess <= 4) return Judgement{false, 0};
         return Judgement{true,
                          at(r.glancing, "halfway-unit-k2") - at(r.glancing, "halfway-g2-k2")};
       }},
      {{"env-map-last",
        "Vlasic, section 6: under point lights the environment map comes last, below the "
        "quadratic Blinn map, the Blinn map and quadratic shading (specular only, against Blinn)",
        "min(quad-blinn-map, blinn-map, quadratic) - env-map"},
       [](const StudyScene&, const Renders& r) {
         const Scores& s = r.specular;
         return Judgement{
             true, std::min({at(s, "quad-blinn-map"), at(s, "blinn-map"), at(s, "quadratic")}) -
                       at(s, "env-map")};
       }},
      {{"fast-phong-beats-gouraud",
        "Bishop-Weimer via Lai-Tai and Vlasic: Fast Phong shading shows the highlight Gouraud "
        "shading misses, beating Gouraud (full colour, against Phong)",
        "fast-phong - gouraud"},
       [](const StudyScene&, const Renders& r) {
         const Scores& f = r.full;
         return Judgement{true, at(f, "fast-phong") - at(f, "gouraud")};
       }},
  };
  return all;
}

std::string vec(const Vec3& v) { return fmt::format("[{:.6f}, {:.6f}, {:.6f}]", v.x, v.y, v.z); }

// A random unit vector (uniform on the sphere's zone) between `inner` and `spread` radians from
// `axis`: inner 0 is the cone of half-angle `spread`.
Vec3 around(Rng& rng, const Vec3& axis, double spread, double inner = 0) {
  const Vec3 side =
      normalized(std::abs(axis.y) < 0.9 ? cross(axis, {0, 1, 0}) : cross(axis, {1, 0, 0}));
  const Vec3 other = cross(axis, side);
  const double cos_t = std::cos(inner) - rng.uniform() * (std::cos(inner) - std::cos(spread));
  const double sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
  const double phi = 2 * std::numbers::pi * rng.uniform();
  return normalized(axis * cos_t + side * (sin_t * std::cos(phi)) +
                    other * (sin_t * std::sin(phi)));
}

// Scene `index` of the study: a pure function of (seed, index). Fills `s` (its glancing
// variant's text too: the same scene lit by one light behind a closed mesh, 130 to 160 degrees
// from the view, so that its highlight lies where light and view graze the surface; none for
// the triangle, which is seen from the front) and returns the scene file's text.
std::string random_scene(std::uint64_t seed, std::uint64_t index, StudyScene& s) {
  Rng rng(seed, kStudyStream, index);
  s.index = index;
  s.mesh = kMeshes[rng.below(kMeshes.size())];
  // View: the triangle from the front within 20 degrees (its back is not lit); closed meshes
  // from any azimuth, elevation -20..60 degrees.
  Vec3 target{0, 0, 0}, view;
  double height = 2.4;
  if (s.mesh == "triangle") {
    target = {0, 0.25, 0};
    view = around(rng, {0, 0, 1}, 20 * std::numbers::pi / 180);
    height = 2;
  } else {
    const double az = 2 * std::numbers::pi * rng.uniform();
    const double el = (-20 + 80 * rng.uniform()) * std::numbers::pi / 180;
    view = {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
    if (s.mesh == "teapot") height = 2.8;  // its longest axis (2) may point up from some views
  }
  // Square images: every view fits (the teapot's own scene is 4:3).
  std::string text = fmt::format(
      "name = \"study-{}\"\nbuiltin = \"{}\"\nwidth = 256\nheight = 256\n[camera]\neye = {}\n"
      "target = {}\nup = [0, 1, 0]\northo_height = {}\n",
      index, s.mesh, vec(target + view * 5.0), vec(target), height);
  // Material over the seeds' range: a random diffuse colour, ambient a tenth of it, grey
  // specular, shininess log-uniform in [4, 128].
  const Vec3 diffuse{0.2 + 0.7 * rng.uniform(), 0.2 + 0.7 * rng.uniform(),
                     0.2 + 0.7 * rng.uniform()};
  const double specular = 0.5 + 0.5 * rng.uniform();
  s.shininess = std::round(std::exp(std::log(4.0) + rng.uniform() * std::log(32.0)));
  text += fmt::format(
      "[material]\nambient = {}\ndiffuse = {}\nspecular = [{:.6f}, {:.6f}, {:.6f}]\n"
      "shininess = {}\n",
      vec(diffuse * 0.1), vec(diffuse), specular, specular, specular, s.shininess);
  if (s.mesh != "triangle") {
    Rng glancing(seed, kGlancingStream, index);
    const double deg = std::numbers::pi / 180;
    const Vec3 dir = around(glancing, view * -1.0, 50 * deg, 20 * deg);
    s.glancing_file = fmt::format("name = \"study-{}-glancing\"{}[[light]]\nposition = {}\n", index,
                                  text.substr(text.find('\n')),
                                  vec(target + dir * (2.5 + 3.5 * glancing.uniform())));
  }
  // One or two white point lights, 2.5 to 6 from the centre, within 60 degrees of the view.
  s.lights = 1 + static_cast<int>(rng.below(2));
  for (int k = 0; k < s.lights; ++k) {
    const Vec3 dir = around(rng, view, 60 * std::numbers::pi / 180);
    text +=
        fmt::format("[[light]]\nposition = {}\n", vec(target + dir * (2.5 + 3.5 * rng.uniform())));
  }
  return text;
}

Scores scores(const fs::path& scene, const std::string& methods, Terms terms,
              const std::string& reference, int size) {
  RenderOptions o;
  o.scene = scene.string();
  o.methods = {};
  for (std::size_t at = 0; at <= methods.size();) {
    const std::size_t end = std::min(methods.find(',', at), methods.size());
    o.methods.push_back(methods.substr(at, end - at));
    at = end + 1;
  }
  o.backend = Backend::float_ref;
  o.size = size;
  o.terms = terms;
  o.reference = reference;
  const RenderResult r = render(o, [](std::string_view, std::uint64_t, std::uint64_t) {});
  Scores s;
  for (const MethodResult& m : r.results) s[m.method] = m.metrics.colour_correctness;
  return s;
}

}  // namespace

const std::vector<StudyClaim>& study_claims() {
  static const std::vector<StudyClaim> claims = [] {
    std::vector<StudyClaim> c;
    for (const ClaimRule& r : rules()) c.push_back(r.claim);
    return c;
  }();
  return claims;
}

std::pair<double, double> wilson_interval(std::uint64_t holds, std::uint64_t n) {
  if (n == 0) return {0, 1};
  constexpr double z = 1.959963984540054;  // the normal distribution's 97.5 % point
  const double p = static_cast<double>(holds) / static_cast<double>(n);
  const double nn = static_cast<double>(n);
  const double centre = (p + z * z / (2 * nn)) / (1 + z * z / nn);
  const double half = z / (1 + z * z / nn) * std::sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

StudyResult run_study(const StudyOptions& o,
                      const std::function<void(std::uint64_t, std::uint64_t)>& progress) {
  if (o.scenes < 1 || o.scenes > 100000) {
    throw Error(fmt::format("--scenes {} is out of range (1..100000)", o.scenes));
  }
  if (o.size < 16 || o.size > 2048) {
    throw Error(fmt::format("--size {} is out of range (16..2048)", o.size));
  }
  StudyResult result;
  result.scenes.resize(o.scenes);
  const unsigned jobs =
      std::clamp<unsigned>(o.jobs == 0 ? std::max(1U, std::thread::hardware_concurrency()) : o.jobs,
                           1, static_cast<unsigned>(std::min<std::uint64_t>(o.scenes, 256)));
  std::atomic<std::uint64_t> next{0}, done{0};
  std::mutex mutex;
  std::exception_ptr failure;
  const auto work = [&] {
    const TempDir dir("study");
    for (std::uint64_t i = next++; i < o.scenes; i = next++) {
      try {
        StudyScene& s = result.scenes[i];
        const fs::path file = dir.path() / fmt::format("scene{}.toml", i);
        s.file = random_scene(o.seed, i, s);
        std::ofstream(file) << s.file;
        Renders renders;
        renders.full = scores(file, kFullMethods, Terms::all, "phong", o.size);
        renders.specular = scores(file, kSpecularMethods, Terms::specular, "blinn", o.size);
        if (!s.glancing_file.empty()) {
          const fs::path glancing = dir.path() / fmt::format("scene{}-glancing.toml", i);
          std::ofstream(glancing) << s.glancing_file;
          renders.glancing = scores(glancing, kGlancingMethods, Terms::specular, "blinn", o.size);
        }
        for (const ClaimRule& r : rules()) {
          const Judgement j = r.judge(s, renders);
          s.applies.push_back(j.applies);
          s.holds.push_back(j.applies && j.difference > 0);
          s.difference.push_back(j.difference);
        }
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        next = o.scenes;
      }
      const std::lock_guard lock(mutex);
      ++done;
      if (progress) progress(done, o.scenes);
    }
  };
  std::vector<std::thread> threads;
  for (unsigned k = 1; k < jobs; ++k) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);

  for (std::size_t c = 0; c < rules().size(); ++c) {
    ClaimResult cr;
    for (const StudyScene& s : result.scenes) {
      cr.scenes += s.applies[c] ? 1 : 0;
      cr.holds += s.holds[c] ? 1 : 0;
    }
    cr.fraction = cr.scenes == 0 ? 0 : static_cast<double>(cr.holds) / cr.scenes;
    std::tie(cr.ci_low, cr.ci_high) = wilson_interval(cr.holds, cr.scenes);
    result.claims.push_back(cr);
  }
  return result;
}

std::string study_markdown(const StudyResult& r) {
  std::string t =
      "| claim | statement | scenes | holds | fraction | 95 % interval |\n"
      "|---|---|---|---|---|---|\n";
  for (std::size_t c = 0; c < r.claims.size(); ++c) {
    const StudyClaim& claim = study_claims()[c];
    const ClaimResult& cr = r.claims[c];
    t += fmt::format("| {} | {} | {} | {} | {:.3f} | {:.3f}–{:.3f} |\n", claim.name,
                     claim.statement, cr.scenes, cr.holds, cr.fraction, cr.ci_low, cr.ci_high);
  }
  return t;
}

std::vector<fs::path> write_study_outputs(const StudyResult& r, OutputSet& set) {
  std::vector<fs::path> written{"study.csv", "study.md", "study.png"};
  std::string csv = "scene,mesh,shininess,lights";
  for (const StudyClaim& c : study_claims()) csv += fmt::format(",{0}_holds,{0}_diff", c.name);
  csv += "\n";
  for (const StudyScene& s : r.scenes) {
    csv += fmt::format("{},{},{},{}", s.index, s.mesh, s.shininess, s.lights);
    for (std::size_t c = 0; c < s.applies.size(); ++c) {
      csv += s.applies[c] ? fmt::format(",{},{:.6f}", s.holds[c] ? 1 : 0, s.difference[c]) : ",,";
    }
    csv += "\n";
  }
  OutputFile& data = set.add(written[0]);
  std::fputs(csv.c_str(), data.get());
  std::fflush(data.get());
  std::fputs(study_markdown(r).c_str(), set.add(written[1]).get());
  for (const StudyScene& s : r.scenes) {
    written.push_back(fs::path("scenes") / fmt::format("scene{}.toml", s.index));
    std::fputs(s.file.c_str(), set.add(written.back()).get());
    if (s.glancing_file.empty()) continue;
    written.push_back(fs::path("scenes") / fmt::format("scene{}-glancing.toml", s.index));
    std::fputs(s.glancing_file.c_str(), set.add(written.back()).get());
  }
  plot_figure("study",
              {"--csv", data.temp_path().string(), "--title",
               fmt::format("The seeds' claims over {} random scenes: metric differences "
                           "(> 0: the claim holds)",
                           r.scenes.size())},
              set.add(written[2]));
  return written;
}

}  // namespace phongsim
