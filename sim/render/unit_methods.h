// The renderer's methods that run on a hardware unit (docs/render.md, "Methods and backends"):
// a unit is one configuration's bit-accurate model or Verilated RTL, and a method feeds it one of
// three kinds of transactions — per pixel and light (the Lyon units), one program per triangle
// (the quadratic interpolator) or one program per span and channel (the Kuijk–Blake engine).
// Internal to the renderer (sim/render/render.cpp chooses the method and the backend).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/render/frame.h"
#include "sim/render/image.h"
#include "sim/render/render.h"

namespace phongsim::shading {

// Lyon's root-shininess unit (Fig. 8) takes m = round(sqrt(n)) and so shades with m^2, not n;
// the float Fig. 8 methods shade the same way.
[[nodiscard]] inline double root_shininess(double n) { return std::round(std::sqrt(n)); }

// One configuration's model or Verilated RTL (located, built on demand unless `no_build`):
// phongsim's, or the user's `rtl` with top `top` when given (RenderOptions::rtl).
class Unit {
 public:
  Unit(const std::filesystem::path& config, Backend backend, bool no_build,
       const RtlSources* rtl = nullptr, const std::string& top = {});

  [[nodiscard]] const Config& config() const { return cfg_; }
  [[nodiscard]] const PipelineModel& model() const { return *model_; }

  // Every output of `vectors` (flattened raw inputs), in order; their cycles go to frame().
  // The RTL's measured cycles must be the cycle model's (Error otherwise: a phongsim bug).
  std::vector<std::int64_t> run(const std::vector<std::int64_t>& vectors,
                                const RenderProgress& progress, std::string_view what);
  // The cycles of the last run(), and each of its vectors' own (PipelineInfo::cycles).
  [[nodiscard]] const FrameCycles& frame() const { return frame_; }
  [[nodiscard]] const std::vector<FrameCycles>& vector_cycles() const { return own_; }

 private:
  Config cfg_;
  std::unique_ptr<PipelineModel> model_;
  Backend backend_;
  std::shared_ptr<RtlLibrary> library_;
  std::string rtl_name_;  // "the RTL of <config>", or "your RTL (top T) with <config>"
  bool user_rtl_ = false;
  FrameCycles frame_;
  std::vector<FrameCycles> own_;
};

// A unit to be made through the RTL: its configuration, and the user's RTL and top (or none).
struct RtlUnit {
  std::filesystem::path config;
  const RtlSources* rtl = nullptr;
  std::string top;
};

// Verilates the plugins of `units` that are not cached yet, all in one parallel build (a line
// each on stderr), so that a render waits for its plugins once, not one after another; the Units
// then find them cached.
void build_unit_plugins(std::span<const RtlUnit> units);

// Each method's image and the frame's cycles on its unit.
struct UnitImage {
  Image image;
  FrameReport frame;
};

// Per-pixel methods through a Lyon unit: one transaction per pixel and light, with
// N0 = N1 = the interpolated normal (not normalized: the unit's g-normalization does that) and
// a = 0; V and L unit vectors; shininess n (arrangement 8: m = round(sqrt(n))).
[[nodiscard]] UnitImage pixel_unit(const Frame& f, Unit& unit, const RenderProgress& progress,
                                   std::string_view what);

// Vertex methods through the quadratic walker (shade_quad, or quad alone): one program per
// triangle with a visible pixel (`linear`, Gouraud: the plane through the vertex colours; else
// the quadratic through the six samples); the unit's pixels are kept where the triangle is the
// visible surface.
[[nodiscard]] UnitImage vertex_unit(bool linear, const Frame& f, Unit& unit,
                                    const RenderProgress& progress, std::string_view what);

// Per-pixel Lyon through the triangle-in, pixels-out pipeline (shade_lyon): one program per
// triangle with a visible pixel and light, the vertex normals interpolated by the walker, V, L
// and the shininess of the triangle's centroid (exact for lights and viewer at infinity); the
// pipeline's pixels are kept where the triangle is the visible surface.
[[nodiscard]] UnitImage triangle_lyon_unit(const Frame& f, Unit& unit,
                                           const RenderProgress& progress, std::string_view what);

// The one-vector method (Kuijk–Blake eq. 4) through the Kuijk–Blake engines (shade_kb: one per
// channel; kb: one engine, the channels in turn): per span and colour channel one program whose
// terms are the ambient (a constant: angle 0, rate 0), and per light the diffuse and the specular
// one-vector terms scaled by the light's and the material's colour.
[[nodiscard]] UnitImage kb_unit(const Frame& f, Unit& unit, const RenderProgress& progress,
                                std::string_view what);

}  // namespace phongsim::shading
