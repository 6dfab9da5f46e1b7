// Tests for scenes (sim/render/scene.*): the built-in scenes, and the scene-file loader's values
// (a scene file and the OBJ mesh it names, written here) and its one-line error messages. Meshes:
// mesh_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/vec3.h"
#include "sim/render/scene.h"
#include "tests/error_of.h"
#include "tests/mesh_helpers.h"

namespace {

namespace fs = std::filesystem;
using namespace phongsim::testing;  // tests/mesh_helpers.h, tests/error_of.h
using phongsim::Error;
using phongsim::Vec3;

// ---- Scenes ----

TEST(Scene, BuiltinScenes) {
  const std::vector<std::string> names = phongsim::builtin_scene_names();
  EXPECT_EQ(names, (std::vector<std::string>{"kbsphere32", "kbsphere512", "triangle",
                                             "dodecahedron", "sphere40", "teapot"}));
  const std::map<std::string, std::size_t> triangles{{"kbsphere32", 32}, {"kbsphere512", 512},
                                                     {"triangle", 1},    {"dodecahedron", 36},
                                                     {"sphere40", 40},   {"teapot", 4032}};
  for (const auto& name : names) {
    SCOPED_TRACE(name);
    const phongsim::Scene sc = phongsim::builtin_scene(name);
    EXPECT_EQ(sc.name, name);
    ExpectWellFormed(sc.mesh);
    EXPECT_EQ(sc.mesh.triangles.size(), triangles.at(name));
    ASSERT_EQ(sc.lights.size(), 1u);
    EXPECT_EQ(sc.camera.fov_deg, 0);  // all orthographic
    for (const Vec3& p : sc.mesh.positions) {
      EXPECT_LE(std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}), 1 + 1e-12);
    }
    // The light is in front (on the viewer's side) of the object.
    EXPECT_GT(dot(sc.lights[0].position, sc.camera.eye - sc.camera.target), 0);
  }
  // Kuijk–Blake: one point light at four radii from the unit sphere's centre.
  const auto kb = phongsim::builtin_scene("kbsphere512");
  EXPECT_FALSE(kb.lights[0].at_infinity);
  EXPECT_NEAR(length(kb.lights[0].position), 4, 1e-12);
  // Vlasic: the teapot's light is directional and white, the triangle's a point light.
  const auto tp = phongsim::builtin_scene("teapot");
  EXPECT_TRUE(tp.lights[0].at_infinity);
  EXPECT_NEAR(length(tp.lights[0].position), 1, 1e-12);
  EXPECT_EQ(tp.lights[0].colour, (Vec3{1, 1, 1}));
  EXPECT_FALSE(phongsim::builtin_scene("triangle").lights[0].at_infinity);
  EXPECT_EQ(phongsim::builtin_scene("teapot", 2).mesh.triangles.size(), 32u * 4 * 2 - 8 * 2);

  const std::string e = ErrorOf([] { (void)phongsim::builtin_scene("teapots"); });
  EXPECT_EQ(e,
            "unknown scene 'teapots' (built-in mesh scenes: kbsphere32, kbsphere512, triangle, "
            "dodecahedron, sphere40, teapot)");
}

constexpr const char* kTetraObj = R"(v 0 0 0
v 4 0 0
v 0 4 0
v 0 0 8
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 4
)";

TEST(Scene, GoodFileLoads) {
  TempDir dir;
  fs::create_directories(dir.path() / "meshes");
  dir.Write("meshes/tetra.obj", kTetraObj);
  const fs::path p = dir.Write("scene.toml", R"(# a test scene
name = "tetra"
mesh = "meshes/tetra.obj"
width = 320
height = 200
background = [0.1, 0.2, 0.3]

[camera]
eye = [1, 2, 10]
target = [0, 0.5, 0]
up = [0, 1, 0]
fov = 30
ortho_height = 3

[material]
ambient = [0.1, 0.1, 0.1]
diffuse = [0.5, 0.25, 0]
specular = [1, 1, 1]
shininess = 64.5

[[light]]
position = [3, 4, 5]

[[light]]
direction = [0, 0, -2]
colour = [0.5, 0.5, 1]
)");
  const phongsim::Scene sc = phongsim::load_scene(p);
  EXPECT_EQ(sc.name, "tetra");
  EXPECT_EQ(sc.width, 320);
  EXPECT_EQ(sc.height, 200);
  EXPECT_EQ(sc.background, (Vec3{0.1, 0.2, 0.3}));
  EXPECT_EQ(sc.camera.eye, (Vec3{1, 2, 10}));
  EXPECT_EQ(sc.camera.target, (Vec3{0, 0.5, 0}));
  EXPECT_EQ(sc.camera.up, (Vec3{0, 1, 0}));
  EXPECT_EQ(sc.camera.fov_deg, 30);
  EXPECT_EQ(sc.camera.ortho_height, 3);
  EXPECT_EQ(sc.material.ambient, (Vec3{0.1, 0.1, 0.1}));
  EXPECT_EQ(sc.material.diffuse, (Vec3{0.5, 0.25, 0}));
  EXPECT_EQ(sc.material.specular, (Vec3{1, 1, 1}));
  EXPECT_EQ(sc.material.shininess, 64.5);
  ASSERT_EQ(sc.lights.size(), 2u);
  EXPECT_EQ(sc.lights[0].position, (Vec3{3, 4, 5}));
  EXPECT_FALSE(sc.lights[0].at_infinity);
  EXPECT_EQ(sc.lights[0].colour, (Vec3{1, 1, 1}));
  EXPECT_EQ(sc.lights[1].position, (Vec3{0, 0, -1}));
  EXPECT_TRUE(sc.lights[1].at_infinity);
  EXPECT_EQ(sc.lights[1].colour, (Vec3{0.5, 0.5, 1}));
  // Normalized by default: the 4 x 4 x 8 tetrahedron's box becomes 1 x 1 x 2, centred.
  ExpectWellFormed(sc.mesh);
  ASSERT_EQ(sc.mesh.triangles.size(), 4u);
  ExpectClosed(sc.mesh);
  EXPECT_GT(SignedVolume(sc.mesh), 0);
  for (const Vec3& q : sc.mesh.positions) {
    EXPECT_TRUE(q == (Vec3{-0.5, -0.5, -1}) || q == (Vec3{0.5, -0.5, -1}) ||
                q == (Vec3{-0.5, 0.5, -1}) || q == (Vec3{-0.5, -0.5, 1}));
  }
}

TEST(Scene, DefaultsBuiltinMeshAndNoNormalize) {
  TempDir dir;
  dir.Write("tetra.obj", kTetraObj);
  const phongsim::Scene a = phongsim::load_scene(dir.Write(
      "pot.toml", "builtin = \"teapot\"\nresolution = 2\n[[light]]\nposition = [0, 0, 4]\n"));
  EXPECT_EQ(a.name, "pot");
  EXPECT_EQ(a.mesh.triangles.size(), 32u * 4 * 2 - 8 * 2);
  EXPECT_EQ(a.width, 256);
  EXPECT_EQ(a.camera.eye, (Vec3{0, 0, 5}));
  EXPECT_EQ(a.camera.fov_deg, 0);
  EXPECT_EQ(a.camera.ortho_height, 2.4);
  EXPECT_EQ(a.material.diffuse, (Vec3{0.8, 0.8, 0.8}));
  EXPECT_EQ(a.material.shininess, 32);
  const phongsim::Scene b = phongsim::load_scene(dir.Write(
      "raw.toml", "mesh = \"tetra.obj\"\nnormalize = false\n[[light]]\ndirection = [0, 3, 4]\n"));
  // Not normalized: the file's coordinates (vertex order is first use: 1, 3, 2, 4).
  EXPECT_EQ(b.mesh.positions, (std::vector<Vec3>{{0, 0, 0}, {0, 4, 0}, {4, 0, 0}, {0, 0, 8}}));
  EXPECT_NEAR(length(b.lights[0].position - Vec3{0, 0.6, 0.8}), 0, 1e-15);
  EXPECT_TRUE(b.lights[0].at_infinity);
}

TEST(Scene, BadFilesGiveOneLineErrors) {
  TempDir dir;
  dir.Write("tetra.obj", kTetraObj);
  const std::string f = (dir.path() / "bad.toml").string();
  const std::string ok_mesh = "mesh = \"tetra.obj\"\n";
  const std::string ok_light = "[[light]]\nposition = [0, 0, 4]\n";
  const auto error = [&](const std::string& text) {
    const std::string e = ErrorOf([&] { (void)phongsim::load_scene(dir.Write("bad.toml", text)); });
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    return e;
  };
  const std::vector<std::pair<std::string, std::string>> cases{
      {ok_mesh + "colour = 1\n" + ok_light,
       ":2: unknown key 'colour' (expected name, mesh, builtin, resolution, normalize, width, "
       "height, background, [camera], [material], [[light]])"},
      {ok_mesh + "width = \"big\"\n" + ok_light, ":2: 'width' must be an integer in [1, 4096]"},
      {ok_mesh + "width = 0\n" + ok_light, ":2: 'width' must be an integer in [1, 4096]"},
      {ok_mesh + "height = 4097\n" + ok_light, ":2: 'height' must be an integer in [1, 4096]"},
      {ok_mesh + "background = [1, 0]\n" + ok_light,
       ":2: 'background' must be an array of 3 numbers (has 2)"},
      {ok_mesh + "background = [1, 0, \"x\"]\n" + ok_light, ":2: 'background' must be a number"},
      {ok_mesh + "background = [1, 0, 1.5]\n" + ok_light,
       ":2: 'background' components must be in [0, 1]"},
      {"width = 10\n" + ok_light, ":1: missing 'mesh = \"<file>\"' or 'builtin = \"<scene>\"'"},
      {ok_mesh + "builtin = \"teapot\"\n" + ok_light,
       ":2: give either 'mesh' or 'builtin', not both"},
      {"builtin = \"shinyballs\"\n" + ok_light,
       ":1: unknown built-in scene 'shinyballs' (known: kbsphere32, kbsphere512, triangle, "
       "dodecahedron, sphere40, teapot)"},
      {"builtin = \"triangle\"\nresolution = 4\n" + ok_light,
       ":2: 'resolution' applies only to builtin = \"teapot\""},
      {ok_mesh, ":1: no light: add at least one [[light]] with a position or direction"},
      {ok_mesh + "[[light]]\nposition = [0, 0, 4]\ndirection = [0, 0, 1]\n",
       ":4: [[light]] has both 'position' and 'direction' (give exactly one)"},
      {ok_mesh + "[[light]]\ncolour = [1, 1, 1]\n",
       ":2: [[light]] needs 'position = [x, y, z]' or 'direction = [x, y, z]'"},
      {ok_mesh + "[[light]]\ndirection = [0, 0, 0]\n", ":3: 'direction' must not be zero"},
      {ok_mesh + "[[light]]\nposition = [0, 0, 4]\ncolor = [1, 1, 1]\n",
       ":4: [[light]] unknown key 'color' (expected position or direction, colour)"},
      {ok_mesh + "light = 3\n", ":2: 'light' must be an array of tables ([[light]])"},
      {ok_mesh + ok_light + "[material]\nshininess = 0\n", ":5: 'shininess' must be > 0"},
      {ok_mesh + ok_light + "[material]\ndiffuse = [0.5, -0.1, 0]\n",
       ":5: 'diffuse' components must be in [0, 1]"},
      {ok_mesh + ok_light + "[material]\nshiny = 3\n",
       ":5: [material] unknown key 'shiny' (expected ambient, diffuse, specular, shininess)"},
      {ok_mesh + ok_light + "[camera]\nfov = 180\n", ":5: 'fov' must be in [0, 180) degrees"},
      {ok_mesh + ok_light + "[camera]\neye = [0, 0]\n",
       ":5: 'eye' must be an array of 3 numbers (has 2)"},
      {ok_mesh + ok_light + "[camera]\northo_height = -1\n", ":5: 'ortho_height' must be > 0"},
      {ok_mesh + ok_light + "[camera]\nup = [0, 0, 1]\n",
       ":4: [camera] 'up' is zero or parallel to the viewing direction"},
      {ok_mesh + ok_light + "[camera]\neye = [0, 0, 0]\n", ":4: [camera] eye and target coincide"},
      {ok_mesh + "camera = 5\n" + ok_light, ":2: 'camera' must be a table ([camera])"},
      {ok_mesh + "normalize = 1\n" + ok_light, ":2: 'normalize' must be true or false"},
      {"name = \"\"\n" + ok_mesh + ok_light, ":1: 'name' must be a non-empty string"},
      {"mesh = \"nothere.obj\"\n" + ok_light,
       ":1: cannot read mesh file '" + (dir.path() / "nothere.obj").string() + "'"},
  };
  for (const auto& [text, expected] : cases) {
    EXPECT_EQ(error(text), f + expected) << text;
  }
  // TOML syntax errors name the line too.
  EXPECT_TRUE(StartsWith(error(ok_mesh + "width = = 3\n"), f + ":2: ")) << error("width = = 3");
  // Errors inside the mesh file name the mesh file.
  dir.Write("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
  EXPECT_EQ(error("mesh = \"broken.obj\"\n" + ok_light),
            (dir.path() / "broken.obj").string() +
                ":4: malformed 'f' statement (an index that is 0, or no number)");
  EXPECT_TRUE(StartsWith(ErrorOf([&] { (void)phongsim::load_scene(dir.path() / "absent.toml"); }),
                         (dir.path() / "absent.toml").string() + ": "));
}

}  // namespace
