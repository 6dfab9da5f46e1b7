// `phongsim render`: shades a scene with one or more methods, each through a backend — the
// float reference, the bit-accurate model or the Verilated RTL of a configuration — and
// compares the images with a reference method (Vlasic's comparison methods, eqs. 6.1-6.3).
// docs/render.md describes the scenes, methods and outputs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/output_file.h"
#include "ref/texture_maps.h"
#include "sim/cosim/frame_cycles.h"
#include "sim/cosim/rtl_args.h"
#include "sim/render/image.h"

namespace phongsim {

enum class Backend { automatic, float_ref, model, rtl };

[[nodiscard]] std::string_view backend_name(Backend b);
[[nodiscard]] Backend parse_backend(std::string_view name);  // auto|float|model|rtl; Error else

// Which terms of the lighting model every method (and the reference) renders: all, or only the
// specular one (ambient and diffuse reflectances zeroed), as Vlasic compares his methods
// (Figures 6.1c-d, Table 6.1).
enum class Terms { all, specular };
[[nodiscard]] std::string_view terms_name(Terms t);
[[nodiscard]] Terms parse_terms(std::string_view name);  // all|specular; Error else

// One shading method (a row of the comparison grid).
struct MethodInfo {
  std::string_view name;
  std::string_view description;
  std::string_view config;  // configs/<config>.toml of its hardware unit; empty: float only
  bool mesh_only = false;   // needs triangles (not the analytic shinyballs scene)
  // The pipeline of the unit `config`'s composed pipeline is built from, which --unit-config can
  // run alone (quad: shade_quad's walker; kb: one engine for shade_kb's three); empty: none.
  std::string_view alone;
};
[[nodiscard]] const std::vector<MethodInfo>& render_methods();
[[nodiscard]] const MethodInfo& find_method(std::string_view name);  // Error lists the names
// Whether method `name` can run on a unit of `pipeline` (render's --unit-config): its built-in
// configuration's pipeline, or its MethodInfo::alone.
[[nodiscard]] bool method_runs_on(std::string_view name, std::string_view pipeline);

struct RenderOptions {
  std::string scene = "shinyballs";  // a built-in scene name or a scene file (.toml)
  std::vector<std::string> methods;  // empty: the scene's default list; "all": every method the
                                     // scene can use
  Backend backend = Backend::automatic;
  int size = 0;               // shinyballs: sphere radius in pixels (default 64); meshes: width
  int teapot_resolution = 0;  // 0: default
  std::string reference;      // empty: "phong"
  bool no_build = false;      // never Verilate: fail when a plugin is missing
  int scanline = -1;          // row of the scanline plot; -1: the middle
  // A configuration file that replaces the built-in one of every unit method of its pipeline
  // (width exploration renders scenes through candidate configurations); Error when no chosen
  // method runs on a unit of that pipeline.
  std::string unit_config;
  // The user's RTL (docs/your-rtl.md, "Rendering your RTL") of the pipeline `rtl_pipeline`, top
  // `rtl_top` (empty: the built-in top's name): every unit whose configuration is of that
  // pipeline and that runs on the RTL backend runs it, with the configuration's parameters; its
  // outputs must equal the model's, output by output (Error otherwise), and its frame clocks
  // are its own. Error when no chosen method runs such a unit through RTL.
  std::string rtl_pipeline;
  RtlSources rtl;
  std::string rtl_top;
  Terms terms = Terms::all;
  // The texture methods' textures (docs/methods.md): texels per side (0: the exact texture
  // function, no sampling) and filtering.
  int texture_size = 256;
  texmap::Filter texture_filter = texmap::Filter::bilinear;
  // Each method (the reference too) is rendered this many times, in interleaved rounds; its
  // times are the medians (`phongsim bench methods`). The images are the same every round.
  int repeats = 1;
};

// The clocks of one frame on a method's hardware unit, fed as the renderer feeds it
// (docs/system.md).
struct FrameReport {
  FrameCycles cycles;  // RTL backend: measured, equal to the cycle model's; model: the model's
  std::uint64_t pixels = 0;  // frame pixels the unit shaded (a unit output is one pixel, or a
                             // pixel's one light (Lyon) or one colour channel (Kuijk-Blake))
  // Methods with one program per triangle (the quadratic walker): each triangle's own cycles.
  std::vector<std::pair<int, FrameCycles>> triangles;
  std::string config;  // the unit's configuration file
};

struct MethodResult {
  std::string method;
  Backend backend = Backend::float_ref;  // the one actually used
  Image image;
  ImageMetrics metrics;                      // against the reference image over the object's pixels
  std::vector<ImageMetrics> region_metrics;  // the same per RenderResult::regions
  double seconds = 0;      // wall-clock time of the shading pass (median over the repeats)
  double cpu_seconds = 0;  // the process's CPU time for it (median over the repeats)
  std::optional<FrameReport> frame;  // methods on a unit (model and RTL backends)
};

struct RenderResult {
  std::string scene;
  std::vector<MethodResult> results;  // in the order asked for
  MethodResult reference;             // float reference image (metrics: against itself)
  std::vector<bool> mask;             // object (non-background) pixels, row-major
  // Named parts of the object (shinyballs: each sphere's visible pixels, "n=1" ... "n=256").
  std::vector<std::pair<std::string, std::vector<bool>>> regions;
  int scanline = 0;  // default row of the scanline plot
  // What the images depend on besides scene and methods: "" or ", specular term only", and the
  // textures' size and filter when a texture method was rendered.
  std::string settings;
};

// Progress: (what, done, total) — called often; the CLI throttles its display.
using RenderProgress = std::function<void(std::string_view, std::uint64_t, std::uint64_t)>;

// Validates everything first (scene, methods, backends, configurations, plugins), then renders.
// Throws Error with one line naming the problem.
[[nodiscard]] RenderResult render(const RenderOptions& options, const RenderProgress& progress);

// Adds to `set` (base/output_file.h: the files appear together on its commit, or not at all):
// <scene>_<method>.png per method, <scene>_<method>_diff.png (eq. 6.2, against the reference),
// <scene>_scanline.csv (eq. 6.3 along the result's scanline, a column per curve), the figures
// <scene>_grid.png (labelled rows) and <scene>_scanline.png drawn by scripts/plot.py
// (sim/render/plot.h), <scene>_metrics.csv and .md; when a method walked triangles on a unit,
// <scene>_triangle_cycles.csv (each triangle's cycles against its pixels) and its plot .png.
// Returns their paths relative to the set.
std::vector<std::filesystem::path> write_render_outputs(const RenderResult& r, OutputSet& set);

// The manifest set a scene's render files belong to ("render <scene>"): rendering a scene again
// into the same directory replaces that scene's files, other scenes' stay.
[[nodiscard]] std::string render_set_name(const RenderResult& r);

// The metrics table (Markdown) printed by the CLI and written to <scene>_metrics.md.
[[nodiscard]] std::string metrics_markdown(const RenderResult& r);

}  // namespace phongsim
