// phongsim command line: co-simulation, golden-vector evaluation, RTL builds, benchmarks.
// Exit status: 0 success; 1 verification failure (mismatch, deadlock, handshake violation);
// 2 bad input or usage (one line on stderr, no output files written).
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "base/error.h"
#include "base/file_util.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "model/config.h"
#include "model/kb_setup.h"
#include "model/lyon.h"
#include "model/quad_setup.h"
#include "ref/lyon_float.h"
#include "sim/cosim/bench.h"
#include "sim/cosim/cosim.h"
#include "sim/cosim/eval.h"
#include "sim/cosim/rtl_library.h"
#include "sim/explore/sweep.h"
#include "sim/pipelines/kb_analysis.h"
#include "sim/pipelines/lyon_analysis.h"
#include "sim/pipelines/quad_analysis.h"
#include "sim/pipelines/quad_stimulus.h"
#include "sim/pipelines/registry.h"
#include "sim/render/render.h"

namespace {

using namespace phongsim;
namespace fs = std::filesystem;

// --pipeline / --config, shared by every subcommand that works on one configuration.
struct Target {
  std::string pipeline;
  std::string config;
  bool no_build = false;
  std::string plugin;  // a plugin built by hand (e.g. from mutated RTL) instead of the lookup

  void add_options(CLI::App& cmd, bool with_build_option = true) {
    cmd.add_option("pipeline,--pipeline", pipeline,
                   "pipeline name (default: the configuration's `pipeline` key)");
    cmd.add_option("--config", config,
                   "configuration file (default: configs/<pipeline>/default.toml)");
    if (with_build_option) {
      cmd.add_flag("--no-build", no_build,
                   "fail instead of Verilating a configuration that is not built yet");
      cmd.add_option(
          "--rtl-plugin", plugin,
          "use this RTL plugin (.so from sim/cosim/rtl_build) instead of looking one up; "
          "it must have been built with the configuration's parameters");
    }
  }
};

struct Loaded {
  Config cfg;
  const PipelineInfo* pipeline = nullptr;
  std::unique_ptr<PipelineModel> model;
};

Loaded load(const Target& t) {
  if (t.config.empty() && t.pipeline.empty()) {
    throw Error("give a pipeline or --config (see phongsim list)");
  }
  if (!t.pipeline.empty()) (void)find_pipeline(t.pipeline);  // unknown: list the known ones
  const std::string config = !t.config.empty()
                                 ? t.config
                                 : (data_root() / "configs" / t.pipeline / "default.toml").string();
  Loaded l{Config::load(config), nullptr, nullptr};
  l.pipeline = &find_pipeline(t.pipeline.empty() ? l.cfg.pipeline() : t.pipeline);
  l.model = make_model(*l.pipeline, l.cfg);
  return l;
}

DutFactory rtl_factory(const Loaded& l, const Target& t) {
  std::shared_ptr<RtlLibrary> library;
  if (!t.plugin.empty()) {
    library = RtlLibrary::open(t.plugin, rtl_gflags(l.cfg));
  } else {
    const RtlPlugin plugin =
        locate_rtl(l.cfg, t.no_build ? RtlBuild::never : RtlBuild::if_missing, stderr);
    library = RtlLibrary::open(plugin.path, plugin.gflags);
  }
  const PipelineModel* model = l.model.get();
  return [library, model]() { return library->create(*model); };
}

nlohmann::json to_json(const CosimReport& r) {
  return {
      {"pipeline", r.pipeline},
      {"config", r.config_name},
      {"config_path", r.config_path},
      {"seed", r.options.seed},
      {"vectors", r.vectors},
      {"directed_vectors", r.directed},
      {"random_vectors", r.random},
      {"outputs", r.outputs},
      {"mismatches", r.mismatches},
      {"cycles", r.cycles},
      {"source_idle", r.options.source.str()},
      {"backpressure", r.options.sink.str()},
      {"throughput", r.throughput},
      {"latency", {{"min", r.latency_min}, {"max", r.latency_max}}},
      {"passed", r.passed},
      {"failure_kind", r.failure_kind},
      {"failure", r.failure},
  };
}

int cmd_cosim(const Target& t, CosimOptions o, const std::string& source, const std::string& sink,
              const std::string& trace, const std::string& json) {
  o.source = StallPattern::parse(source);
  o.sink = StallPattern::parse(sink);
  const Loaded l = load(t);
  if (o.only_index && o.random_vectors != 0) {
    // --vector-index replaces --vectors; keep the report's repro line exact.
    o.random_vectors = 0;
  }
  std::optional<OutputFile> json_file;
  std::optional<OutputFile> trace_file;
  if (!json.empty()) json_file.emplace(json);
  if (!trace.empty()) {
    trace_file.emplace(trace);
    o.trace_path = trace_file->temp_path().string();
  }
  const DutFactory make_dut = rtl_factory(l, t);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  CosimReport r = cosim({std::string(l.pipeline->name), l.cfg, *l.model, stimulus,
                         l.pipeline->independent_vectors, make_dut},
                        o);
  if (trace_file) {
    trace_file->commit();
    r.trace_written = trace;
    std::string& f = r.failure;
    if (const auto at = f.find(o.trace_path); at != std::string::npos) {
      f.replace(at, o.trace_path.size(), trace);
    }
  }
  if (!r.passed) fmt::print("{}", r.failure);
  fmt::print("{}\n", r.summary());
  if (trace_file && r.passed) fmt::print("waveform (first {} cycles): {}\n", o.trace_window, trace);
  if (json_file) {
    fmt::print(json_file->get(), "{}\n", to_json(r).dump(2));
    json_file->commit();
  }
  return r.passed ? 0 : 1;
}

int cmd_eval(const Target& t, const std::string& backend, const std::string& in,
             const std::string& out, bool real) {
  const Loaded l = load(t);
  DutFactory make_dut;
  if (backend == "rtl") make_dut = rtl_factory(l, t);
  const std::size_t rows = eval_csv(*l.model, make_dut, in, out, real);
  fmt::print("{} output rows from {} ({} backend, {}) -> {}\n", rows, in, backend, l.cfg.origin(),
             out);
  return 0;
}

int cmd_build_rtl(const Target& t) {
  const Loaded l = load(t);
  const RtlPlugin plugin = locate_rtl(l.cfg, RtlBuild::if_missing, stderr);
  (void)RtlLibrary::open(plugin.path, plugin.gflags)->create(*l.model);  // loads and binds
  fmt::print("{} ({}): {}\n  {}\n", l.cfg.origin(), plugin.origin, plugin.path.string(),
             plugin.gflags);
  return 0;
}

// Progress of long renders on stderr: a self-overwriting line on a terminal, nothing otherwise
// (logs stay clean); at most five updates a second.
RenderProgress render_progress(bool quiet) {
  if (quiet || isatty(STDERR_FILENO) == 0) return [](std::string_view, auto, auto) {};
  auto last = std::make_shared<std::chrono::steady_clock::time_point>();
  return [last](std::string_view what, std::uint64_t done, std::uint64_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (done != total && now - *last < std::chrono::milliseconds(200)) return;
    *last = now;
    if (total == 0) {
      fmt::print(stderr, "\r\033[K  {}: {} outputs", what, done);
    } else {
      fmt::print(stderr, "\r\033[K  {}: {}/{} pixels", what, done, total);
    }
    if (done == total) fmt::print(stderr, "\r\033[K");
  };
}

struct RenderCli {
  RenderOptions options;
  std::string backend = "auto";
  std::string terms = "all";
  std::string texture_filter = "bilinear";
  std::string out_dir = "render";
  std::string json;
  bool quiet = false;
};

int cmd_render(RenderCli c) {
  c.options.backend = parse_backend(c.backend);
  c.options.terms = parse_terms(c.terms);
  c.options.texture_filter = texmap::parse_filter(c.texture_filter);
  std::optional<OutputFile> json;
  if (!c.json.empty()) json.emplace(c.json);  // unwritable: fail before rendering
  const RenderResult r = render(c.options, render_progress(c.quiet));
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

// ---- sweep ----

std::function<void(std::size_t, std::size_t)> sweep_progress() {
  if (isatty(STDERR_FILENO) == 0) return [](std::size_t, std::size_t) {};
  return [](std::size_t done, std::size_t total) {
    fmt::print(stderr, "\r\033[K  sweep: point {}/{}", done, total);
    if (done == total) fmt::print(stderr, "\r\033[K");
  };
}

int cmd_sweep(const std::string& action, const std::string& file, const std::string& out,
              const std::string& sweep_file, std::size_t index, const std::string& write,
              bool verify) {
  if (action == "point") {  // one job of a plan: evaluate a point's configuration
    const SweepSpec spec = load_sweep(sweep_file);
    OutputFile check(out);  // unwritable: fail before the work
    const PointResult r = evaluate_point(spec, file, index, stderr);
    write_point_result(r, out);
    fmt::print("point {}: max error {:.4g} LSB{}\n", index, r.error.max_lsb,
               r.synthesized ? fmt::format(", {} cells", r.synth.cells) : "");
    return 0;
  }
  if (action == "search") {
    const SearchSpec spec = load_search(file);
    const SearchResult r =
        search_min_width(spec, [](std::string_view s) { fmt::print("  {}\n", s); });
    const Config base = Config::load(spec.base);
    const fs::path dest = write.empty()
                              ? data_root() / "configs" / base.pipeline() / (spec.name + ".toml")
                              : fs::path(write);
    fmt::print("found after {} evaluations: {} fraction bits fewer, max error {:.4g} LSB{}\n",
               r.evaluations, r.bits_saved, r.error.max_lsb,
               std::isnan(r.colour_correctness)
                   ? ""
                   : fmt::format(", colour correctness {:.5f}", r.colour_correctness));
    for (const auto& [sig, f] : r.formats) fmt::print("  {} = {}\n", sig, f);
    OutputFile found(dest);  // unwritable: fail before Verilating
    std::fputs(r.toml.c_str(), found.get());
    if (verify) {
      // Verilate the found point and co-simulate it before it lands at `dest`.
      const fs::path dir = fs::temp_directory_path() / fmt::format("phongsim-search-{}", getpid());
      fs::create_directories(dir);
      const std::shared_ptr<void> cleanup(nullptr, [dir](void*) {
        std::error_code ec;
        fs::remove_all(dir, ec);
      });
      const fs::path candidate = dir / dest.filename();
      {
        OutputFile c(candidate);
        std::fputs(r.toml.c_str(), c.get());
        c.commit();
      }
      const Config cfg = Config::load(candidate);
      const auto model = make_model(find_pipeline(cfg.pipeline()), cfg);
      const RtlPlugin plugin = locate_rtl(cfg, RtlBuild::if_missing, stderr);
      const auto library = RtlLibrary::open(plugin.path, plugin.gflags);
      CosimOptions o;
      o.random_vectors = spec.verify_vectors;
      o.source = StallPattern::parse("random:0.2");
      o.sink = StallPattern::parse("random:0.5");
      const PipelineInfo& info = find_pipeline(cfg.pipeline());
      const Stimulus stimulus = info.make_stimulus(*model, cfg);
      const CosimReport rep =
          cosim({std::string(info.name), cfg, *model, stimulus, info.independent_vectors,
                 [&]() { return library->create(*model); }},
                o);
      if (!rep.passed) {
        fmt::print("{}", rep.failure);
        throw Error(fmt::format("the found configuration fails co-simulation; not written to {}",
                                dest.string()));
      }
      fmt::print("verified: {}\n", rep.summary());
    }
    found.commit();
    fmt::print("wrote {}\n", dest.string());
    return 0;
  }
  const SweepSpec spec = load_sweep(file);
  if (action == "plan") {
    const auto points = plan_sweep(spec, out);
    fmt::print(
        "{} points: {}/points/*.toml; run {}/jobs.txt (e.g. parallel < jobs.txt, or a "
        "Slurm array: scripts/slurm-sweep.sh), or make -j -C {}; then phongsim sweep "
        "merge {} --out {}\n",
        points.size(), out, out, out, file, out);
    return 0;
  }
  if (action == "merge") {
    const auto results = merge_sweep(spec, out);
    fmt::print("{} points merged: {}/sweep.csv, {}/summary.md{}\n", results.size(), out, out,
               spec.synth.generic || spec.synth.ice40 ? fmt::format(", {}/pareto.png", out) : "");
    return 0;
  }
  if (action == "run") {
    const auto results = run_sweep(spec, out, sweep_progress(), stderr);
    fmt::print("{}\n{} points: {}/sweep.csv, {}/summary.md\n",
               read_file(fs::path(out) / "summary.md"), results.size(), out, out);
    return 0;
  }
  throw Error(fmt::format("unknown sweep action '{}' (run, plan, point, merge, search)", action));
}

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

int cmd_bench(const Target& t, std::uint64_t vectors, int render_radius,
              const MethodsBench& methods) {
  if (t.pipeline == "render" && t.config.empty()) return bench_render(render_radius);
  if (t.pipeline == "methods" && t.config.empty()) return bench_methods(methods);
  const Loaded l = load(t);
  const DutFactory make_dut = rtl_factory(l, t);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  const BenchReport r = bench({std::string(l.pipeline->name), l.cfg, *l.model, stimulus,
                               l.pipeline->independent_vectors, make_dut},
                              vectors);
  fmt::print("bench {}/{}: {} random vectors each\n{}", l.pipeline->name, l.cfg.name(), vectors,
             r.table());
  return 0;
}

int cmd_vectors(const Target& t, std::uint64_t seed, std::uint64_t random, bool directed,
                const std::string& out) {
  const Loaded l = load(t);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  const auto& fields = l.model->inputs();
  OutputFile file(out);
  std::string text;
  for (std::size_t i = 0; i < fields.size(); ++i) text += (i ? "," : "") + fields[i].name;
  text += "\n";
  std::vector<std::int64_t> v(fields.size());
  const std::uint64_t first = directed ? 0 : stimulus.directed_count();
  const std::uint64_t last = stimulus.directed_count() + random;
  for (std::uint64_t index = first; index < last; ++index) {
    stimulus.vector(seed, index, v);
    for (std::size_t i = 0; i < v.size(); ++i) text += fmt::format("{}{}", i ? "," : "", v[i]);
    text += "\n";
  }
  std::fputs(text.c_str(), file.get());
  file.commit();
  fmt::print("{} vectors ({} directed + {} random, seed {}) -> {}\n", last - first,
             directed ? stimulus.directed_count() : 0, random, seed, out);
  return 0;
}

std::vector<fs::path> pipeline_configs(std::string_view pipeline) {
  const fs::path dir = data_root() / "configs" / pipeline;
  std::vector<fs::path> files;
  if (fs::is_directory(dir)) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() == ".toml") files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

int analyze_kb(std::uint64_t samples, std::uint64_t seed) {
  fmt::print("Three-piece quadratic against cos^n theta over [0, pi] (kb::max_error, rms_error)\n");
  fmt::print("  {:>3}  {:>8} {:>8} {:>9} {:>9}   {:>8} {:>8} {:>9} {:>9}\n", "n", "a closed",
             "b closed", "max", "rms", "a lsq", "b lsq", "max", "rms");
  for (const KbFitRow& r : kb_fit_table()) {
    fmt::print(
        "  {:>3}  {:>8.5f} {:>8.5f} {:>9.6f} {:>9.6f}   {:>8.5f} {:>8.5f} {:>9.6f} {:>9.6f}\n", r.n,
        r.closed.a, r.closed.b, r.closed_max, r.closed_rms, r.lsq.a, r.lsq.b, r.lsq_max, r.lsq_rms);
  }
  const int spans = static_cast<int>(std::max<std::uint64_t>(1, samples / 2000));
  const fx::Format out{false, 0, 8};
  const int lengths[] = {16, 64, 256, 1024, 4096};
  const int guards[] = {0, 4, 8, 12, 16, 20, 24, 40};
  for (const KbPolicy policy : {KbPolicy::exact_reload, KbPolicy::d2_only}) {
    fmt::print(
        "\nDrift: max |accumulator - exact span|, both clamped to [0, 1], in LSBs of an 8-bit "
        "output; {} random spans per cell (1-2 terms, n 1..125), seed {}, policy {}\n",
        spans, seed, policy == KbPolicy::d2_only ? "d2_only" : "exact_reload");
    fmt::print("  {:>6}", "length");
    for (const int g : guards) fmt::print(" {:>9}", fmt::format("G={}", g));
    fmt::print("\n");
    for (const int length : lengths) {
      fmt::print("  {:>6}", length);
      for (const int g : guards)
        fmt::print(" {:>9.4f}", kb_drift(length, g, policy, out, spans, seed));
      fmt::print("\n");
    }
  }
  fmt::print(
      "\nGuard bits for a drift of at most 1/2 output LSB (exact_reload): analytic bound "
      "G >= log2((L^2 - L + 2)/2), and the smallest G that met it on the spans above\n");
  fmt::print("  {:>6} {:>9} {:>9}\n", "length", "analytic", "measured");
  for (const int length : lengths) {
    int measured = 0;
    while (measured < 40 &&
           kb_drift(length, measured, KbPolicy::exact_reload, out, spans, seed) > 0.5) {
      ++measured;
    }
    fmt::print("  {:>6} {:>9} {:>9}\n", length, kb_guard_bits_needed(length), measured);
  }
  return 0;
}

int analyze_quad(std::uint64_t samples, std::uint64_t seed) {
  const int triangles = static_cast<int>(std::max<std::uint64_t>(1, samples / 5000));
  const fx::Format out{false, 0, 8};
  const int sizes[] = {16, 64, 256, 1024};
  const int guards[] = {0, 4, 8, 12, 16, 20, 24, 40};
  fmt::print(
      "Drift: max |accumulator - r(s, t) evaluated directly (eqs. 4.1, 4.3)|, both clamped "
      "to [0, 1], in LSBs of an 8-bit output; {} random triangles with vertices in a "
      "size x size box per cell, quadratic colours, seed {}\n",
      triangles, seed);
  fmt::print("  {:>5}", "size");
  for (const int g : guards) fmt::print(" {:>9}", fmt::format("G={}", g));
  fmt::print("\n");
  for (const int size : sizes) {
    fmt::print("  {:>5}", size);
    for (const int g : guards) fmt::print(" {:>9.4f}", quad_drift(size, g, out, triangles, seed));
    fmt::print("\n");
  }
  fmt::print(
      "\nGuard bits for a drift of at most 1/2 output LSB over a box: analytic bound "
      "G >= log2(1 + (w-1)^2 + (w-1)(h-1) + (h-1)^2), and the smallest G that met it on "
      "the triangles above\n");
  fmt::print("  {:>5} {:>9} {:>9}\n", "size", "analytic", "measured");
  for (const int size : sizes) {
    int measured = 0;
    while (measured < 40 && quad_drift(size, measured, out, triangles, seed) > 0.5) ++measured;
    fmt::print("  {:>5} {:>9} {:>9}\n", size, quad_guard_bits_needed(size, size), measured);
  }
  fmt::print(
      "\nOutput against direct evaluation, per configuration: |output - r(s, t)|, r clamped to the "
      "output range, in "
      "output LSBs over {} random triangles of the co-simulation's distribution (boxes up to "
      "1024 pixels), colours of the configuration's [setup] mode, seed {}\n",
      triangles * 10, seed);
  fmt::print("  {:<16} {:>9} {:>6} {:>5} {:>10} {:>9} {:>9}\n", "config", "mode", "acc", "out",
             "pixels", "max", "mean");
  for (const auto& file : pipeline_configs("quad")) {
    const Loaded l = load(Target{"quad", file.string(), false, ""});
    const QuadFormats f = QuadFormats::from_config(l.cfg);
    const QuadMode mode = quad_mode(l.cfg);
    const QuadOutputError e = quad_output_error(f, mode, triangles * 10, seed);
    fmt::print("  {:<16} {:>9} {:>6} {:>5} {:>10} {:>9.4f} {:>9.4f}\n", l.cfg.name(),
               mode == QuadMode::linear ? "linear" : "quadratic", f.acc.str(), f.out.str(),
               e.pixels, e.max, e.mean);
  }
  return 0;
}

int cmd_analyze(const std::string& pipeline, std::vector<std::string> configs,
                std::uint64_t samples, std::uint64_t seed) {
  if (pipeline == "kb") return analyze_kb(samples, seed);
  if (pipeline == "quad") return analyze_quad(samples, seed);
  if (pipeline != "lyon") {
    (void)find_pipeline(pipeline);  // unknown names get the list of known ones
    throw Error(
        fmt::format("no analysis for pipeline '{}' yet (available: lyon, kb, quad)", pipeline));
  }
  if (configs.empty()) {
    for (const auto& f : pipeline_configs("lyon")) configs.push_back(f.string());
  }
  std::vector<Loaded> loaded;
  for (const auto& c : configs) loaded.push_back(load(Target{"lyon", c, false, ""}));
  const auto model_of = [](const Loaded& l) -> const LyonModel& {
    return dynamic_cast<const LyonModel&>(*l.model);
  };
  // The normalization table uses the first configuration that normalizes N.
  const Loaded* norm_cfg = &loaded.front();
  for (const auto& l : loaded) {
    if (model_of(l).formats().norm > 0) {
      norm_cfg = &l;
      break;
    }
  }
  const LyonModel& nm = model_of(*norm_cfg);
  fmt::print("Approximate normalization: length of a vector after g (Lyon, Fig. 4)\n");
  fmt::print("  {:>6}  {:>10}  {:>10}  {:>10}   fixed: {} (g{})\n", "length", "g1 float",
             "g2 float", "fixed", norm_cfg->cfg.name(), nm.formats().norm);
  for (const auto& r : lyon_norm_table(nm)) {
    fmt::print("  {:>6.2f}  {:>10.5f}  {:>10.5f}  {:>10.5f}\n", r.length, r.g1, r.g2, r.fixed);
  }
  fmt::print("  at y = 1/2 (length 0.7071): g1 = {}, g2 = {}, exact 1/sqrt(1/2) = {:.4f}\n\n",
             lyon::g1(0.5), lyon::g2(0.5), 1 / std::sqrt(0.5));

  fmt::print("Shape function: max over alpha of |f_k(x) - cos^n alpha|, x = (n/2)|D|^2, float\n");
  fmt::print("  {:>6}  {:>9}  {:>9}  {:>9}  {:>9}\n", "n", "k=0", "k=1", "k=2", "k=3");
  for (const auto& r : lyon_shape_table()) {
    fmt::print("  {:>6}  {:>9.6f}  {:>9.6f}  {:>9.6f}  {:>9.6f}\n", r.n, r.max_error[0],
               r.max_error[1], r.max_error[2], r.max_error[3]);
  }
  fmt::print(
      "\nFixed-point output against the float datapath (same quantized inputs), in output "
      "LSBs; {} random pixels, seed {}\n",
      samples, seed);
  fmt::print("  {:<14} {:>9} {:>13} {:>9} {:>9} {:>9} {:>11}\n", "config", "spec max", "max n<=256",
             "spec mean", "diff max", "diff mean", "highlights");
  for (const auto& l : loaded) {
    const LyonOutputError e = lyon_output_error(model_of(l), samples, seed);
    fmt::print("  {:<14} {:>9.2f} {:>13.2f} {:>9.3f} {:>9.2f} {:>9.3f} {:>10.1f}%\n", l.cfg.name(),
               e.spec_max, e.spec_max_low_n, e.spec_mean, e.diff_max, e.diff_mean,
               100.0 * static_cast<double>(e.spec_nonzero) / static_cast<double>(e.samples));
  }
  for (const auto& l : loaded) {
    fmt::print("\nStage formats of {} ({}, latency {} cycles)\n{}", l.cfg.origin(),
               l.cfg.description(), model_of(l).latency(), lyon_stage_formats(model_of(l)));
  }
  return 0;
}

int cmd_list() {
  for (const auto& p : pipelines()) {
    fmt::print("{:<8} {}\n", p.name, p.summary);
    for (const auto& f : pipeline_configs(p.name)) {
      const Config cfg = Config::load(f);
      fmt::print("  {:<40} {}\n", fs::relative(f, data_root()).string(), cfg.description());
    }
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "phongsim: co-simulates fixed-point pixel-shading RTL against its bit-accurate "
      "C++ model.\nExit status: 0 ok, 1 verification failure, 2 bad input."};
  app.require_subcommand(1);
  std::function<int()> action;

  // cosim
  Target cosim_target;
  CosimOptions cosim_options;
  std::string source = "none";
  std::string sink = "none";
  std::string trace;
  std::string json;
  std::uint64_t vector_index = 0;
  auto* cosim_cmd = app.add_subcommand(
      "cosim", "Co-simulate model and Verilated RTL on directed + seeded random vectors");
  cosim_target.add_options(*cosim_cmd);
  cosim_cmd
      ->add_option("--vectors", cosim_options.random_vectors,
                   "random vectors after the directed corners")
      ->capture_default_str();
  cosim_cmd->add_option("--seed", cosim_options.seed, "seed of stimulus and random stalls")
      ->capture_default_str();
  cosim_cmd
      ->add_option("--source-idle", source,
                   "when the source offers input: none | periodic:BITS | random:P | "
                   "long[:STALL[:RUN]]")
      ->capture_default_str();
  cosim_cmd->add_option("--backpressure", sink, "when the sink is ready (same patterns)")
      ->capture_default_str();
  auto* index_opt = cosim_cmd->add_option("--vector-index", vector_index,
                                          "run only this vector (as numbered in a failure report)");
  cosim_cmd->add_flag("!--no-directed", cosim_options.directed, "skip the directed corners");
  cosim_cmd->add_option("--trace", trace,
                        "write an FST waveform: the window before the first failure, or the "
                        "first cycles of a passing run");
  cosim_cmd->add_option("--trace-window", cosim_options.trace_window, "waveform length in cycles")
      ->capture_default_str();
  cosim_cmd
      ->add_option("--timeout", cosim_options.timeout,
                   "cycles without a handshake that count as deadlock (0: 100000)")
      ->capture_default_str();
  cosim_cmd->add_option("--json", json, "write a JSON summary");
  cosim_cmd->callback([&]() {
    if (*index_opt) cosim_options.only_index = vector_index;
    action = [&]() { return cmd_cosim(cosim_target, cosim_options, source, sink, trace, json); };
  });

  // eval
  Target eval_target;
  std::string backend = "model";
  std::string in;
  std::string out;
  bool real = false;
  auto* eval_cmd =
      app.add_subcommand("eval", "Evaluate a CSV of input vectors through the model or the RTL");
  eval_target.add_options(*eval_cmd);
  eval_cmd->add_option("--backend", backend, "model or rtl")
      ->check(CLI::IsMember({"model", "rtl"}))
      ->capture_default_str();
  eval_cmd->add_option("--in", in, "input CSV: header of input field names, one vector per row")
      ->required();
  eval_cmd->add_option("--out", out, "output CSV: header of output field names")->required();
  eval_cmd->add_flag("--real", real, "values are reals instead of raw integers");
  eval_cmd->callback(
      [&]() { action = [&]() { return cmd_eval(eval_target, backend, in, out, real); }; });

  // build-rtl
  Target build_target;
  auto* build_cmd = app.add_subcommand(
      "build-rtl", "Verilate a configuration into the RTL cache (or find it built in)");
  build_target.add_options(*build_cmd, false);
  build_cmd->callback([&]() { action = [&]() { return cmd_build_rtl(build_target); }; });

  // bench
  Target bench_target;
  std::uint64_t bench_vectors = 200000;
  auto* bench_cmd =
      app.add_subcommand("bench",
                         "Vectors per second: model, Verilated RTL, co-simulation (a pipeline); "
                         "render: pixels per second per backend; methods: CPU time per shading "
                         "method");
  bench_target.add_options(*bench_cmd);
  bench_cmd->add_option("--vectors", bench_vectors, "vectors per measurement")
      ->capture_default_str();
  int bench_radius = 85;
  bench_cmd
      ->add_option("--radius", bench_radius,
                   "bench render: shinyballs sphere radius (85: a 511-pixel-wide strip)")
      ->capture_default_str();
  MethodsBench bench_methods_options;
  bench_cmd
      ->add_option("--scene", bench_methods_options.scene,
                   "bench methods: the scene (as phongsim render --scene)")
      ->capture_default_str();
  bench_cmd
      ->add_option("--method", bench_methods_options.methods,
                   "bench methods: the methods (gouraud and phong are added if missing)")
      ->delimiter(',')
      ->capture_default_str();
  bench_cmd
      ->add_option("--rounds", bench_methods_options.rounds,
                   "bench methods: interleaved rounds (the median is printed)")
      ->capture_default_str();
  bench_cmd->add_option("--size", bench_methods_options.size,
                        "bench methods: image width (as phongsim render --size)");
  bench_cmd->add_option("--teapot-resolution", bench_methods_options.teapot_resolution,
                        "bench methods: as phongsim render --teapot-resolution");
  bench_cmd->callback([&]() {
    action = [&]() {
      return cmd_bench(bench_target, bench_vectors, bench_radius, bench_methods_options);
    };
  });

  // sweep
  std::string sweep_action, sweep_file, sweep_out = "sweep-out", sweep_of, sweep_write;
  std::size_t sweep_index = 0;
  bool sweep_verify = true;
  auto* sweep_cmd = app.add_subcommand(
      "sweep",
      "Bit-width exploration: run|plan|point|merge a sweep file, or search for the "
      "narrowest configuration within an error budget (docs/exploration.md)");
  sweep_cmd->add_option("action", sweep_action, "run, plan, point, merge or search")->required();
  sweep_cmd
      ->add_option("file", sweep_file,
                   "the sweep file (point: the point's configuration; search: the search "
                   "file)")
      ->required();
  sweep_cmd->add_option("--out", sweep_out, "output directory (point: the result JSON)")
      ->capture_default_str();
  sweep_cmd->add_option("--sweep", sweep_of, "point: the sweep file it belongs to");
  sweep_cmd->add_option("--index", sweep_index, "point: its index");
  sweep_cmd->add_option("--write", sweep_write,
                        "search: where the found configuration goes (default "
                        "configs/<pipeline>/<search name>.toml)");
  sweep_cmd->add_flag("!--no-verify", sweep_verify,
                      "search: skip Verilating and co-simulating the found configuration");
  sweep_cmd->callback([&]() {
    action = [&]() {
      if (sweep_action == "point" && sweep_of.empty()) throw Error("sweep point needs --sweep");
      return cmd_sweep(sweep_action, sweep_file, sweep_out, sweep_of, sweep_index, sweep_write,
                       sweep_verify);
    };
  });

  // render
  RenderCli render_cli;
  auto* render_cmd = app.add_subcommand(
      "render",
      "Shade a scene with shading methods through float, model or RTL backends; write "
      "images, difference images, a scanline plot and metrics");
  render_cmd
      ->add_option("--scene", render_cli.options.scene,
                   "shinyballs, kbsphere32, kbsphere512, triangle, dodecahedron, "
                   "sphere40, teapot, or a scene file (.toml)")
      ->capture_default_str();
  render_cmd
      ->add_option("--method", render_cli.options.methods,
                   "method(s), one grid row each (default: the scene's list; all: every "
                   "method the scene and backend can use; `phongsim render --list-methods`)")
      ->delimiter(',');
  render_cmd
      ->add_option("--backend", render_cli.backend,
                   "auto (RTL where a method has a unit, else float), float, model, rtl")
      ->capture_default_str();
  render_cmd->add_option("--size", render_cli.options.size,
                         "shinyballs: sphere radius in pixels (default 64); meshes: image width");
  render_cmd->add_option("--teapot-resolution", render_cli.options.teapot_resolution,
                         "teapot: grid cells per patch side (default: about 3750 facets)");
  render_cmd->add_option("--reference", render_cli.options.reference,
                         "reference method for metrics and difference images (default phong, "
                         "float)");
  render_cmd->add_option("--scanline", render_cli.options.scanline,
                         "row of the scanline illumination plot (default: the middle)");
  render_cmd->add_option("--unit-config", render_cli.options.unit_config,
                         "a configuration file replacing the built-in one of every unit method "
                         "of its pipeline");
  render_cmd
      ->add_option("--terms", render_cli.terms,
                   "lighting terms: all, or specular only (Vlasic's Table 6.1 compares those)")
      ->capture_default_str();
  render_cmd
      ->add_option("--texture-size", render_cli.options.texture_size,
                   "texture methods: texels per side (0: the exact texture function)")
      ->capture_default_str();
  render_cmd
      ->add_option("--texture-filter", render_cli.texture_filter,
                   "texture methods: nearest or bilinear")
      ->capture_default_str();
  render_cmd->add_option("--out", render_cli.out_dir, "output directory")->capture_default_str();
  render_cmd->add_option("--json", render_cli.json, "write a JSON summary here");
  render_cmd->add_flag("--no-build", render_cli.options.no_build,
                       "fail instead of Verilating a configuration that is not built yet");
  render_cmd->add_flag("--quiet", render_cli.quiet, "no progress display");
  bool list_methods = false;
  render_cmd->add_flag("--list-methods", list_methods, "list the methods and exit");
  render_cmd->callback([&]() {
    action = [&]() {
      if (list_methods) {
        for (const MethodInfo& m : render_methods()) {
          fmt::print("  {:<22} {:<6} {}{}\n", m.name, m.config.empty() ? "float" : "unit",
                     m.description, m.mesh_only ? " [meshes only]" : "");
        }
        return 0;
      }
      return cmd_render(render_cli);
    };
  });

  // vectors
  Target vectors_target;
  std::uint64_t vectors_seed = 1;
  std::uint64_t vectors_random = 1000;
  bool vectors_directed = true;
  std::string vectors_out;
  auto* vectors_cmd = app.add_subcommand(
      "vectors", "Write the co-simulation stimulus (directed + seeded random) as an input CSV");
  vectors_target.add_options(*vectors_cmd, false);
  vectors_cmd->add_option("--vectors", vectors_random, "random vectors after the directed ones")
      ->capture_default_str();
  vectors_cmd->add_option("--seed", vectors_seed, "seed")->capture_default_str();
  vectors_cmd->add_flag("!--no-directed", vectors_directed, "skip the directed corners");
  vectors_cmd->add_option("--out", vectors_out, "output CSV (input of phongsim eval)")->required();
  vectors_cmd->callback([&]() {
    action = [&]() {
      return cmd_vectors(vectors_target, vectors_seed, vectors_random, vectors_directed,
                         vectors_out);
    };
  });

  // analyze
  std::string analyze_pipeline;
  std::vector<std::string> analyze_configs;
  std::uint64_t analyze_samples = 100000;
  std::uint64_t analyze_seed = 1;
  auto* analyze_cmd = app.add_subcommand(
      "analyze", "Accuracy analysis of a pipeline: approximations and fixed-point error");
  analyze_cmd->add_option("pipeline", analyze_pipeline, "pipeline (lyon, kb, quad)")->required();
  analyze_cmd->add_option("--config", analyze_configs,
                          "configuration(s) to analyze (default: every one in configs/<pipeline>)");
  analyze_cmd->add_option("--samples", analyze_samples, "random pixels per configuration")
      ->capture_default_str();
  analyze_cmd->add_option("--seed", analyze_seed, "seed")->capture_default_str();
  analyze_cmd->callback([&]() {
    action = [&]() {
      return cmd_analyze(analyze_pipeline, analyze_configs, analyze_samples, analyze_seed);
    };
  });

  // list
  app.add_subcommand("list", "Pipelines and their named configurations")->callback([&]() {
    action = cmd_list;
  });

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "phongsim: error: {} (see phongsim --help)\n", e.what());
    return 2;
  }
  try {
    return action();
  } catch (const Error& e) {
    fmt::print(stderr, "phongsim: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "phongsim: error: {}\n", e.what());
    return 2;
  }
}
