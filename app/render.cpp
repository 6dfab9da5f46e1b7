// phongsim render: shade a scene with shading methods through float, model or RTL backends, and
// write the images, difference images, a scanline plot and metrics (docs/render.md).
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/output_file.h"
#include "model/config.h"
#include "sim/explore/synth.h"
#include "sim/pipelines/registry.h"
#include "sim/render/render.h"

namespace phongsim::cli {
namespace {

namespace fs = std::filesystem;

struct RenderCli {
  RenderOptions options;
  Target rtl;  // the user's RTL (--rtl, -f, -F, -I, -D, --top) and its --pipeline
  std::string backend = "auto";
  std::string terms = "all";
  std::string texture_filter = "bilinear";
  std::string out_dir = "render";
  std::string json;
  std::string clock;  // --clock-mhz: MHz, or "ice40"
  bool quiet = false;
};

// A unit's clock for frames per second (--clock-mhz): the given frequency, or its iCE40 fmax.
struct Clock {
  std::optional<double> mhz;
  std::string note;  // where it comes from, or why there is none
};

constexpr double kMaxClockMhz = 100000;

// --clock-mhz: empty (no clock), ice40, or a frequency in (0, kMaxClockMhz] MHz. Checked before
// anything is rendered.
std::optional<double> parse_clock(const std::string& text) {
  if (text.empty() || text == "ice40") return std::nullopt;
  double mhz = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), mhz);
  if (ec != std::errc{} || end != text.data() + text.size() || !(mhz > 0) || mhz > kMaxClockMhz) {
    throw Error(fmt::format("--clock-mhz {}: expected a frequency in MHz (0 < f <= {:g}) or ice40",
                            text, kMaxClockMhz));
  }
  return mhz;
}

// Each unit configuration's clock: --clock-mhz's frequency, or with ice40 what nextpnr reaches
// placing and routing it on the UP5K (`phongsim synth --ice40`, cached by content), where it fits
// and the flow runs.
std::map<std::string, Clock> unit_clocks(const RenderResult& r, const std::string& clock) {
  std::map<std::string, Clock> clocks;
  if (clock.empty()) return clocks;
  const std::optional<double> given = parse_clock(clock);
  // A clock no frame would use is a mistake, not something to ignore (as --unit-config's).
  if (std::none_of(r.results.begin(), r.results.end(),
                   [](const MethodResult& m) { return m.frame.has_value(); })) {
    throw Error(fmt::format(
        "--clock-mhz {}: no method chosen here runs on a hardware unit (through --backend model, "
        "rtl or auto)",
        clock));
  }
  for (const MethodResult& m : r.results) {
    if (!m.frame || clocks.contains(m.frame->config)) continue;
    Clock& c = clocks[m.frame->config];
    if (given) {
      c = {given, "--clock-mhz"};
      continue;
    }
    const Config cfg = Config::load(m.frame->config);
    try {
      const SynthResult s = synthesize(rtl_design(find_pipeline(cfg.pipeline()), cfg), cfg.origin(),
                                       SynthOptions{.generic = false, .ice40 = true}, stderr);
      if (s.fits) {
        c = {s.fmax_mhz,
             fmt::format("nextpnr-ice40 --{}, seed {}", kSynthIce40Device, kSynthIce40Seed)};
      } else {
        c.note = fmt::format("does not fit the iCE40 {} ({} LUT4, {} FF, {} MAC16)",
                             kSynthIce40Device, s.lut4, s.ff, s.mac16);
      }
    } catch (const Error& e) {
      std::string why = e.what();  // without the configuration the table names already
      if (why.starts_with(cfg.origin() + ": ")) why.erase(0, cfg.origin().size() + 2);
      c.note = "the iCE40 flow failed: " + why;
    }
  }
  return clocks;
}

nlohmann::ordered_json metrics_json(const ImageMetrics& m) {
  return {{"colour_correctness", m.colour_correctness},
          {"psnr_db", json_number(m.psnr)},
          {"max_error", m.max_error},
          {"pixels", m.pixels}};
}

double frame_rate(const FrameReport& f) {
  return f.cycles.cycles == 0 ? 0.0 : static_cast<double>(f.pixels) / f.cycles.cycles;
}

double frames_per_second(const FrameReport& f, double mhz) {
  return f.cycles.cycles == 0 ? 0.0 : mhz * 1e6 / static_cast<double>(f.cycles.cycles);
}

// The frame's clocks per method on a hardware unit (docs/system.md); empty when none ran on one.
// With clocks (--clock-mhz), frames per second at each unit's clock, and why a unit has none.
std::string frame_table(const RenderResult& r, const std::map<std::string, Clock>& clocks) {
  std::string t, notes;
  const bool fps = !clocks.empty();
  for (const MethodResult& m : r.results) {
    if (!m.frame) continue;
    if (t.empty()) {
      t = fmt::format(
          "\nClocks of the frame on each method's unit (RTL: measured; model: the cycle model)\n"
          "| method | backend | cycles | pixels | pixels/clock | outputs | fill | setup | "
          "empty rows | stalls |{}\n|---|---|---|---|---|---|---|---|---|---|{}\n",
          fps ? " clock (MHz) | frames/s |" : "", fps ? "---|---|" : "");
    }
    const FrameCycles& c = m.frame->cycles;
    t += fmt::format("| {} | {} | {} | {} | {:.3f} | {} | {} | {} | {} | {} |", m.method,
                     backend_name(m.backend), c.cycles, m.frame->pixels, frame_rate(*m.frame),
                     c.outputs, c.fill_cycles, c.setup_cycles, c.empty_row_cycles, c.stall_cycles);
    if (fps) {
      const Clock& k = clocks.at(m.frame->config);
      if (k.mhz) {
        t += fmt::format(" {:.2f} | {:.1f} |", *k.mhz, frames_per_second(*m.frame, *k.mhz));
      } else {
        t += " — | — |";
        notes += fmt::format("{}: {}: {}\n", m.method, m.frame->config, k.note);
      }
    }
    t += "\n";
  }
  return t + notes;
}

int run(RenderCli c) {
  c.options.backend = parse_backend(c.backend);
  c.options.terms = parse_terms(c.terms);
  c.options.texture_filter = texmap::parse_filter(c.texture_filter);
  if (quick_mode()) {  // PHONGSIM_QUICK: small images (docs/cosim.md)
    const bool analytic = c.options.scene == "shinyballs";
    const int cap = analytic ? 16 : 96;
    c.options.size = c.options.size == 0 ? cap : std::min(c.options.size, cap);
    c.options.teapot_resolution = 3;
    c.options.texture_size = std::min(c.options.texture_size, 64);
  }
  check_distinct(
      {{"--json", c.json}, {"--unit-config", c.options.unit_config}, {"--scene", c.options.scene}});
  if (c.rtl.user_rtl()) {
    if (c.rtl.pipeline.empty()) {
      throw Error("--rtl: say which pipeline your RTL implements with --pipeline (phongsim list)");
    }
    (void)find_pipeline(c.rtl.pipeline);  // Error naming an unknown one
    c.options.rtl_pipeline = c.rtl.pipeline;
    c.options.rtl = c.rtl.checked_sources();
    c.options.rtl_top = c.rtl.top;
  } else {
    (void)c.rtl.checked_sources();  // -I or -D alone
    if (!c.rtl.pipeline.empty() || !c.rtl.top.empty()) {
      throw Error(
          "--pipeline and --top name your RTL's pipeline and top: give the RTL (--rtl or -f)");
    }
  }
  (void)parse_clock(c.clock);
  // The files appear together when the render is done, or not at all; a --json inside the
  // output directory is one of them. Both are checked before anything is rendered.
  OutputSet set(c.out_dir, "", {});
  const std::optional<fs::path> json_in_set =
      c.json.empty() || c.json == "-" ? std::nullopt : inside(c.json, c.out_dir);
  std::optional<JsonOutput> json;
  if (!json_in_set) json.emplace(c.json);
  std::FILE* const text = json && json->to_stdout() ? stderr : stdout;
  const RenderResult r = render(c.options, progress_line(c.quiet));
  const std::map<std::string, Clock> clocks = unit_clocks(r, c.clock);
  set.rename(render_set_name(r), {render_set_name(r)});
  const auto files = write_render_outputs(r, set);
  nlohmann::ordered_json j = json_document("render");
  j["scene"] = r.scene;
  j["width"] = r.reference.image.width();
  j["height"] = r.reference.image.height();
  j["reference"] = r.reference.method;
  j["terms"] = terms_name(c.options.terms);
  j["texture_size"] = c.options.texture_size;
  j["texture_filter"] = texmap::filter_name(c.options.texture_filter);
  j["out"] = c.out_dir;
  j["files"] = nlohmann::ordered_json::array();
  for (const auto& f : files) j["files"].push_back((fs::path(c.out_dir) / f).string());
  j["regions"] = nlohmann::ordered_json::array();
  for (const auto& region : r.regions) j["regions"].push_back(region.first);
  j["methods"] = nlohmann::ordered_json::array();
  for (const MethodResult& m : r.results) {
    nlohmann::ordered_json method{{"method", m.method}, {"backend", backend_name(m.backend)}};
    method.update(metrics_json(m.metrics));
    method["seconds"] = m.seconds;
    method["cpu_seconds"] = m.cpu_seconds;
    if (m.frame) {
      const FrameCycles& c = m.frame->cycles;
      method["frame"] = {{"cycles", c.cycles},
                         {"pixels", m.frame->pixels},
                         {"pixels_per_clock", frame_rate(*m.frame)},
                         {"outputs", c.outputs},
                         {"fill_cycles", c.fill_cycles},
                         {"setup_cycles", c.setup_cycles},
                         {"empty_row_cycles", c.empty_row_cycles},
                         {"stall_cycles", c.stall_cycles},
                         {"clock_mhz", nullptr},
                         {"frames_per_second", nullptr},
                         {"clock", nullptr}};
      if (const auto k = clocks.find(m.frame->config); k != clocks.end()) {
        if (k->second.mhz) {
          method["frame"]["clock_mhz"] = *k->second.mhz;
          method["frame"]["frames_per_second"] = frames_per_second(*m.frame, *k->second.mhz);
        }
        method["frame"]["clock"] = k->second.note;
      }
    } else {
      method["frame"] = nullptr;
    }
    method["regions"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < r.regions.size() && i < m.region_metrics.size(); ++i) {
      nlohmann::ordered_json region{{"region", r.regions[i].first}};
      region.update(metrics_json(m.region_metrics[i]));
      method["regions"].push_back(region);
    }
    j["methods"].push_back(method);
  }
  if (json_in_set) {
    std::fputs((j.dump(2) + "\n").c_str(), set.add(*json_in_set).get());
  }
  set.commit();
  if (json) json->write(j);
  fmt::print(text, "{}: {} x {} pixels ({} object pixels), reference {} (float){}\n{}", r.scene,
             r.reference.image.width(), r.reference.image.height(), r.reference.metrics.pixels,
             r.reference.method, r.settings, metrics_markdown(r));
  fmt::print(text, "{}", frame_table(r, clocks));
  fmt::print(text, "wrote {} files to {} (grid: {})\n", files.size(), c.out_dir,
             (fs::path(c.out_dir) / (r.scene + "_grid.png")).string());
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
  add_int(*cmd, "--size", c->options.size,
          "shinyballs: sphere radius in pixels (default 64, at most 340); meshes: image width "
          "(default: the scene's)",
          1, 2048);
  add_int(*cmd, "--teapot-resolution", c->options.teapot_resolution,
          "teapot: grid cells per patch side (default 8: 4032 facets, about Vlasic's 3750)", 1,
          256);
  cmd->add_option("--reference", c->options.reference,
                  "reference method for metrics and difference images (default phong, "
                  "float)");
  add_int(*cmd, "--scanline", c->options.scanline,
          "row of the scanline illumination plot (default: the middle)", 0, 2047);
  cmd->add_option("--unit-config", c->options.unit_config,
                  "a configuration file replacing the built-in one of every unit method "
                  "that runs on its pipeline (a quad or kb configuration: the walker or one "
                  "Kuijk-Blake engine alone)");
  cmd->add_option("--terms", c->terms,
                  "lighting terms: all, or specular only (Vlasic's Table 6.1 compares those)")
      ->capture_default_str();
  add_int(*cmd, "--texture-size", c->options.texture_size,
          "texture methods: texels per side (0: the exact texture function)", 0,
          texmap::kMaxTextureSize)
      ->capture_default_str();
  cmd->add_option("--texture-filter", c->texture_filter, "texture methods: nearest or bilinear")
      ->capture_default_str();
  cmd->add_option("--out", c->out_dir,
                  "output directory (created; this scene's files there are replaced as a set)")
      ->capture_default_str();
  cmd->add_option("--json", c->json,
                  "write the results as JSON (docs/json.md: files, metrics, per-sphere metrics); "
                  "- is standard output");
  cmd->add_option("--clock-mhz", c->clock,
                  "frames per second at this clock: a frequency in MHz for every unit, or ice40: "
                  "each unit's fmax placed and routed on the iCE40 UP5K (phongsim synth --ice40, "
                  "cached), where it fits");
  cmd->add_flag("--no-build", c->options.no_build,
                "fail instead of Verilating a configuration that is not built yet");
  c->rtl.add_source_options(*cmd);
  cmd->add_option("--pipeline", c->rtl.pipeline,
                  "the pipeline your --rtl implements: it runs every unit of that pipeline "
                  "through the RTL backend (docs/your-rtl.md, \"Rendering your RTL\")");
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
