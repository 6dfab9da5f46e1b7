// The renderer: the model and RTL backends give byte-identical images on every built-in scene,
// and the seeds' observations hold on our renders (docs/results.md).
#include <gtest/gtest.h>

#include "tests/error_of.h"

#include <cmath>

#include "model/error.h"
#include "sim/render.h"

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
}

}  // namespace
}  // namespace phongsim
