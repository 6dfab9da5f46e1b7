#include "sim/explore/sweep.h"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "base/error.h"
#include "base/file_util.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "sim/explore/spec_file.h"
#include "sim/pipelines/registry.h"
#include "sim/render/plot.h"
#include "sim/render/render.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;
using namespace explore;

std::string literal(const toml::node& n) {
  std::ostringstream s;
  if (const auto* v = n.as_string()) {
    s << toml::value<std::string>(v->get());
  } else if (const auto* i = n.as_integer()) {
    s << i->get();
  } else {
    return "";
  }
  return s.str();
}

std::string describe(const std::vector<std::pair<std::string, std::string>>& values) {
  std::string d;
  for (const auto& [k, v] : values) d += fmt::format("{}{}={}", d.empty() ? "" : ", ", k, v);
  return d;
}

std::string unquote(std::string v) {  // TOML string literals: "..." or '...'
  if (v.size() >= 2 && (v.front() == '"' || v.front() == '\'')) return v.substr(1, v.size() - 2);
  return v;
}

}  // namespace

// ---- Sweep files ----

SweepSpec load_sweep(const fs::path& file) {
  SweepSpec s;
  s.file = file;
  s.name = file.stem().string();
  const toml::table t = parse_toml(file);
  const std::set<std::string> known{"name",  "base",   "bases", "axes",
                                    "error", "scenes", "synth", "plot"};
  for (const auto& [k, v] : t) {
    if (!known.contains(std::string(k.str()))) {
      fail_at(file, v,
              fmt::format("unknown key '{}' (expected name, base or bases, [axes], [error], "
                          "[scenes], [synth], [plot])",
                          k.str()));
    }
  }
  if (const auto n = t["name"].value<std::string>()) s.name = *n;
  if (const auto b = t["base"].value<std::string>()) s.bases.push_back(resolve_path(file, *b));
  if (const auto* arr = t["bases"].as_array()) {
    for (const auto& b : *arr) {
      const auto p = b.value<std::string>();
      if (!p) fail_at(file, b, "bases: expected strings");
      s.bases.push_back(resolve_path(file, *p));
    }
  }
  if (s.bases.empty())
    throw Error(fmt::format("{}: no base configuration (base = \"...\")", file.string()));
  if (const auto* axes = t["axes"].as_table()) {
    for (const auto& [k, v] : *axes) {
      SweepAxis axis;
      axis.key = std::string(k.str());
      const auto dot = axis.key.find('.');
      const std::set<std::string> sections{"format", "mode", "param", "setup"};
      if (dot == std::string::npos || !sections.contains(axis.key.substr(0, dot))) {
        fail_at(file, v,
                fmt::format("axis '{}': expected format.<key>, mode.<key>, param.<key> "
                            "or setup.<key>",
                            axis.key));
      }
      if (const auto* arr = v.as_array()) {
        if (arr->size() > kMaxAxisValues) {
          fail_at(file, v,
                  fmt::format("axis '{}' has {} values, at most {}", axis.key, arr->size(),
                              kMaxAxisValues));
        }
        for (const auto& x : *arr) {
          const std::string lit = literal(x);
          if (lit.empty())
            fail_at(file, x, fmt::format("axis '{}': values are strings or integers", axis.key));
          axis.values.push_back(lit);
        }
      } else if (const auto* range = v.as_table()) {
        // { frac = [lo, hi] }: the base's format with lo..hi fraction bits.
        const auto* fr = (*range)["frac"].as_array();
        if (axis.key.substr(0, dot) != "format" || fr == nullptr || fr->size() != 2 ||
            !(*fr)[0].is_integer() || !(*fr)[1].is_integer() || range->size() != 1) {
          fail_at(file, v,
                  fmt::format("axis '{}': a range is {{ frac = [lo, hi] }} on a format", axis.key));
        }
        const auto lo = (*fr)[0].value<std::int64_t>().value();
        const auto hi = (*fr)[1].value<std::int64_t>().value();
        if (lo < 0 || hi > 62) {
          fail_at(file, v,
                  fmt::format("axis '{}': fraction bits {}..{} outside 0..62", axis.key, lo, hi));
        }
        const toml::table base = parse_toml(s.bases.front());
        const auto fmt_text = base["format"][axis.key.substr(dot + 1)].value<std::string>();
        if (!fmt_text) {
          fail_at(
              file, v,
              fmt::format("axis '{}': {} has no such format", axis.key, s.bases.front().string()));
        }
        const fx::Format f = fx::Format::parse(*fmt_text);
        for (std::int64_t b = lo; b <= hi; ++b) {
          axis.values.push_back(fmt::format("\"{}{}.{}\"", f.is_signed ? "S" : "", f.int_bits, b));
        }
      }
      if (axis.values.empty()) fail_at(file, v, fmt::format("axis '{}' is empty", axis.key));
      s.axes.push_back(std::move(axis));
    }
  }
  std::size_t points = s.bases.size();  // the grid, checked without overflowing
  for (const SweepAxis& a : s.axes) {
    if (points > kMaxSweepPoints) break;
    points *= a.values.size();
  }
  if (points > kMaxSweepPoints) {
    std::string sizes = fmt::format("{} base{}", s.bases.size(), s.bases.size() == 1 ? "" : "s");
    for (const SweepAxis& a : s.axes) sizes += fmt::format(" x {}", a.values.size());
    throw Error(fmt::format(
        "{}: the grid has {} points ({}), at most {}", file.string(),
        points > kMaxSweepPoints * 1000 ? std::string("too many") : std::to_string(points), sizes,
        kMaxSweepPoints));
  }
  if (const auto* e = t["error"].as_table()) {
    for (const auto& [k, v] : *e) {
      const auto n = v.value<std::int64_t>();
      if (k.str() == "samples" && n && *n >= 1) {
        if (static_cast<std::uint64_t>(*n) > kMaxSweepSamples) {
          fail_at(file, v, fmt::format("[error] samples = {}: at most {}", *n, kMaxSweepSamples));
        }
        s.samples = static_cast<std::uint64_t>(*n);
      } else if (k.str() == "seed" && n && *n >= 0) {
        s.seed = static_cast<std::uint64_t>(*n);
      } else {
        fail_at(file, v, fmt::format("[error] {}: expected samples >= 1 or seed >= 0", k.str()));
      }
    }
  }
  if (const auto* sc = t["scenes"].as_table()) {
    for (const auto& [k, v] : *sc) {
      if (k.str() == "size") {
        const auto n = v.value<std::int64_t>();
        if (!n || *n < 1 || *n > 2048) fail_at(file, v, "[scenes] size: 1..2048");
        s.scene_size = static_cast<int>(*n);
        continue;
      }
      const auto m = v.value<std::string>();
      if (!m) fail_at(file, v, fmt::format("[scenes] {}: expected a method name", k.str()));
      (void)find_method(*m);
      s.scenes.push_back({std::string(k.str()), *m});
    }
  }
  if (const auto* sy = t["synth"].as_table()) {
    for (const auto& [k, v] : *sy) {
      const auto b = v.value<bool>();
      if (k.str() == "generic" && b) {
        s.synth.generic = *b;
      } else if (k.str() == "ice40" && b) {
        s.synth.ice40 = *b;
      } else {
        fail_at(file, v,
                fmt::format("[synth] {}: expected generic or ice40 = true/false", k.str()));
      }
    }
  }
  if (const auto* pl = t["plot"].as_table()) {
    for (const auto& [k, v] : *pl) {
      const auto str = v.value<std::string>();
      if (k.str() == "variant" && str) {
        s.variant = *str;
      } else if (k.str() == "area" && str &&
                 (*str == "cells" || *str == "transistors" || *str == "lut4")) {
        s.area = *str;
      } else {
        fail_at(file, v,
                fmt::format("[plot] {}: expected variant = \"<axis>\" or area = cells, "
                            "transistors or lut4",
                            k.str()));
      }
    }
  }
  if (!s.variant.empty() && s.variant != "base" &&
      std::none_of(s.axes.begin(), s.axes.end(),
                   [&](const SweepAxis& a) { return a.key == s.variant; })) {
    throw Error(fmt::format("{}: [plot] variant '{}' is not an axis (or \"base\")", file.string(),
                            s.variant));
  }
  if (s.area == "lut4" && !s.synth.ice40) {
    throw Error(
        fmt::format("{}: [plot] area = \"lut4\" needs [synth] ice40 = true", file.string()));
  }
  if (s.area != "lut4" && (s.synth.generic || s.synth.ice40) && !s.synth.generic) {
    s.area = "lut4";
  }
  return s;
}

std::vector<SweepPoint> expand(const SweepSpec& spec) {
  std::vector<SweepPoint> points;
  std::size_t combos = 1;
  for (const auto& a : spec.axes) combos *= a.values.size();
  for (const fs::path& base : spec.bases) {
    for (std::size_t c = 0; c < combos; ++c) {
      SweepPoint p;
      p.index = points.size();
      p.base = base;
      std::size_t rest = c;
      for (std::size_t a = spec.axes.size(); a-- > 0;) {
        const auto& axis = spec.axes[a];
        p.values.insert(p.values.begin(), {axis.key, axis.values[rest % axis.values.size()]});
        rest /= axis.values.size();
      }
      const std::string origin =
          fmt::format("{} point {} ({}{}{})", spec.file.string(), p.index, base.filename().string(),
                      p.values.empty() ? "" : ": ", describe(p.values));
      try {
        p.toml = point_toml(
            base, p.values,
            fmt::format("# {} point {}: {}, {}\n", spec.name, p.index, base.string(),
                        describe(p.values)),
            fmt::format("sweep {} point {}: {}{}{}", spec.name, p.index, base.stem().string(),
                        p.values.empty() ? "" : ", ", describe(p.values)));
        const Config cfg = Config::parse(p.toml, fmt::format("point{:04}.toml", p.index));
        (void)make_model(find_pipeline(cfg.pipeline()), cfg);
      } catch (const Error& e) {
        throw Error(fmt::format("{}: {}", origin, e.what()));
      } catch (const toml::parse_error& e) {
        throw Error(fmt::format("{}: {}", origin, e.description()));
      }
      points.push_back(std::move(p));
    }
  }
  return points;
}

PointResult evaluate_point(const SweepSpec& spec, const fs::path& config, std::size_t index,
                           std::FILE* log, const SweepRtl* rtl) {
  const auto start = std::chrono::steady_clock::now();
  const Config cfg = Config::load(config);
  PointResult r;
  r.index = index;
  r.config = config.string();
  r.config_hash = content_hash(read_file(config, "point configuration"));
  const PipelineInfo& pipeline = find_pipeline(cfg.pipeline());
  (void)make_model(pipeline, cfg);  // refuses a configuration the pipeline cannot take
  r.error = pipeline.float_error(cfg, spec.samples, spec.seed);
  r.latency = pipeline.latency(cfg);
  for (const SweepScene& sc : spec.scenes) {
    const ImageMetrics m = scene_metrics(sc.scene, sc.method, spec.scene_size, config);
    r.colour_correctness.emplace_back(sc.scene, m.colour_correctness);
    r.psnr.emplace_back(sc.scene, m.psnr);
  }
  if (spec.synth.generic || spec.synth.ice40) {
    r.synth = synthesize(rtl != nullptr ? rtl_design(pipeline, cfg, rtl->sources, rtl->top)
                                        : rtl_design(pipeline, cfg),
                         cfg.origin(), spec.synth, log);
    r.synthesized = true;
  }
  if (rtl != nullptr) {
    const SweepRtl::Verdict v = rtl->verify(config);
    r.rtl = v.rtl;
    r.verified = v.passed;
    r.verification = v.summary;
    if (v.latency >= 0) r.latency = v.latency;
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

namespace {

nlohmann::json to_json(const PointResult& r) {
  nlohmann::json values = nlohmann::json::object();
  for (const auto& [k, v] : r.values) values[k] = v;
  nlohmann::json cc = nlohmann::json::object();
  for (const auto& [k, v] : r.colour_correctness) cc[k] = v;
  nlohmann::json psnr = nlohmann::json::object();
  for (const auto& [k, v] : r.psnr)
    psnr[k] = std::isinf(v) ? nlohmann::json(nullptr) : nlohmann::json(v);
  const auto count = [](std::int64_t n) {
    return n >= 0 ? nlohmann::json(n) : nlohmann::json(nullptr);
  };
  const bool ice40 = r.synth.lut4 >= 0;
  return {
      {"index", r.index},
      {"config", r.config},
      {"config_hash", r.config_hash},
      {"error",
       {{"max_lsb", r.error.max_lsb},
        {"mean_lsb", r.error.mean_lsb},
        {"max_abs", r.error.max_abs},
        {"samples", r.error.samples}}},
      {"colour_correctness", cc},
      {"psnr", psnr},
      // What was not computed (generic or iCE40 synthesis) is null.
      {"synth", r.synthesized ? nlohmann::json{{"cells", count(r.synth.cells)},
                                               {"transistors", count(r.synth.transistors)},
                                               {"depth", count(r.synth.depth)},
                                               {"lut4", count(r.synth.lut4)},
                                               {"carry", count(r.synth.carry)},
                                               {"mac16", count(r.synth.mac16)},
                                               {"ff", count(r.synth.ff)},
                                               {"fits", ice40 ? nlohmann::json(r.synth.fits)
                                                              : nlohmann::json(nullptr)},
                                               {"fmax_mhz", ice40 && r.synth.fits
                                                                ? nlohmann::json(r.synth.fmax_mhz)
                                                                : nlohmann::json(nullptr)},
                                               {"cached", r.synth.cached}}
                              : nlohmann::json(nullptr)},
      {"latency", r.latency},
      {"seconds", r.seconds},
      {"rtl", r.rtl.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.rtl)},
      {"verified", r.verified ? nlohmann::json{{"passed", *r.verified}, {"summary", r.verification}}
                              : nlohmann::json(nullptr)}};
}

PointResult from_json(const nlohmann::json& j) {
  PointResult r;
  r.index = j.at("index").get<std::size_t>();
  r.config = j.at("config").get<std::string>();
  r.config_hash = j.value("config_hash", std::string());
  r.error.max_lsb = j.at("error").at("max_lsb").get<double>();
  r.error.mean_lsb = j.at("error").at("mean_lsb").get<double>();
  r.error.max_abs = j.at("error").at("max_abs").get<double>();
  r.error.samples = j.at("error").at("samples").get<std::uint64_t>();
  for (const auto& [k, v] : j.at("colour_correctness").items())
    r.colour_correctness.emplace_back(k, v.get<double>());
  for (const auto& [k, v] : j.at("psnr").items()) {
    r.psnr.emplace_back(k, v.is_null() ? INFINITY : v.get<double>());
  }
  if (!j.at("synth").is_null()) {
    const auto& s = j.at("synth");
    const auto count = [&](const char* key) {
      return s.at(key).is_null() ? std::int64_t{-1} : s.at(key).get<std::int64_t>();
    };
    r.synthesized = true;
    r.synth.cells = count("cells");
    r.synth.transistors = count("transistors");
    r.synth.depth = s.contains("depth") ? count("depth") : -1;
    r.synth.lut4 = count("lut4");
    r.synth.carry = count("carry");
    r.synth.mac16 = count("mac16");
    r.synth.ff = count("ff");
    r.synth.fits = s.at("fits").is_null() || s.at("fits").get<bool>();
    r.synth.fmax_mhz =
        s.at("fmax_mhz").is_null() ? (r.synth.fits ? -1.0 : 0.0) : s.at("fmax_mhz").get<double>();
    r.synth.cached = s.at("cached").get<bool>();
  }
  r.latency = j.at("latency").get<int>();
  r.seconds = j.at("seconds").get<double>();
  if (j.contains("rtl") && !j.at("rtl").is_null()) r.rtl = j.at("rtl").get<std::string>();
  if (j.contains("verified") && !j.at("verified").is_null()) {
    r.verified = j.at("verified").at("passed").get<bool>();
    r.verification = j.at("verified").at("summary").get<std::string>();
  }
  return r;
}

fs::path point_file(std::size_t i) { return fs::path("points") / fmt::format("{:04}.toml", i); }
fs::path result_file(std::size_t i) { return fs::path("results") / fmt::format("{:04}.json", i); }

double area_of(const SweepSpec& spec, const PointResult& r) {
  if (!r.synthesized) return NAN;
  const std::int64_t a = spec.area == "transistors" ? r.synth.transistors
                         : spec.area == "lut4"      ? r.synth.lut4
                                                    : r.synth.cells;
  return a < 0 ? NAN : static_cast<double>(a);
}

// "lirp/default": the base's folder (the pipeline's, for configs/) and name.
std::string base_name(const fs::path& base) {
  return base.parent_path().filename().string() + "/" + base.stem().string();
}

}  // namespace

std::string content_hash(const std::string& text) {
  ContentHash h;
  h.add(text);
  return h.hex();
}

std::string point_result_json(const PointResult& r) { return to_json(r).dump(2) + "\n"; }

void write_point_result(const PointResult& r, const fs::path& path) {
  write_text(path, point_result_json(r));
}

std::vector<SweepPoint> plan_sweep(const SweepSpec& spec, const fs::path& out,
                                   const SweepRtl* rtl) {
  const std::vector<SweepPoint> points = expand(spec);
  // The plan appears whole or not at all; planning again replaces the plan and what was merged
  // from the old one.
  OutputSet set(out, "sweep plan", {"sweep plan", "sweep merge"});
  const fs::path exe = fs::canonical("/proc/self/exe");
  const fs::path sweep = fs::absolute(spec.file);
  const fs::path dir = fs::absolute(out);
  std::string jobs;
  std::string make = "# make -j<N> -f Makefile: every point of the sweep, then merge\nall:";
  std::string rules;
  for (const SweepPoint& p : points) {
    std::fputs(p.toml.c_str(), set.add(point_file(p.index)).get());
    const std::string cmd =
        fmt::format("{} sweep point {} --sweep {} --index {} --out {}{}", exe.string(),
                    (dir / point_file(p.index)).string(), sweep.string(), p.index,
                    (dir / result_file(p.index)).string(), rtl != nullptr ? rtl->options : "");
    jobs += cmd + "\n";
    make += fmt::format(" results/{:04}.json", p.index);
    rules += fmt::format("results/{:04}.json:\n\t{}\n", p.index, cmd);
  }
  make += fmt::format("\n\t{} sweep merge {} --out {}\n{}", exe.string(), sweep.string(),
                      dir.string(), rules);
  std::fputs(jobs.c_str(), set.add("jobs.txt").get());
  std::fputs(make.c_str(), set.add("Makefile").get());
  set.commit();
  std::error_code ec;
  fs::create_directories(out / "results", ec);
  if (ec)
    throw Error(fmt::format("cannot create {}: {}", (out / "results").string(), ec.message()));
  return points;
}

bool on_pareto_front(const SweepSpec& spec, const PointResult& a,
                     const std::vector<PointResult>& results) {
  const double aa = area_of(spec, a);
  if (std::isnan(aa)) return false;
  return std::none_of(results.begin(), results.end(), [&](const PointResult& b) {
    const double ab = area_of(spec, b);
    return !std::isnan(ab) && ab <= aa && b.error.max_abs <= a.error.max_abs &&
           (ab < aa || b.error.max_abs < a.error.max_abs);
  });
}

std::vector<PointResult> merge_sweep(const SweepSpec& spec, const fs::path& out) {
  const std::vector<SweepPoint> points = expand(spec);
  std::vector<PointResult> results;
  for (const SweepPoint& p : points) {
    // The plan in `out` must be this sweep's: same point files, results made from them.
    const fs::path pp = out / point_file(p.index);
    if (!fs::exists(pp)) {
      throw Error(
          fmt::format("{} holds no plan of {} ({} is missing): run phongsim sweep plan "
                      "first",
                      out.string(), spec.file.string(), pp.string()));
    }
    const std::string planned = read_file(pp);
    if (planned != p.toml) {
      throw Error(
          fmt::format("{} is not point {} of {} ({}): plan the sweep again into an empty "
                      "directory",
                      pp.string(), p.index, spec.file.string(), describe(p.values)));
    }
    const fs::path rp = out / result_file(p.index);
    if (!fs::exists(rp)) {
      throw Error(fmt::format("point {} ({}) has no result yet: {}", p.index, describe(p.values),
                              rp.string()));
    }
    std::ifstream in(rp);
    PointResult r;
    try {
      r = from_json(nlohmann::json::parse(in));
    } catch (const std::exception& e) {
      throw Error(fmt::format("{}: {}", rp.string(), e.what()));
    }
    if (fs::weakly_canonical(r.config) != fs::weakly_canonical(pp)) {
      throw Error(
          fmt::format("{} was computed from {}, not from {}", rp.string(), r.config, pp.string()));
    }
    if (r.config_hash != content_hash(planned)) {
      throw Error(
          fmt::format("{} was computed from another version of {}: run point {} again (its line in "
                      "jobs.txt)",
                      rp.string(), pp.string(), p.index));
    }
    r.values = p.values;
    r.base = p.base.string();
    results.push_back(std::move(r));
  }
  // One design: the user's (the same in every result) or phongsim's.
  for (const PointResult& r : results) {
    if (r.rtl != results.front().rtl) {
      throw Error(fmt::format(
          "point {} was evaluated with {}, point {} with {}: run the sweep again with one design",
          results.front().index,
          results.front().rtl.empty() ? "phongsim's RTL" : results.front().rtl, r.index,
          r.rtl.empty() ? "phongsim's RTL" : r.rtl));
    }
  }
  const bool user_rtl = !results.empty() && !results.front().rtl.empty();
  const bool synth = spec.synth.generic || spec.synth.ice40;
  std::vector<bool> pareto;
  for (const PointResult& r : results) pareto.push_back(on_pareto_front(spec, r, results));

  // CSV: what was not computed is an empty cell.
  const auto count = [](std::int64_t n) { return n >= 0 ? std::to_string(n) : std::string(); };
  std::string csv = "index,pipeline,base";
  for (const auto& a : spec.axes) csv += "," + a.key;
  csv += ",max_error_lsb,mean_error_lsb,max_error_abs";
  for (const auto& sc : spec.scenes) csv += fmt::format(",cc_{0},psnr_{0}", sc.scene);
  csv += ",cells,transistors,depth,lut4,carry,mac16,ff,ice40_fits,fmax_mhz,latency,pareto";
  csv += user_rtl ? ",rtl_passed\n" : "\n";
  for (std::size_t k = 0; k < results.size(); ++k) {
    const PointResult& r = results[k];
    const Config cfg = Config::load(out / point_file(r.index));
    csv += fmt::format("{},{},{}", r.index, cfg.pipeline(), base_name(r.base));
    for (const auto& v : r.values) csv += fmt::format(",{}", unquote(v.second));
    csv += fmt::format(",{:.6g},{:.6g},{:.6g}", r.error.max_lsb, r.error.mean_lsb, r.error.max_abs);
    for (std::size_t i = 0; i < r.colour_correctness.size(); ++i) {
      csv += fmt::format(",{:.6f},{}", r.colour_correctness[i].second,
                         std::isfinite(r.psnr[i].second) ? fmt::format("{:.3f}", r.psnr[i].second)
                                                         : std::string("inf"));
    }
    const bool generic = r.synthesized && spec.synth.generic;
    const bool ice40 = r.synthesized && spec.synth.ice40 && r.synth.lut4 >= 0;
    csv +=
        fmt::format(",{},{},{}", generic ? count(r.synth.cells) : "",
                    generic ? count(r.synth.transistors) : "", generic ? count(r.synth.depth) : "");
    csv += fmt::format(",{},{},{},{},{},{}", ice40 ? count(r.synth.lut4) : "",
                       ice40 ? count(r.synth.carry) : "", ice40 ? count(r.synth.mac16) : "",
                       ice40 ? count(r.synth.ff) : "", ice40 ? (r.synth.fits ? "1" : "0") : "",
                       ice40 && r.synth.fits ? fmt::format("{:.2f}", r.synth.fmax_mhz) : "");
    csv += fmt::format(",{},{}", r.latency, synth ? (pareto[k] ? "1" : "0") : "");
    csv += user_rtl ? fmt::format(",{}\n", r.verified.value_or(false) ? 1 : 0) : "\n";
  }
  OutputSet set(out, "sweep merge", {"sweep merge"});
  std::fputs(csv.c_str(), set.add("sweep.csv").get());

  std::string md =
      fmt::format("# Sweep {}\n\n`{}`: {} points, error over {} samples (seed {})\n\n", spec.name,
                  spec.file.string(), results.size(), spec.samples, spec.seed);
  if (user_rtl) {
    const std::string failed = failed_points(results);
    md += fmt::format("RTL: {}; {}{}\n\n", results.front().rtl,
                      spec.synth.generic || spec.synth.ice40 ? "synthesized and " : "",
                      failed.empty() ? "co-simulated at every point: all pass" : failed);
  }
  md += "| # | base |";
  std::string rule = "|---|---|";
  for (const auto& a : spec.axes) {
    md += " " + a.key + " |";
    rule += "---|";
  }
  md += " max err (LSB) | mean err (LSB) |";
  rule += "---|---|";
  for (const auto& sc : spec.scenes) {
    md += fmt::format(" cc {} |", sc.scene);
    rule += "---|";
  }
  if (spec.synth.generic) {
    md += " cells | transistors | depth |";
    rule += "---|---|---|";
  }
  if (spec.synth.ice40) {
    md += " LUT4 | carry | MAC16 | fmax (MHz) |";
    rule += "---|---|---|---|";
  }
  md += " latency |";
  rule += "---|";
  if (synth) {
    md += " Pareto |";
    rule += "---|";
  }
  if (user_rtl) {
    md += " RTL |";
    rule += "---|";
  }
  md += "\n" + rule + "\n";
  for (std::size_t k = 0; k < results.size(); ++k) {
    const PointResult& r = results[k];
    md += fmt::format("| {} | {} |", r.index, fs::path(r.base).stem().string());
    for (const auto& v : r.values) md += fmt::format(" {} |", unquote(v.second));
    md += fmt::format(" {:.4g} | {:.4g} |", r.error.max_lsb, r.error.mean_lsb);
    for (const auto& c : r.colour_correctness) md += fmt::format(" {:.4f} |", c.second);
    if (spec.synth.generic) {
      md += fmt::format(" {} | {} | {} |", r.synth.cells, r.synth.transistors, r.synth.depth);
    }
    if (spec.synth.ice40) {
      md += fmt::format(" {} | {} | {} | {} |", r.synth.lut4, r.synth.carry, r.synth.mac16,
                        r.synth.fits ? fmt::format("{:.1f}", r.synth.fmax_mhz) : "does not fit");
    }
    md += fmt::format(" {} |", r.latency);
    if (synth) md += pareto[k] ? " yes |" : " |";
    if (user_rtl) md += r.verified.value_or(false) ? " PASS |" : " FAIL |";
    md += "\n";
  }
  std::fputs(md.c_str(), set.add("summary.md").get());

  if (synth) {
    // pareto.csv (the figure's data) and pareto.png (scripts/plot.py pareto): error against
    // area, one series per variant, the front drawn and its points labelled "#<index> ...".
    const auto axis_name = [](const std::string& key) { return key.substr(key.rfind('.') + 1); };
    std::string data = "series,label,area,max_error,pareto\n";
    for (std::size_t k = 0; k < results.size(); ++k) {
      const PointResult& r = results[k];
      const double area = area_of(spec, r);
      if (!std::isfinite(area)) continue;
      std::string series = "all points";
      if (spec.variant == "base") {
        series = base_name(r.base);
      } else if (!spec.variant.empty()) {
        for (const auto& v : r.values) {
          if (v.first == spec.variant) series = axis_name(v.first) + " = " + unquote(v.second);
        }
      }
      std::string label = fmt::format("#{}", r.index);
      if (spec.bases.size() > 1 && spec.variant != "base") label += " " + base_name(r.base);
      for (const auto& v : r.values)
        label += fmt::format(" {}={}", axis_name(v.first), unquote(v.second));
      // The CSV has no quoting: keep commas out of the names.
      std::replace(series.begin(), series.end(), ',', ';');
      std::replace(label.begin(), label.end(), ',', ';');
      data +=
          fmt::format("{},{},{},{},{}\n", series, label, area, r.error.max_abs, pareto[k] ? 1 : 0);
    }
    OutputFile& pareto_csv = set.add("pareto.csv");
    std::fputs(data.c_str(), pareto_csv.get());
    std::fflush(pareto_csv.get());
    const std::string area_caption = spec.area == "transistors"
                                         ? "area: transistors (Yosys stat -tech cmos)"
                                     : spec.area == "lut4" ? "area: iCE40 LUT4s (synth_ice40)"
                                                           : "area: cells (Yosys generic synth)";
    plot_figure("pareto",
                {"--csv", pareto_csv.temp_path().string(), "--title",
                 fmt::format("{}: max error against area", spec.name), "--x-label", area_caption,
                 "--y-label", "max |error| against the float reference (output units)"},
                set.add("pareto.png"));
  }
  set.commit();
  return results;
}

std::vector<PointResult> run_sweep(const SweepSpec& spec, const fs::path& out,
                                   const std::function<void(std::size_t, std::size_t)>& progress,
                                   std::FILE* log, const SweepRtl* rtl) {
  const std::vector<SweepPoint> points = plan_sweep(spec, out, rtl);
  for (const SweepPoint& p : points) {
    progress(p.index, points.size());
    PointResult r = evaluate_point(spec, out / point_file(p.index), p.index, log, rtl);
    write_point_result(r, out / result_file(p.index));
  }
  progress(points.size(), points.size());
  return merge_sweep(spec, out);
}

std::string failed_points(const std::vector<PointResult>& results) {
  std::vector<std::string> failed;
  for (const PointResult& r : results) {
    if (r.verified && !*r.verified) failed.push_back(fmt::format("{:04}", r.index));
  }
  if (failed.empty()) return "";
  return fmt::format("{} of {} points fail co-simulation: {}", failed.size(), results.size(),
                     fmt::join(failed, ", "));
}

}  // namespace phongsim
