// phongsim bench: vectors per second of one configuration (model, Verilated RTL,
// co-simulation); `bench render`: pixels per second per render backend; `bench methods`: CPU time
// per shading method (Lai and Tai's Table 1).
#include <fmt/format.h>

#include <algorithm>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/paths.h"
#include "model/plan.h"
#include "sim/cosim/bench.h"
#include "sim/cosim/icarus_dut.h"
#include "sim/render/render.h"

namespace phongsim::cli {
namespace {

// `phongsim bench render`: lyon-k2 on shinyballs through each backend, object pixels per second
// (two lights: two unit transactions per pixel) and the ratios.
int bench_render(int radius, JsonOutput& json) {
  RenderOptions o;
  o.size = static_cast<int>(quick_cap(static_cast<std::uint64_t>(radius), 16));
  radius = o.size;
  o.methods = {"lyon-k2"};
  double rate[3] = {};
  const Backend backends[] = {Backend::float_ref, Backend::model, Backend::rtl};
  std::string table;
  std::uint64_t pixels = 0;
  int width = 0, height = 0;
  for (int i = 0; i < 3; ++i) {
    o.backend = backends[i];
    const RenderResult r = render(o, progress_line());
    const MethodResult& m = r.results.front();
    pixels = m.metrics.pixels;
    width = m.image.width();
    height = m.image.height();
    rate[i] = static_cast<double>(pixels) / m.seconds;
    table += fmt::format("  {:<22} {:>12.0f}\n", backend_name(backends[i]), rate[i]);
  }
  fmt::print(json.text(),
             "bench render: shinyballs radius {} ({} x {} pixels, {} on the spheres), lyon-k2\n"
             "  {:<22} {:>12}\n{}  {:<22} {:>11.2f}x\n  {:<22} {:>11.2f}x\n",
             radius, width, height, pixels, "object pixels/s", "", table, "rtl / model",
             rate[2] / rate[1], "model / float", rate[1] / rate[0]);
  nlohmann::ordered_json j = json_document("bench");
  j["kind"] = "render";
  j["scene"] = "shinyballs";
  j["size"] = radius;
  j["width"] = width;
  j["height"] = height;
  j["object_pixels"] = pixels;
  j["method"] = "lyon-k2";
  j["object_pixels_per_s"] = {{"float", json_number(rate[0])},
                              {"model", json_number(rate[1])},
                              {"rtl", json_number(rate[2])}};
  json.write(j);
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

int bench_methods(const MethodsBench& b, JsonOutput& json) {
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
  o.repeats = static_cast<int>(quick_cap(static_cast<std::uint64_t>(b.rounds), 1));
  o.size = b.size;
  if (quick_mode()) o.size = o.size == 0 ? 96 : std::min(o.size, 96);
  o.teapot_resolution = b.teapot_resolution;
  if (quick_mode()) o.teapot_resolution = 3;
  const RenderResult r = render(o, progress_line());
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
  std::FILE* const out = json.text();
  fmt::print(out,
             "bench methods: {} ({} x {} pixels, {} object pixels), float, CPU time of the "
             "shading pass, median of {} rounds\n\n"
             "| method | CPU time (s) | Gouraud ratio | Phong ratio |\n|---|---|---|---|\n",
             r.scene, r.reference.image.width(), r.reference.image.height(),
             r.reference.metrics.pixels, o.repeats);
  nlohmann::ordered_json j = json_document("bench");
  j["kind"] = "methods";
  j["scene"] = r.scene;
  j["width"] = r.reference.image.width();
  j["height"] = r.reference.image.height();
  j["object_pixels"] = r.reference.metrics.pixels;
  j["rounds"] = o.repeats;
  j["methods"] = nlohmann::ordered_json::array();
  for (const MethodResult& m : r.results) {
    fmt::print(out, "| {} | {:.4f} | {:.4f} | {:.4f} |\n", m.method, m.cpu_seconds,
               m.cpu_seconds / gouraud, m.cpu_seconds / phong);
    j["methods"].push_back({{"method", m.method},
                            {"cpu_seconds", m.cpu_seconds},
                            {"gouraud_ratio", m.cpu_seconds / gouraud},
                            {"phong_ratio", m.cpu_seconds / phong}});
  }
  json.write(j);
  return 0;
}

struct BenchCli {
  Target target;
  std::uint64_t vectors = 200000;
  unsigned jobs = 1;
  bool no_icarus = false;
  int size = 0;  // --size (alias --radius): as render --size; bench render's default 85
  MethodsBench methods;
  std::string json;
  CLI::Option* vectors_opt = nullptr;
  CLI::Option* jobs_opt = nullptr;
  CLI::Option* no_icarus_opt = nullptr;
  CLI::Option* size_opt = nullptr;
  CLI::Option* scene_opt = nullptr;
  CLI::Option* method_opt = nullptr;
  CLI::Option* rounds_opt = nullptr;
  CLI::Option* resolution_opt = nullptr;
};

nlohmann::ordered_json rate_json(const BenchRate& r) {
  return {{"vectors_per_s", json_number(r.vectors_per_s)},
          {"outputs_per_s", json_number(r.outputs_per_s)}};
}

// The native kernel implements the default configuration's RTL parameters only.
NativeKernel native_kernel(const Loaded& l, std::string& why_not) {
  const Config default_cfg =
      Config::load(data_root() / "configs" / l.pipeline->name / "default.toml");
  if (l.pipeline->native == nullptr) {
    why_not = "no native kernel for this pipeline";
  } else if (default_cfg.rtl_parameters() != l.cfg.rtl_parameters()) {
    why_not =
        "native kernel: written for default.toml's widths and modes, not this configuration's";
  } else {
    return l.pipeline->native;
  }
  return {};
}

int run(BenchCli c) {
  const Target& t = c.target;
  const bool render_bench = t.pipeline == "render" && t.config.empty();
  const bool methods_bench = t.pipeline == "methods" && t.config.empty();
  // Options of another kind of benchmark are mistakes, not silently ignored.
  const auto refuse = [](CLI::Option* o, std::string_view where) {
    if (o != nullptr && *o) {
      throw Error(fmt::format("{} is for {}", o->get_name(), where));
    }
  };
  if (!methods_bench) {
    for (CLI::Option* o : {c.scene_opt, c.method_opt, c.rounds_opt, c.resolution_opt}) {
      refuse(o, "bench methods");
    }
  }
  if (render_bench || methods_bench) {
    refuse(c.vectors_opt, "benchmarks of a pipeline");
    refuse(c.jobs_opt, "benchmarks of a pipeline");
    refuse(c.no_icarus_opt, "benchmarks of a pipeline");
  }
  if (!render_bench && !methods_bench) refuse(c.size_opt, "bench render and bench methods");
  check_distinct({{"--json", c.json}, {"--config", t.config}});
  JsonOutput json(c.json);
  if (render_bench) return bench_render(*c.size_opt ? c.size : 85, json);
  if (methods_bench) {
    c.methods.size = c.size;
    return bench_methods(c.methods, json);
  }
  const Loaded l = load(t);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  const std::uint64_t vectors = quick_cap(c.vectors, kQuickVectors);
  std::string why_not;
  const NativeKernel native = native_kernel(l, why_not);
  std::function<DutFactory()> icarus;
  if (!c.no_icarus) icarus = [&]() { return icarus_duts(design_of(l, t), *l.model, stderr); };
  BenchReport r = bench(subject_of(l, t, stimulus), vectors, native, c.jobs, icarus,
                        quick_cap(kIcarusCycles, 1000));
  if (!why_not.empty()) r.native_note = why_not;
  const char* isa = fx::isa_name(fx::kernel_isa());
  fmt::print(json.text(), "bench {}/{}: {} random vectors each, kernels on {}\n{}",
             l.pipeline->name, l.cfg.name(), vectors, isa, r.table());
  const auto ratio = [](double a, double b) { return json_number(a / b); };
  nlohmann::ordered_json j = json_document("bench");
  j["kind"] = "pipeline";
  j["pipeline"] = l.pipeline->name;
  j["config"] = l.cfg.name();
  j["config_path"] = l.cfg.origin();
  j["vectors"] = vectors;
  j["isa"] = isa;
  j["stimulus"] = {{"vectors_per_s", json_number(r.stimulus.vectors_per_s)}};
  j["model"] = rate_json(r.model);
  j["native"] = r.native ? rate_json(*r.native) : nlohmann::ordered_json(nullptr);
  j["rtl"] = rate_json(r.rtl);
  j["rtl"]["cycles_per_s"] = json_number(r.rtl.cycles_per_s);
  j["bare_rtl"] = rate_json(r.bare_rtl);
  j["bare_rtl"]["cycles_per_s"] = json_number(r.bare_rtl.cycles_per_s);
  j["cosim"] = rate_json(r.cosim);
  j["cosim_jobs"] = nullptr;
  j["bare_rtl_jobs"] = nullptr;
  if (r.jobs > 1) {
    j["cosim_jobs"] = rate_json(r.cosim_jobs);
    j["cosim_jobs"]["jobs"] = r.jobs;
    j["bare_rtl_jobs"] = rate_json(r.bare_rtl_jobs);
    j["bare_rtl_jobs"]["cycles_per_s"] = json_number(r.bare_rtl_jobs.cycles_per_s);
    j["bare_rtl_jobs"]["jobs"] = r.jobs;
  }
  j["icarus"] = nullptr;
  if (r.icarus) {
    j["icarus"] = {{"vectors", r.icarus_vectors}};
    j["icarus"].update(rate_json(*r.icarus));
    j["icarus"]["cycles_per_s"] = json_number(r.icarus->cycles_per_s);
  }
  j["ratios"] = {
      {"model_native", r.native ? ratio(r.model.outputs_per_s, r.native->outputs_per_s)
                                : nlohmann::ordered_json(nullptr)},
      {"model_rtl", ratio(r.model.outputs_per_s, r.rtl.outputs_per_s)},
      {"rtl_bare_rtl", ratio(r.rtl.cycles_per_s, r.bare_rtl.cycles_per_s)},
      {"cosim_rtl", ratio(r.cosim.outputs_per_s, r.rtl.outputs_per_s)},
      {"cosim_ceiling_rtl", json_number(r.cosim_ceiling())},
      {"jobs_cosim", r.jobs > 1 ? ratio(r.cosim_jobs.outputs_per_s, r.cosim.outputs_per_s)
                                : nlohmann::ordered_json(nullptr)},
      {"jobs_bare_rtl",
       r.jobs > 1 ? json_number(r.bare_jobs_ratio()) : nlohmann::ordered_json(nullptr)},
      {"verilator_icarus", r.icarus ? ratio(r.rtl.cycles_per_s, r.icarus->cycles_per_s)
                                    : nlohmann::ordered_json(nullptr)}};
  json.write(j);
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
  c->vectors_opt = add_count(*cmd, "--vectors", c->vectors,
                             "a pipeline's benchmark: vectors per measurement (held in memory)",
                             kMaxBenchVectors, 1);
  c->jobs_opt =
      cmd->add_option("--jobs", c->jobs,
                      "a pipeline's benchmark: also time the co-simulation with this many workers "
                      "(cosim --jobs)")
          ->check(CLI::Range(1U, 256U).description(""))
          ->type_name("1..256")
          ->capture_default_str();
  c->no_icarus_opt = cmd->add_flag(
      "--no-icarus", c->no_icarus,
      "a pipeline's benchmark: skip the Icarus Verilog measurement (and the Verilator/Icarus "
      "ratio)");
  c->size_opt = add_int(*cmd, "--size,--radius", c->size,
                        "bench render and bench methods: as phongsim render --size — shinyballs' "
                        "sphere radius (bench render: 85, a 511-pixel-wide strip), a mesh "
                        "scene's image width (--radius: the same, its older name)",
                        1, 2048);
  c->scene_opt = cmd->add_option("--scene", c->methods.scene,
                                 "bench methods: the scene (as phongsim render --scene)")
                     ->capture_default_str();
  c->method_opt = cmd->add_option("--method", c->methods.methods,
                                  "bench methods: the methods (gouraud and phong are added if "
                                  "missing)")
                      ->delimiter(',')
                      ->capture_default_str();
  c->rounds_opt = add_int(*cmd, "--rounds", c->methods.rounds,
                          "bench methods: interleaved rounds (the median is printed)", 1, 1000)
                      ->capture_default_str();
  c->resolution_opt = add_int(*cmd, "--teapot-resolution", c->methods.teapot_resolution,
                              "bench methods: as phongsim render --teapot-resolution", 1, 256);
  cmd->add_option("--json", c->json, "write the results as JSON (docs/json.md; - is stdout)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
