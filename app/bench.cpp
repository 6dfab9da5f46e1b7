// phongsim bench: vectors per second of one configuration (model, Verilated RTL,
// co-simulation); `bench render`: pixels per second per render backend; `bench methods`: CPU time
// per shading method (Lai and Tai's Table 1).
#include <fmt/format.h>

#include <algorithm>

#include "app/commands.h"
#include "base/error.h"
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
  int radius = 85;
  MethodsBench methods;
};

int run(const BenchCli& c) {
  const Target& t = c.target;
  if (t.pipeline == "render" && t.config.empty()) return bench_render(c.radius);
  if (t.pipeline == "methods" && t.config.empty()) return bench_methods(c.methods);
  if (c.vectors == 0) throw Error("--vectors 0: nothing to time");
  const Loaded l = load(t);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  const BenchReport r = bench(subject_of(l, t, stimulus), c.vectors);
  fmt::print("bench {}/{}: {} random vectors each\n{}", l.pipeline->name, l.cfg.name(), c.vectors,
             r.table());
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
