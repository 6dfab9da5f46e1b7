#include "sim/render/scene.h"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <cmath>
#include <optional>

#include "base/error.h"
#include "base/file_util.h"
#include "sim/render/teapot.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

const std::vector<std::string> kNames{"kbsphere32",   "kbsphere512", "triangle",
                                      "dodecahedron", "sphere40",    "teapot"};

std::string joined_names() {
  std::string s;
  for (const auto& n : kNames) s += (s.empty() ? "" : ", ") + n;
  return s;
}

Vec3 grey(double g) { return {g, g, g}; }

Light point_light(Vec3 p) { return {p, false, {1, 1, 1}}; }

// Reads one scene file; every error names the file and a line.
class SceneParser {
 public:
  explicit SceneParser(fs::path path) : path_(std::move(path)), origin_(path_.string()) {}

  Scene parse();

 private:
  static int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }
  [[noreturn]] void fail(int line, const std::string& what) const {
    throw Error(fmt::format("{}:{}: {}", origin_, line, what));
  }
  [[noreturn]] void fail(const toml::node& n, const std::string& what) const {
    fail(line_of(n), what);
  }

  double number(const toml::node& n, const std::string& key) const {
    double v = 0;
    if (const auto* i = n.as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = n.as_floating_point()) {
      v = f->get();
    } else {
      fail(n, fmt::format("'{}' must be a number", key));
    }
    if (!std::isfinite(v)) fail(n, fmt::format("'{}' must be finite", key));
    return v;
  }

  Vec3 vec3(const toml::node& n, const std::string& key) const {
    const auto* a = n.as_array();
    if (a == nullptr || a->size() != 3) {
      fail(n, fmt::format("'{}' must be an array of 3 numbers{}", key,
                          a == nullptr ? "" : fmt::format(" (has {})", a->size())));
    }
    return {number((*a)[0], key), number((*a)[1], key), number((*a)[2], key)};
  }

  Vec3 colour(const toml::node& n, const std::string& key) const {
    const Vec3 c = vec3(n, key);
    for (const double v : {c.x, c.y, c.z}) {
      if (v < 0 || v > 1) fail(n, fmt::format("'{}' components must be in [0, 1]", key));
    }
    return c;
  }

  int integer(const toml::node& n, const std::string& key, int lo, int hi) const {
    const auto* i = n.as_integer();
    if (i == nullptr || i->get() < lo || i->get() > hi) {
      fail(n, fmt::format("'{}' must be an integer in [{}, {}]", key, lo, hi));
    }
    return static_cast<int>(i->get());
  }

  bool boolean(const toml::node& n, const std::string& key) const {
    const auto* b = n.as_boolean();
    if (b == nullptr) fail(n, fmt::format("'{}' must be true or false", key));
    return b->get();
  }

  std::string string(const toml::node& n, const std::string& key) const {
    const auto* s = n.as_string();
    if (s == nullptr || s->get().empty())
      fail(n, fmt::format("'{}' must be a non-empty string", key));
    return s->get();
  }

  const toml::table& table(const toml::node& n, const std::string& key) const {
    const auto* t = n.as_table();
    if (t == nullptr) fail(n, fmt::format("'{}' must be a table ([{}])", key, key));
    return *t;
  }

  void camera(const toml::table& t, Camera& cam) const;
  void material(const toml::table& t, Material& mat) const;
  Light light(const toml::table& t) const;

  fs::path path_;
  std::string origin_;
};

void SceneParser::camera(const toml::table& t, Camera& cam) const {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (key == "eye") {
      cam.eye = vec3(v, "eye");
    } else if (key == "target") {
      cam.target = vec3(v, "target");
    } else if (key == "up") {
      cam.up = vec3(v, "up");
    } else if (key == "fov") {
      cam.fov_deg = number(v, "fov");
      if (cam.fov_deg < 0 || cam.fov_deg >= 180) fail(v, "'fov' must be in [0, 180) degrees");
    } else if (key == "ortho_height") {
      cam.ortho_height = number(v, "ortho_height");
      if (cam.ortho_height <= 0) fail(v, "'ortho_height' must be > 0");
    } else {
      fail(v, fmt::format("[camera] unknown key '{}' (expected eye, target, up, fov, "
                          "ortho_height)",
                          key));
    }
  }
  const Vec3 view = cam.target - cam.eye;
  if (length(view) == 0) fail(t, "[camera] eye and target coincide");
  if (length(cross(view, cam.up)) <= 1e-9 * length(view) * length(cam.up)) {
    fail(t, "[camera] 'up' is zero or parallel to the viewing direction");
  }
}

void SceneParser::material(const toml::table& t, Material& mat) const {
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (key == "ambient") {
      mat.ambient = colour(v, "ambient");
    } else if (key == "diffuse") {
      mat.diffuse = colour(v, "diffuse");
    } else if (key == "specular") {
      mat.specular = colour(v, "specular");
    } else if (key == "shininess") {
      mat.shininess = number(v, "shininess");
      if (mat.shininess <= 0) fail(v, "'shininess' must be > 0");
    } else {
      fail(v, fmt::format("[material] unknown key '{}' (expected ambient, diffuse, specular, "
                          "shininess)",
                          key));
    }
  }
}

Light SceneParser::light(const toml::table& t) const {
  Light l;
  const toml::node* position = nullptr;
  const toml::node* direction = nullptr;
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (key == "position") {
      position = &v;
    } else if (key == "direction") {
      direction = &v;
    } else if (key == "colour") {
      l.colour = colour(v, "colour");
    } else {
      fail(v,
           fmt::format("[[light]] unknown key '{}' (expected position or direction, colour)", key));
    }
  }
  if (position != nullptr && direction != nullptr) {
    fail(std::max(line_of(*position), line_of(*direction)),
         "[[light]] has both 'position' and 'direction' (give exactly one)");
  }
  if (position == nullptr && direction == nullptr) {
    fail(t, "[[light]] needs 'position = [x, y, z]' or 'direction = [x, y, z]'");
  }
  if (position != nullptr) {
    l.position = vec3(*position, "position");
  } else {
    const Vec3 d = vec3(*direction, "direction");
    if (length(d) == 0) fail(*direction, "'direction' must not be zero");
    l.position = normalized(d);
    l.at_infinity = true;
  }
  return l;
}

Scene SceneParser::parse() {
  const std::string text = read_file(path_, "scene file");
  toml::table root;
  try {
    root = toml::parse(text, origin_);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}: {}", origin_, e.source().begin.line, e.description()));
  }

  Scene sc;
  sc.name = path_.stem().string();
  const toml::node* mesh = nullptr;
  const toml::node* builtin = nullptr;
  const toml::node* resolution = nullptr;
  std::optional<bool> normalize;
  bool have_lights = false;
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key == "name") {
      sc.name = string(v, "name");
    } else if (key == "mesh") {
      mesh = &v;
    } else if (key == "builtin") {
      builtin = &v;
    } else if (key == "resolution") {
      resolution = &v;
    } else if (key == "normalize") {
      normalize = boolean(v, "normalize");
    } else if (key == "width") {
      sc.width = integer(v, "width", 1, 4096);
    } else if (key == "height") {
      sc.height = integer(v, "height", 1, 4096);
    } else if (key == "background") {
      sc.background = colour(v, "background");
    } else if (key == "camera") {
      camera(table(v, "camera"), sc.camera);
    } else if (key == "material") {
      material(table(v, "material"), sc.material);
    } else if (key == "light") {
      const auto* lights = v.as_array();
      if (lights == nullptr || !lights->is_array_of_tables()) {
        fail(v, "'light' must be an array of tables ([[light]])");
      }
      for (const auto& l : *lights) sc.lights.push_back(light(*l.as_table()));
      have_lights = !sc.lights.empty();
    } else {
      fail(v, fmt::format("unknown key '{}' (expected name, mesh, builtin, resolution, normalize, "
                          "width, height, background, [camera], [material], [[light]])",
                          key));
    }
  }

  if (mesh != nullptr && builtin != nullptr) {
    fail(std::max(line_of(*mesh), line_of(*builtin)), "give either 'mesh' or 'builtin', not both");
  }
  if (mesh == nullptr && builtin == nullptr) {
    fail(1, "missing 'mesh = \"<file>\"' or 'builtin = \"<scene>\"'");
  }
  if (resolution != nullptr && (builtin == nullptr || builtin->value<std::string>() != "teapot")) {
    fail(*resolution, "'resolution' applies only to builtin = \"teapot\"");
  }
  if (!have_lights) fail(1, "no light: add at least one [[light]] with a position or direction");

  if (mesh != nullptr) {
    const fs::path file = path_.parent_path() / string(*mesh, "mesh");
    if (!fs::is_regular_file(file)) {
      fail(*mesh, fmt::format("cannot read mesh file '{}'", file.string()));
    }
    sc.mesh = read_mesh(file);
    try {
      if (normalize.value_or(true)) normalize_to_unit_box(sc.mesh);
    } catch (const Error& e) {
      throw Error(fmt::format("{}: {}", file.string(), e.what()));
    }
  } else {
    const std::string name = string(*builtin, "builtin");
    bool known = false;
    for (const auto& n : kNames) known = known || n == name;
    if (!known) {
      fail(*builtin, fmt::format("unknown built-in scene '{}' (known: {})", name, joined_names()));
    }
    const int res = resolution != nullptr ? integer(*resolution, "resolution", 1, 256) : 0;
    sc.mesh = builtin_scene(name, res).mesh;
    if (normalize.value_or(false)) normalize_to_unit_box(sc.mesh);
  }
  check(sc.mesh);
  return sc;
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return kNames; }

Scene builtin_scene(std::string_view name, int teapot_resolution) {
  if (teapot_resolution < 0 || teapot_resolution > 256) {
    throw Error(fmt::format("teapot resolution {} outside [1, 256] (0: default {})",
                            teapot_resolution, kTeapotDefaultResolution));
  }
  Scene sc;
  sc.name = std::string(name);
  if (name == "kbsphere32" || name == "kbsphere512") {
    sc.mesh = octahedron_sphere(name == "kbsphere32" ? 1 : 3);
    const double d = 4 / std::sqrt(3.0);
    sc.lights = {point_light({d, d, d})};
    sc.material = {grey(0.1), grey(0.7), grey(0.8), 20};
  } else if (name == "triangle") {
    sc.mesh = single_triangle();
    sc.lights = {point_light({0.5, 0.5, 2})};
    sc.material = {{0, 0, 0.1}, {0.1, 0.2, 0.9}, grey(1), 32};
    sc.camera.eye = {0, 0.25, 5};
    sc.camera.target = {0, 0.25, 0};
    sc.camera.ortho_height = 2;
  } else if (name == "dodecahedron" || name == "sphere40") {
    sc.mesh = name == "dodecahedron" ? dodecahedron() : sphere40();
    sc.lights = {point_light({2, 2, 3})};
    sc.material = {grey(0.08), {0.8, 0.25, 0.2}, grey(1), 32};
  } else if (name == "teapot") {
    sc.mesh = teapot(teapot_resolution);
    normalize_to_unit_box(sc.mesh);
    sc.lights = {{normalized({-1, 1, 1}), true, {1, 1, 1}}};
    sc.material = {grey(0.1), {0.8, 0.5, 0.25}, grey(1), 32};
    sc.camera.eye = {0, 2, 5};
    sc.camera.ortho_height = 1.8;
    sc.width = 320;
    sc.height = 240;
  } else {
    throw Error(fmt::format("unknown scene '{}' (built-in mesh scenes: {})", name, joined_names()));
  }
  check(sc.mesh);
  return sc;
}

Scene load_scene(const fs::path& path) { return SceneParser(path).parse(); }

}  // namespace phongsim
