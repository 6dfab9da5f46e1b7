// The renderer: the model and RTL backends give byte-identical images on every built-in scene,
// and the seeds' observations hold on our renders (docs/results.md).
#include <gtest/gtest.h>

#include "tests/error_of.h"
#include "tests/temp_dir.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "base/error.h"
#include "ref/quad_float.h"
#include "sim/render/render.h"

namespace phongsim {
namespace {

void Quiet(std::string_view, std::uint64_t, std::uint64_t) {}

RenderResult Render(const std::string& scene, std::vector<std::string> methods, Backend backend,
                    int size, int teapot_resolution = 0) {
  RenderOptions o;
  o.scene = scene;
  o.methods = std::move(methods);
  o.backend = backend;
  o.size = size;
  o.teapot_resolution = teapot_resolution;
  o.no_build = true;  // the built-in configurations are built with the project
  return render(o, Quiet);
}

// Object pixels that differ from the background: the image shows something.
int Lit(const RenderResult& r, const Image& img) {
  int n = 0;
  for (std::size_t i = 0; i < r.mask.size(); ++i) {
    if (r.mask[i] && !(img.pixels()[i] == Rgb8{0, 0, 0}) && !(img.pixels()[i] == kWhite)) ++n;
  }
  return n;
}

void ExpectModelEqualsRtl(const std::string& scene, const std::vector<std::string>& methods,
                          int size, int teapot_resolution = 0) {
  const RenderResult model = Render(scene, methods, Backend::model, size, teapot_resolution);
  const RenderResult rtl = Render(scene, methods, Backend::rtl, size, teapot_resolution);
  const RenderResult fl = Render(scene, methods, Backend::float_ref, size, teapot_resolution);
  ASSERT_EQ(model.results.size(), methods.size());
  for (std::size_t i = 0; i < methods.size(); ++i) {
    SCOPED_TRACE(scene + " " + methods[i]);
    EXPECT_EQ(model.results[i].backend, Backend::model);
    EXPECT_EQ(rtl.results[i].backend, Backend::rtl);
    EXPECT_GT(Lit(model, model.results[i].image), static_cast<int>(model.mask.size() / 20));
    EXPECT_TRUE(model.results[i].image == rtl.results[i].image);
    // The hardware is close to its own method in float.
    EXPECT_GT(compare(fl.results[i].image, model.results[i].image, model.mask).colour_correctness,
              0.99);
  }
}

TEST(RenderBackends, ShinyballsModelEqualsRtl) {
  ExpectModelEqualsRtl("shinyballs",
                       {"lyon-k0", "lyon-k1", "lyon-k2", "lyon-k3", "lyon-fig8-k1", "lyon-fig8-k2",
                        "halfway-g2-proj-k2", "halfway-proj-k1-fig8"},
                       12);
}

TEST(RenderBackends, MeshScenesModelEqualsRtl) {
  for (const char* scene : {"kbsphere32", "kbsphere512", "triangle", "dodecahedron", "sphere40"}) {
    ExpectModelEqualsRtl(scene, {"gouraud", "quadratic", "lyon-k2", "kb-onevec"}, 48);
  }
  ExpectModelEqualsRtl("teapot", {"gouraud", "quadratic", "lyon-k2", "kb-onevec"}, 64, 3);
}

// Lyon, Figure 9: f_2 approaches cos^n as n grows and beats f_1 and f_0 there; f_0 is too abrupt
// at small n (n = 4: f_0's highlight ends in a step, f_2 matches cos^4 closely).
TEST(RenderFidelity, ShinyballsShapeFunctions) {
  const RenderResult r =
      Render("shinyballs", {"lyon-k0", "lyon-k1", "lyon-k2"}, Backend::model, 32);
  ASSERT_EQ(r.regions.size(), 5u);
  const auto cc = [&](int method, int sphere) {
    return r.results[static_cast<std::size_t>(method)]
        .region_metrics[static_cast<std::size_t>(sphere)]
        .colour_correctness;
  };
  EXPECT_GT(cc(2, 4), cc(1, 4));  // n = 256: k = 2 > k = 1 > k = 0
  EXPECT_GT(cc(1, 4), cc(0, 4));
  EXPECT_GT(cc(2, 4), 0.995);
  EXPECT_LT(cc(0, 1), 0.95);  // n = 4: k = 0 too abrupt
  EXPECT_GT(cc(2, 1), 0.995);
}

// Lyon: "the halfway row 10 loses the glancing highlight" — the back light's highlight near the
// limb at the upper right of each sphere. Brightest pixel of that crescent on the n = 64 sphere.
TEST(RenderFidelity, HalfwayRow10LosesTheGlancingHighlight) {
  const int m = 32;
  const RenderResult r =
      Render("shinyballs", {"phong", "halfway-g2-k2", "lyon-k2"}, Backend::float_ref, m);
  const auto crescent_max = [&](const Image& img) {
    int best = 0;
    for (int py = 0; py < img.height(); ++py) {
      for (int px = 0; px < img.width(); ++px) {
        const double x = (0.5 + (px - m)) / m - 3;  // n = 64 sphere
        const double y = -(0.5 + (py - m)) / m;
        if (x < 0 || y < 0 || x * x + y * y > 1 || x * x + y * y < 0.7) continue;
        best = std::max(best, static_cast<int>(img.at(px, py).r));
      }
    }
    return best;
  };
  const int phong = crescent_max(r.results[0].image);
  EXPECT_GT(phong, 200);
  EXPECT_LT(crescent_max(r.results[1].image), phong / 2);
  EXPECT_GT(crescent_max(r.results[2].image), phong * 9 / 10);  // the reflect method keeps it
}

// Vlasic, Table 6.1: quadratic shading beats Gouraud on the subdivided mesh, which beats Gouraud,
// on the single triangle (a point light) and on the teapot — through the hardware unit.
TEST(RenderFidelity, VlasicTableOrdering) {
  for (const char* scene : {"triangle", "teapot"}) {
    SCOPED_TRACE(scene);
    const RenderResult r =
        Render(scene, {"gouraud", "gouraud4", "quadratic"}, Backend::automatic, 0);
    EXPECT_EQ(r.results[2].backend, Backend::rtl);
    const double g = r.results[0].metrics.colour_correctness;
    const double g4 = r.results[1].metrics.colour_correctness;
    const double q = r.results[2].metrics.colour_correctness;
    EXPECT_GT(q, g4);
    EXPECT_GT(g4, g);
  }
}

// Kuijk-Blake, Photographs 5 and 6: the cosine's diffuse term reaches zero at the terminator
// with a kink (a Mach band); the quadratic approaches zero smoothly. Along the middle row of the
// diffuse-only 512-triangle sphere: the rise over the first lit pixels after the dark side.
TEST(RenderFidelity, QuadraticDiffuseRemovesTheMachBand) {
  RenderOptions o;
  o.scene = std::string(PHONGSIM_SOURCE_DIR) + "/data/scenes/kbsphere512-diffuse.toml";
  o.methods = {"phong", "kb-onevec", "kb-exact"};
  o.no_build = true;
  const RenderResult r = render(o, Quiet);
  const auto rise = [&](const Image& img) {  // mean step over the first 4 lit pixels
    const int y = img.height() / 2;
    int x = 0;
    while (x < img.width() && img.at(x, y).r == 0) ++x;
    return (img.at(x + 3, y).r - img.at(x - 1, y).r) / 4.0;
  };
  const double cosine = rise(r.results[0].image);
  EXPECT_GT(cosine, 1.5);  // about 2 levels per pixel right at the terminator
  EXPECT_LT(rise(r.results[1].image), cosine / 3);
  EXPECT_LT(rise(r.results[2].image), cosine / 3);
}

// ---- The seeds' other methods (docs/methods.md) ----

// A 4 x 4-cell grid in the plane z = 0 seen orthographically at one pixel per unit, with every
// vertex, edge midpoint and triangle centroid on a pixel centre (cells of 12 pixels): pixel
// (8 + 12i, 8 + 12j) is vertex (i, j). Normals tilt outwards like a dome's (centre 30 units
// behind), so every lighting quantity varies over each triangle. Written as an OBJ and a scene
// file into the test's own directory `dir`; `light` is the scene file's [[light]] line.
constexpr int kGridCell = 12, kGridCells = 4, kGridOrigin = 8;

std::string GridScene(const std::filesystem::path& dir, const std::string& name,
                      const std::string& light) {
  std::ofstream obj(dir / "grid.obj");
  for (int j = 0; j <= kGridCells; ++j) {
    for (int i = 0; i <= kGridCells; ++i) {
      const double x = kGridOrigin + 0.5 + kGridCell * i - 32,
                   y = 32 - (kGridOrigin + 0.5 + kGridCell * j);
      const Vec3 n = normalized(Vec3{x, y, 0} - Vec3{0, 0, -30});
      obj << fmt::format("v {} {} 0\nvn {} {} {}\n", x, y, n.x, n.y, n.z);
    }
  }
  const auto at = [](int i, int j) { return j * (kGridCells + 1) + i + 1; };
  for (int j = 0; j < kGridCells; ++j) {
    for (int i = 0; i < kGridCells; ++i) {
      const int a = at(i, j), b = at(i + 1, j), c = at(i, j + 1), d = at(i + 1, j + 1);
      // Triangles (a, c, d) and (a, d, b), their corners rotated from cell to cell so that the
      // pixels on vertices belong to each corner index 0, 1, 2 of their triangles.
      for (std::array<int, 3> tri : {std::array{a, c, d}, std::array{a, d, b}}) {
        std::rotate(tri.begin(), tri.begin() + (i + 2 * j) % 3, tri.end());
        obj << fmt::format("f {0}//{0} {1}//{1} {2}//{2}\n", tri[0], tri[1], tri[2]);
      }
    }
  }
  obj.close();
  const std::filesystem::path scene = dir / (name + ".toml");
  std::ofstream(scene) << "mesh = \"grid.obj\"\nnormalize = false\nwidth = 64\nheight = 64\n"
                          "[camera]\neye = [0, 0, 100]\ntarget = [0, 0, 0]\nup = [0, 1, 0]\n"
                          "ortho_height = 64\n[material]\nambient = [0.05, 0.05, 0.05]\n"
                          "diffuse = [0.6, 0.5, 0.4]\nspecular = [1, 1, 1]\nshininess = 20\n"
                          "[[light]]\n"
                       << light << "\n";
  return scene.string();
}

RenderResult RenderWith(const std::string& scene, std::vector<std::string> methods,
                        const std::string& reference, int texture_size = 0,
                        Terms terms = Terms::all) {
  RenderOptions o;
  o.scene = scene;
  o.methods = std::move(methods);
  o.backend = Backend::float_ref;
  o.reference = reference;
  o.texture_size = texture_size;
  o.terms = terms;
  return render(o, Quiet);
}

struct Px {
  int x, y;
};

// Pixels of the grid scene: the vertices (step 12 from pixel 8), with the edge midpoints too
// (step 6), or the triangle centroids.
std::vector<Px> GridPixels(int step) {
  std::vector<Px> v;
  for (int y = kGridOrigin; y <= kGridOrigin + kGridCell * kGridCells; y += step) {
    for (int x = kGridOrigin; x <= kGridOrigin + kGridCell * kGridCells; x += step) {
      if (step == kGridCell / 2 && x % kGridCell != kGridOrigin % kGridCell &&
          y % kGridCell != kGridOrigin % kGridCell &&
          (x - kGridOrigin) % kGridCell + (y - kGridOrigin) % kGridCell != kGridCell) {
        continue;  // a cell centre, not on an edge (the diagonal runs from (i+1, j) to (i, j+1))
      }
      v.push_back({x, y});
    }
  }
  return v;
}

std::vector<Px> GridCentroids() {
  std::vector<Px> v;
  for (int j = 0; j < kGridCells; ++j) {
    for (int i = 0; i < kGridCells; ++i) {
      const int x = kGridOrigin + kGridCell * i, y = kGridOrigin + kGridCell * j;
      v.push_back({x + kGridCell / 3, y + 2 * kGridCell / 3});  // (i, j), (i, j+1), (i+1, j+1)
      v.push_back({x + 2 * kGridCell / 3, y + kGridCell / 3});  // (i, j), (i+1, j+1), (i+1, j)
    }
  }
  return v;
}

// Largest channel difference from the reference over the given pixels that show the object;
// counts them in `covered`.
int MaxErrorAt(const RenderResult& r, const Image& img, const std::vector<Px>& pixels,
               int* covered = nullptr) {
  int e = 0, n = 0;
  for (const Px& p : pixels) {
    if (!r.mask[static_cast<std::size_t>(p.y) * img.width() + p.x]) continue;
    ++n;
    const Rgb8 a = r.reference.image.at(p.x, p.y), b = img.at(p.x, p.y);
    e = std::max({e, std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
  }
  if (covered != nullptr) *covered = n;
  return e;
}

// Vlasic §6.4-6.5 and §6.3, Lai-Tai §2, Bishop-Weimer: where each method is exact. With the
// exact texture function (texture size 0) the texture methods match the per-pixel lighting of
// their model to the byte where the paper says they must: the Blinn map at the vertices, the
// quadratic Blinn map at the six samples, the environment map at the vertices when the light
// is directional (and not with a point light: the test shows the difference), Fast Phong at the
// centroids (its expansion point), Gouraud and quadratic shading at their samples.
TEST(RenderMethods, ExactWhereTheSeedsSayTheyAre) {
  const testing::TempDir dir;
  const std::string point = GridScene(dir.path(), "point", "position = [10, 15, 40]");
  const std::string directional = GridScene(dir.path(), "directional", "direction = [0.3, 0.5, 1]");
  const std::vector<Px> vertices = GridPixels(kGridCell), samples = GridPixels(kGridCell / 2),
                        centroids = GridCentroids();
  int covered = 0;
  for (const std::string& scene : {point, directional}) {
    SCOPED_TRACE(scene);
    const RenderResult blinn =
        RenderWith(scene, {"blinn-map", "quad-blinn-map", "fast-phong"}, "blinn");
    EXPECT_EQ(MaxErrorAt(blinn, blinn.results[0].image, vertices, &covered), 0);
    EXPECT_GE(covered, 16);
    EXPECT_EQ(MaxErrorAt(blinn, blinn.results[1].image, samples, &covered), 0);
    EXPECT_GE(covered, 50);
    EXPECT_EQ(MaxErrorAt(blinn, blinn.results[2].image, centroids, &covered), 0);
    EXPECT_EQ(covered, 32);
    // ... and not elsewhere: each differs from the reference somewhere.
    for (const MethodResult& m : blinn.results) EXPECT_GT(m.metrics.max_error, 2) << m.method;
    const RenderResult phong = RenderWith(scene, {"gouraud", "quadratic", "env-map"}, "phong");
    EXPECT_EQ(MaxErrorAt(phong, phong.results[0].image, vertices), 0);
    EXPECT_EQ(MaxErrorAt(phong, phong.results[1].image, samples), 0);
    if (scene == directional) {
      EXPECT_EQ(MaxErrorAt(phong, phong.results[2].image, vertices), 0);
    } else {
      // The map holds one direction per light: a point light's varies over the surface.
      EXPECT_GT(MaxErrorAt(phong, phong.results[2].image, vertices), 10);
    }
  }
  // The specular texture sampled at 1024 texels with bilinear filtering stays within a level or
  // two at the vertices.
  const RenderResult sampled = RenderWith(point, {"blinn-map"}, "blinn", 1024);
  EXPECT_LE(MaxErrorAt(sampled, sampled.results[0].image, vertices), 2);
}

// Lai-Tai §2: Fence and highlight-track shading evaluate the exact normal at the ends of every
// span (the triangle's edges). The spans here come from the quad unit's coverage rule applied
// to the grid's triangles directly.
TEST(RenderMethods, FenceIsExactAtTheSpanEnds) {
  const testing::TempDir dir;
  const std::string scene = GridScene(dir.path(), "point", "position = [10, 15, 40]");
  const RenderResult r = RenderWith(scene, {"fence", "highlight-track"}, "phong");
  std::vector<Px> ends;
  const auto v = [](int i, int j) {
    return quad::Vertex2{kGridOrigin + 0.5 + kGridCell * i, kGridOrigin + 0.5 + kGridCell * j};
  };
  for (int j = 0; j < kGridCells; ++j) {
    for (int i = 0; i < kGridCells; ++i) {
      for (const auto& tri : {quad::quantize(v(i, j), v(i, j + 1), v(i + 1, j + 1), 4),
                              quad::quantize(v(i, j), v(i + 1, j + 1), v(i + 1, j), 4)}) {
        const auto cov = quad::raster(tri, 64, 64);
        for (std::size_t k = 0; k < cov.size(); ++k) {
          if (k == 0 || cov[k].second != cov[k - 1].second)
            ends.push_back({cov[k].first, cov[k].second});
          if (k + 1 == cov.size() || cov[k + 1].second != cov[k].second)
            ends.push_back({cov[k].first, cov[k].second});
        }
      }
    }
  }
  int covered = 0;
  EXPECT_EQ(MaxErrorAt(r, r.results[0].image, ends, &covered), 0);
  EXPECT_GT(covered, 700);
  EXPECT_EQ(MaxErrorAt(r, r.results[1].image, ends), 0);
  EXPECT_GT(r.results[0].metrics.max_error, 2);  // interpolated inside
}

// The brightest pixel (eq. 6.3 illumination) and where it is.
struct Peak {
  double value = -1;
  int x = 0, y = 0;
};
Peak Brightest(const Image& img) {
  Peak p;
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      const Rgb8 c = img.at(x, y);
      const double i = (c.r + c.g + c.b) / (3.0 * 255);
      if (i > p.value) p = {i, x, y};
    }
  }
  return p;
}

// Lai-Tai §3: the highlight inside a polygon, missed by Gouraud and Fence shading, is caught by
// the highlight track (at full height: the track pixels are lit exactly). Vlasic's single
// triangle has exactly such a highlight.
TEST(RenderMethods, HighlightTrackCatchesTheHighlightInsideTheTriangle) {
  const RenderResult r =
      Render("triangle", {"gouraud", "fence", "highlight-track"}, Backend::float_ref, 0);
  const double phong = Brightest(r.reference.image).value;
  EXPECT_LT(Brightest(r.results[0].image).value, phong - 0.3);
  EXPECT_LT(Brightest(r.results[1].image).value, phong - 0.3);
  EXPECT_GT(Brightest(r.results[2].image).value, phong - 0.02);
  EXPECT_GT(r.results[2].metrics.colour_correctness,
            r.results[1].metrics.colour_correctness + 0.02);
}

// Vlasic §6.3 (Figure 6.8): the environment map cannot show a point light. Its texture is
// indexed by the reflected view vector alone, so the light is reduced to one direction: moving
// the single triangle's point light twice as far along that direction changes Phong's highlight
// but not one pixel of the map's; and the map's highlight is not where Phong's is.
TEST(RenderMethods, EnvironmentMapCannotShowAPointLight) {
  const testing::TempDir tmp;
  const std::filesystem::path& dir = tmp.path();
  // The triangle scene (sim/render/scene.h) with its light at (0.5, 0.5, 2), and twice as far from
  // the triangle's centre (0, 0.25, 0) in the same direction.
  std::vector<RenderResult> r;
  for (const char* light : {"[0.5, 0.5, 2]", "[1, 0.75, 4]"}) {
    const std::filesystem::path scene = dir / fmt::format("t{}.toml", r.size());
    std::ofstream(scene)
        << "builtin = \"triangle\"\n[camera]\neye = [0, 0.25, 5]\n"
           "target = [0, 0.25, 0]\northo_height = 2\n[material]\n"
           "ambient = [0, 0, 0.1]\ndiffuse = [0.1, 0.2, 0.9]\nspecular = [1, 1, 1]\n"
           "shininess = 32\n[[light]]\nposition = "
        << light << "\n";
    r.push_back(RenderWith(scene.string(), {"env-map"}, "phong", 256, Terms::specular));
  }
  EXPECT_TRUE(r[0].results[0].image == r[1].results[0].image);
  EXPECT_GT(compare(r[0].reference.image, r[1].reference.image, r[0].mask).max_error, 50);
  const Peak phong = Brightest(r[0].reference.image), env = Brightest(r[0].results[0].image);
  EXPECT_GT(std::hypot(env.x - phong.x, env.y - phong.y), 10);
  // The same on the built-in scene: the map's image is the farther light's.
  RenderOptions o;
  o.scene = "triangle";
  o.methods = {"env-map"};
  o.terms = Terms::specular;
  EXPECT_TRUE(render(o, Quiet).results[0].image == r[1].results[0].image);
}

// Vlasic's Table 6.1 protocol (specular components, against Phong shading with Blinn's model):
// his ranking "quadratic Blinn map > Blinn map > quadratic shading > environment map" holds on
// the single triangle, and on the teapot the texture methods keep his order (quadratic Blinn
// map > Blinn map > environment map > Gouraud).
TEST(RenderMethods, VlasicRanking) {
  RenderOptions o;
  o.methods = {"gouraud", "quadratic", "env-map", "blinn-map", "quad-blinn-map"};
  o.backend = Backend::float_ref;
  o.reference = "blinn";
  o.terms = Terms::specular;
  const auto cc = [](const RenderResult& r, std::size_t i) {
    return r.results[i].metrics.colour_correctness;
  };
  o.scene = "triangle";
  const RenderResult t = render(o, Quiet);
  EXPECT_GT(cc(t, 4), cc(t, 3));
  EXPECT_GT(cc(t, 3), cc(t, 1));
  EXPECT_GT(cc(t, 1), cc(t, 2));
  o.scene = "teapot";
  const RenderResult p = render(o, Quiet);
  EXPECT_GT(cc(p, 4), cc(p, 3));
  EXPECT_GT(cc(p, 3), cc(p, 2));
  EXPECT_GT(cc(p, 2), cc(p, 0));
}

// Texture resolution and filtering: bilinear beats nearest, and a finer texture approaches the
// exact function.
TEST(RenderMethods, TextureSamplingConverges) {
  RenderOptions o;
  o.scene = "triangle";
  o.methods = {"blinn-map", "env-map"};
  o.backend = Backend::float_ref;
  o.texture_size = 0;
  const RenderResult exact = render(o, Quiet);
  const auto cc = [&](int size, texmap::Filter filter, std::size_t method) {
    o.texture_size = size;
    o.texture_filter = filter;
    return compare(exact.results[method].image, render(o, Quiet).results[method].image, exact.mask)
        .colour_correctness;
  };
  for (std::size_t m = 0; m < 2; ++m) {
    SCOPED_TRACE(m);
    EXPECT_LT(cc(32, texmap::Filter::nearest, m), cc(32, texmap::Filter::bilinear, m));
    EXPECT_LT(cc(32, texmap::Filter::bilinear, m), cc(256, texmap::Filter::bilinear, m));
    EXPECT_GT(cc(256, texmap::Filter::bilinear, m), 0.999);
    EXPECT_LT(cc(32, texmap::Filter::nearest, m), 0.999);
  }
}

// `--method all`: every method the scene and backend can use, in the table's order.
TEST(RenderMethods, AllMethods) {
  RenderOptions o;
  o.scene = "shinyballs";
  o.size = 6;
  o.methods = {"all"};
  o.backend = Backend::float_ref;
  const RenderResult r = render(o, Quiet);
  std::size_t mesh_only = 0;
  for (const MethodInfo& m : render_methods()) mesh_only += m.mesh_only ? 1 : 0;
  EXPECT_EQ(r.results.size(), render_methods().size() - mesh_only);
  o.backend = Backend::model;
  o.no_build = true;
  for (const MethodResult& m : render(o, Quiet).results)
    EXPECT_FALSE(find_method(m.method).config.empty());
}

// --unit-config: a method runs on its built-in configuration's pipeline, and a composed
// pipeline's methods also on the unit it is built from, alone; nothing else.
TEST(RenderMethods, UnitPipelines) {
  struct Case {
    const char* method;
    const char* pipeline;
    bool runs;
  };
  for (const Case& c : std::vector<Case>{{"quadratic", "shade_quad", true},
                                         {"gouraud", "quad", true},
                                         {"kb-onevec", "shade_kb", true},
                                         {"kb-onevec", "kb", true},
                                         {"lyon-k2", "lyon", true},
                                         {"lyon-k2-tri", "shade_lyon", true},
                                         {"quadratic", "kb", false},
                                         {"kb-onevec", "quad", false},
                                         {"lyon-k2-tri", "lyon", false},
                                         {"lyon-k2", "shade_lyon", false},
                                         {"phong", "lyon", false},
                                         {"phong", "", false}}) {
    EXPECT_EQ(method_runs_on(c.method, c.pipeline), c.runs) << c.method << " on " << c.pipeline;
  }
}

TEST(RenderErrors, OneLineEach) {
  const auto error_of = [](const RenderOptions& o) {
    return testing::ErrorOf([&] { (void)render(o, Quiet); });
  };
  RenderOptions o;
  o.methods = {"gouraud"};
  EXPECT_EQ(error_of(o),
            "method 'gouraud' interpolates over triangles; scene 'shinyballs' has none (use a "
            "mesh scene)");
  o.methods = {"nonesuch"};
  EXPECT_TRUE(error_of(o).starts_with("unknown method 'nonesuch' (known: flat, gouraud,"));
  o.methods = {"phong"};
  o.backend = Backend::rtl;
  EXPECT_EQ(error_of(o),
            "method 'phong' has no hardware unit: --backend rtl is not available (use float or "
            "auto)");
  o = {};
  o.scene = "nonesuch";
  EXPECT_TRUE(error_of(o).starts_with("unknown scene 'nonesuch'")) << error_of(o);
  o = {};
  o.size = 5000;
  EXPECT_EQ(error_of(o), "--size 5000 is out of range (1..2048)");
  o = {};
  o.texture_size = -1;
  EXPECT_EQ(error_of(o), "--texture-size -1 is out of range (0..4096; 0: the exact texture)");
  o = {};
  o.repeats = 0;
  EXPECT_EQ(error_of(o), "repeats 0 is out of range (1..1000)");
  EXPECT_EQ(testing::ErrorOf([] { (void)parse_terms("diffuse"); }),
            "unknown terms 'diffuse' (known: all, specular)");
}

}  // namespace
}  // namespace phongsim
