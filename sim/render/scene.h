// Scenes for the renderer: a mesh, one material, lights, a camera and an image size. The
// built-in mesh scenes reproduce the test objects of the seeds; scene files (TOML) describe
// others. The analytic "shinyballs" scene is the renderer's own (sim/render.*), not listed here.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "base/vec3.h"
#include "sim/render/mesh.h"

namespace phongsim {

struct Light {
  Vec3 position;  // at_infinity: the unit direction towards the light
  bool at_infinity = false;
  Vec3 colour{1, 1, 1};
};

struct Material {
  Vec3 ambient{0, 0, 0};
  Vec3 diffuse{0.8, 0.8, 0.8};
  Vec3 specular{1, 1, 1};
  double shininess = 32;
};

struct Camera {
  Vec3 eye{0, 0, 5};
  Vec3 target{0, 0, 0};
  Vec3 up{0, 1, 0};
  double fov_deg = 0;         // vertical field of view; 0: orthographic
  double ortho_height = 2.4;  // world units visible vertically when orthographic
};

struct Scene {
  std::string name;
  Mesh mesh;
  Material material;
  std::vector<Light> lights;
  Camera camera;
  Vec3 background{0, 0, 0};
  int width = 256, height = 256;  // default image size
};

// The built-in mesh scenes (all orthographic, camera on +z looking at the origin unless noted,
// black background, white lights):
//  kbsphere32, kbsphere512  Kuijk–Blake's photographs (seed 001): octahedron_sphere(1) and (3),
//      unit radius; one point light at distance 4 (four radii) from the centre, upper right
//      front: (4/√3)·(1, 1, 1) ≈ (2.309, 2.309, 2.309); no perspective. Grey material: ambient
//      0.1, diffuse 0.7, specular 0.8, shininess 20. 256 x 256, ortho_height 2.4.
//  triangle  Vlasic §6 (Fig. 6.1b): single_triangle(), blue (ambient (0, 0, 0.1), diffuse
//      (0.1, 0.2, 0.9), specular 1, shininess 32), point light at (0.5, 0.5, 2) in front of it.
//      Camera eye (0, 0.25, 5) looking at (0, 0.25, 0) (the triangle's bounding-box centre),
//      ortho_height 2. 256 x 256.
//  dodecahedron, sphere40  Vlasic Figs. 6.15 and 6.16: dodecahedron() (36 triangles, see
//      mesh.h) and sphere40(), unit circumradius; point light at (2, 2, 3); red material
//      (ambient 0.08, diffuse (0.8, 0.25, 0.2), specular 1, shininess 32). 256 x 256,
//      ortho_height 2.4.
//  teapot  Vlasic §6 (Fig. 6.1a): teapot(resolution) scaled into [-1, 1]³
//      (normalize_to_unit_box), white directional light from normalize(-1, 1, 1) (upper left
//      front); camera eye (0, 2, 5) looking at the origin (about 22° from above), ortho_height
//      1.8; copper-ish material (ambient 0.1, diffuse (0.8, 0.5, 0.25), specular 1,
//      shininess 32). 320 x 240.
// teapot_resolution: 0 = kTeapotDefaultResolution; ignored by the other scenes. Throws Error
// listing the known names for an unknown one.
[[nodiscard]] Scene builtin_scene(std::string_view name, int teapot_resolution = 0);
[[nodiscard]] std::vector<std::string> builtin_scene_names();

// Reads a scene file (TOML):
//   name = "..."                      optional; default: the file's stem
//   mesh = "path.obj|bpt"          relative to the scene file's directory, or
//   builtin = "teapot"                 the mesh of a built-in scene (exactly one of the two)
//   resolution = 8                     only with builtin = "teapot": its tessellation, 1..256
//   normalize = true                   normalize_to_unit_box; default true for mesh files,
//                                      false for built-in meshes (already about unit size)
//   width = 256, height = 256          1..4096 each
//   background = [r, g, b]             colours: 3 numbers in [0, 1]
//   [camera]   eye, target, up = [x, y, z]; fov = degrees in [0, 180) (0 or absent:
//              orthographic); ortho_height > 0
//   [material] ambient, diffuse, specular = [r, g, b]; shininess > 0
//   [[light]]  position = [x, y, z] or direction = [x, y, z] (towards the light; exactly one);
//              colour = [r, g, b] (default white). At least one light.
// Defaults are those of the structs above. Throws Error("<file>:<line>: <what>") on one line
// for a TOML syntax error, an unknown key, a wrong type or array length, a value out of range,
// a missing mesh or light (reported at line 1), a missing mesh file; errors inside the mesh
// file come from read_mesh and name that file.
[[nodiscard]] Scene load_scene(const std::filesystem::path& path);

}  // namespace phongsim
