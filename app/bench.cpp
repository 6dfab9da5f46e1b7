// phongsim bench: vectors per second of one configuration (model, Verilated RTL,
// co-simulation); `bench render`: pixels per second per render backend; `bench methods`: CPU time
// per shading method (Lai and Tai's Table 1).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <optional>

#include "app/commands.h"
#include "base/error.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "sim/cosim/bench.h"
#include "sim/render/render.h"

namespace phongsim::cli {
namespace {

// `phongsim bench render`: lyon-k2 on shinyballs through each backend, object pixels per second
// (two lights: two unit transactions per pixel) and the ratios.
int bench_render(int radius) {
  RenderOptions o;
  o.size = radius;
  o.methods = {"lyon-k2"};
  double rate[3] = {};
  const Backend backends[] = {Backend::float_ref, Backend::model, Backend::rtl};
  std::string table;
  std::uint64_t pixels = 0;
  int width = 0, height = 0;
  for (int i = 0; i < 3; ++i) {
    o.backend = backends[i];
    const RenderResult r = render(o, [](std::string_view, auto, auto) {});
    const MethodResult& m = r.results.front();
    pixels = m.metrics.pixels;
    width = m.image.width();
    height = m.image.height();
    rate[i] = static_cast<double>(pixels) / m.seconds;
    table += fmt::format("  {:<22} {:>12.0f}\n", backend_name(backends[i]), rate[i]);
  }
  fmt::print(
      "bench render: shinyballs radius {} ({} x {} pixels, {} on the spheres), lyon-k2\n"
      "  {:<22} {:>12}\n{}  {:<22} {:>11.2f}x\n  {:<22} {:>11.2f}x\n",
      radius, width, height, pixels, "object pixels/s", "", table, "rtl / model", rate[2] / rate[1],
      "model / float", rate[1] / rate[0]);
  return 0;
}

// `phongsim bench methods`: the CPU time of each method's float shading pass on one scene
// (rasterization and visibility are shared and not timed), the median of `rounds` interleaved
// rounds, and its ratios to Gouraud's and to Phong's, like Lai and Tai's Table 1 (seed 003).
struct MethodsBench {
  std::string scene = "teapot";
  std::vector<std::string> methods{"gouraud", "phong", "fast-phong", "highlight-track", "fence"};
  int rounds = 9;
  int size = 0;
  int teapot_resolution = 0;
};

int bench_methods(const MethodsBench& b) {
  if (b.rounds < 1 || b.rounds > 1000) {
    throw Error(fmt::format("--rounds {} is out of range (1..1000)", b.rounds));
  }
  RenderOptions o;
  o.scene = b.scene;
  o.methods = b.methods;
  const bool all = o.methods.size() == 1 && o.methods.front() == "all";
  for (const char* needed : {"phong", "gouraud"}) {  // the two ratios' denominators
    if (!all && std::find(o.methods.begin(), o.methods.end(), needed) == o.methods.end()) {
      o.methods.insert(o.methods.begin(), needed);
    }
  }
  o.backend = Backend::float_ref;
  o.repeats = b.rounds;
  o.size = b.size;
  o.teapot_resolution = b.teapot_resolution;
  const RenderResult r = render(o, [](std::string_view, auto, auto) {});
  const auto cpu_of = [&](std::string_view name) {
    for (const MethodResult& m : r.results) {
      if (m.method == name) return m.cpu_seconds;
    }
    return 0.0;
  };
  const double gouraud = cpu_of("gouraud"), phong = cpu_of("phong");
  if (!(gouraud > 0) || !(phong > 0)) {
    throw Error(
        "bench methods: the Gouraud or Phong pass took no measurable CPU time "
        "(use a larger --size)");
  }
  fmt::print(
      "bench methods: {} ({} x {} pixels, {} object pixels), float, CPU time of the shading "
      "pass, median of {} rounds\n\n"
      "| method | CPU time (s) | Gouraud ratio | Phong ratio |\n|---|---|---|---|\n",
      r.scene, r.reference.image.width(), r.reference.image.height(), r.reference.metrics.pixels,
      b.rounds);
  for (const MethodResult& m : r.results) {
    fmt::print("| {} | {:.4f} | {:.4f} | {:.4f} |\n", m.method, m.cpu_seconds,
               m.cpu_seconds / gouraud, m.cpu_seconds / phong);
  }
  return 0;
}

struct BenchCli {
  Target target;
  std::uint64_t vectors = 200000;
  unsigned jobs = 1;
  std::string json;
  int radius = 85;
  MethodsBench methods;
};

nlohmann::json to_json(const BenchRate& b, bool rtl) {
  nlohmann::json j{{"vectors_per_s", b.vectors_per_s}, {"outputs_per_s", b.outputs_per_s}};
  if (rtl) j["cycles_per_s"] = b.cycles_per_s;
  return j;
}

nlohmann::json to_json(const Loaded& l, const BenchReport& r) {
  nlohmann::json j{{"pipeline", l.pipeline->name},
                   {"config", l.cfg.name()},
                   {"config_path", l.cfg.origin()},
                   {"vectors", r.vectors},
                   {"model", to_json(r.model, false)},
                   {"native", r.native ? to_json(*r.native, false) : nlohmann::json()},
                   {"rtl", to_json(r.rtl, true)},
                   {"bare_rtl", to_json(r.bare_rtl, true)},
                   {"cosim", to_json(r.cosim, false)}};
  nlohmann::json ratios{{"model_rtl", r.model.outputs_per_s / r.rtl.outputs_per_s},
                        {"rtl_bare_rtl", r.rtl.cycles_per_s / r.bare_rtl.cycles_per_s},
                        {"cosim_rtl", r.cosim.outputs_per_s / r.rtl.outputs_per_s}};
  ratios["model_native"] =
      r.native ? nlohmann::json(r.model.outputs_per_s / r.native->outputs_per_s) : nlohmann::json();
  if (r.jobs > 1) {
    j["cosim_jobs"] = to_json(r.cosim_jobs, false);
    j["cosim_jobs"]["jobs"] = r.jobs;
    ratios["jobs_cosim"] = r.cosim_jobs.outputs_per_s / r.cosim.outputs_per_s;
  }
  j["ratios"] = ratios;
  return j;
}

int run(const BenchCli& c) {
  const Target& t = c.target;
  if (t.pipeline == "render" && t.config.empty()) return bench_render(c.radius);
  if (t.pipeline == "methods" && t.config.empty()) return bench_methods(c.methods);
  if (c.vectors == 0) throw Error("--vectors 0: nothing to time");
  const Loaded l = load(t);
  std::optional<OutputFile> json_file;
  if (!c.json.empty()) json_file.emplace(c.json);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  // The native kernel implements the default configuration's RTL parameters.
  const Config default_cfg =
      Config::load(data_root() / "configs" / l.pipeline->name / "default.toml");
  NativeKernel native;
  std::string why_not;
  if (l.pipeline->native == nullptr) {
    why_not = "no native kernel for this pipeline";
  } else if (default_cfg.rtl_parameters() != l.cfg.rtl_parameters()) {
    why_not =
        "native kernel: written for default.toml's widths and modes, not this configuration's";
  } else {
    native = l.pipeline->native;
  }
  BenchReport r = bench(subject_of(l, t, stimulus), c.vectors, native, c.jobs);
  if (!why_not.empty()) r.native_note = why_not;
  fmt::print("bench {}/{}: {} random vectors each\n{}", l.pipeline->name, l.cfg.name(), c.vectors,
             r.table());
  if (json_file) {
    fmt::print(json_file->get(), "{}\n", to_json(l, r).dump(2));
    json_file->commit();
  }
  return 0;
}

}  // namespace

void add_bench(CLI::App& app, Action& action) {
  auto c = std::make_shared<BenchCli>();
  auto* cmd = app.add_subcommand("bench",
                                 "Vectors per second: model, Verilated RTL, co-simulation (a "
                                 "pipeline); render: pixels per second per backend; methods: CPU "
                                 "time per shading method");
  c->target.add_options(*cmd);
  add_count(*cmd, "--vectors", c->vectors, "vectors per measurement", kMaxVectors);
  cmd->add_option("--jobs", c->jobs,
                  "also time the co-simulation with this many workers (cosim --jobs)")
      ->check(CLI::Range(1U, 256U))
      ->capture_default_str();
  cmd->add_option("--json", c->json,
                  "write the rates and ratios as JSON (model, native, rtl, bare_rtl, cosim)");
  cmd->add_option("--radius", c->radius,
                  "bench render: shinyballs sphere radius (85: a 511-pixel-wide strip)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  cmd->add_option("--scene", c->methods.scene,
                  "bench methods: the scene (as phongsim render --scene)")
      ->capture_default_str();
  cmd->add_option("--method", c->methods.methods,
                  "bench methods: the methods (gouraud and phong are added if missing)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--rounds", c->methods.rounds,
                  "bench methods: interleaved rounds (the median is printed)")
      ->capture_default_str();
  cmd->add_option("--size", c->methods.size,
                  "bench methods: image width (as phongsim render --size)");
  cmd->add_option("--teapot-resolution", c->methods.teapot_resolution,
                  "bench methods: as phongsim render --teapot-resolution");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
