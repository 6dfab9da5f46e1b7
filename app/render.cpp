// phongsim render: shade a scene with shading methods through float, model or RTL backends, and
// write the images, difference images, a scanline plot and metrics (docs/render.md).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>

#include "app/commands.h"
#include "base/output_file.h"
#include "sim/render/render.h"

namespace phongsim::cli {
namespace {

namespace fs = std::filesystem;

struct RenderCli {
  RenderOptions options;
  std::string backend = "auto";
  std::string terms = "all";
  std::string texture_filter = "bilinear";
  std::string out_dir = "render";
  std::string json;
  bool quiet = false;
};

int run(RenderCli c) {
  c.options.backend = parse_backend(c.backend);
  c.options.terms = parse_terms(c.terms);
  c.options.texture_filter = texmap::parse_filter(c.texture_filter);
  std::optional<OutputFile> json;
  if (!c.json.empty()) json.emplace(c.json);  // unwritable: fail before rendering
  const RenderResult r = render(c.options, progress_line(c.quiet));
  const auto files = write_render_outputs(r, c.out_dir);
  fmt::print("{}: {} x {} pixels ({} object pixels), reference {} (float){}\n{}", r.scene,
             r.reference.image.width(), r.reference.image.height(), r.reference.metrics.pixels,
             r.reference.method, r.settings, metrics_markdown(r));
  fmt::print("wrote {} files to {} (grid: {})\n", files.size(), c.out_dir,
             (fs::path(c.out_dir) / (r.scene + "_grid.png")).string());
  if (json) {
    nlohmann::json j{{"scene", r.scene},
                     {"width", r.reference.image.width()},
                     {"height", r.reference.image.height()},
                     {"reference", r.reference.method},
                     {"terms", terms_name(c.options.terms)},
                     {"texture_size", c.options.texture_size},
                     {"texture_filter", texmap::filter_name(c.options.texture_filter)},
                     {"files", nlohmann::json::array()},
                     {"methods", nlohmann::json::array()}};
    for (const auto& f : files) j["files"].push_back(f.string());
    for (const MethodResult& m : r.results) {
      j["methods"].push_back(
          {{"method", m.method},
           {"backend", backend_name(m.backend)},
           {"colour_correctness", m.metrics.colour_correctness},
           {"psnr_db",
            std::isinf(m.metrics.psnr) ? nlohmann::json(nullptr) : nlohmann::json(m.metrics.psnr)},
           {"max_error", m.metrics.max_error},
           {"pixels", m.metrics.pixels},
           {"seconds", m.seconds},
           {"cpu_seconds", m.cpu_seconds}});
    }
    std::fputs((j.dump(2) + "\n").c_str(), json->get());
    json->commit();
  }
  return 0;
}

}  // namespace

void add_render(CLI::App& app, Action& action) {
  auto c = std::make_shared<RenderCli>();
  auto* cmd = app.add_subcommand(
      "render",
      "Shade a scene with shading methods through float, model or RTL backends; write "
      "images, difference images, a scanline plot and metrics");
  cmd->add_option("--scene", c->options.scene,
                  "shinyballs, kbsphere32, kbsphere512, triangle, dodecahedron, "
                  "sphere40, teapot, or a scene file (.toml)")
      ->capture_default_str();
  cmd->add_option("--method", c->options.methods,
                  "method(s), one grid row each (default: the scene's list; all: every "
                  "method the scene and backend can use; `phongsim render --list-methods`)")
      ->delimiter(',');
  cmd->add_option("--backend", c->backend,
                  "auto (RTL where a method has a unit, else float), float, model, rtl")
      ->capture_default_str();
  cmd->add_option("--size", c->options.size,
                  "shinyballs: sphere radius in pixels (default 64); meshes: image width");
  cmd->add_option("--teapot-resolution", c->options.teapot_resolution,
                  "teapot: grid cells per patch side (default: about 3750 facets)");
  cmd->add_option("--reference", c->options.reference,
                  "reference method for metrics and difference images (default phong, "
                  "float)");
  cmd->add_option("--scanline", c->options.scanline,
                  "row of the scanline illumination plot (default: the middle)");
  cmd->add_option("--unit-config", c->options.unit_config,
                  "a configuration file replacing the built-in one of every unit method "
                  "of its pipeline");
  cmd->add_option("--terms", c->terms,
                  "lighting terms: all, or specular only (Vlasic's Table 6.1 compares those)")
      ->capture_default_str();
  cmd->add_option("--texture-size", c->options.texture_size,
                  "texture methods: texels per side (0: the exact texture function)")
      ->capture_default_str();
  cmd->add_option("--texture-filter", c->texture_filter, "texture methods: nearest or bilinear")
      ->capture_default_str();
  cmd->add_option("--out", c->out_dir, "output directory")->capture_default_str();
  cmd->add_option("--json", c->json, "write a JSON summary here");
  cmd->add_flag("--no-build", c->options.no_build,
                "fail instead of Verilating a configuration that is not built yet");
  cmd->add_flag("--quiet", c->quiet, "no progress display");
  auto list_methods = std::make_shared<bool>(false);
  cmd->add_flag("--list-methods", *list_methods, "list the methods and exit");
  cmd->callback([c, list_methods, &action]() {
    action = [c, list_methods]() {
      if (*list_methods) {
        for (const MethodInfo& m : render_methods()) {
          fmt::print("  {:<22} {:<6} {}{}\n", m.name, m.config.empty() ? "float" : "unit",
                     m.description, m.mesh_only ? " [meshes only]" : "");
        }
        return 0;
      }
      return run(*c);
    };
  });
}

}  // namespace phongsim::cli
