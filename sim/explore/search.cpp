#include "sim/explore/search.h"

#include <fmt/format.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "base/error.h"
#include "base/temporaries.h"
#include "sim/explore/spec_file.h"
#include "sim/pipelines/registry.h"
#include "sim/render/render.h"

namespace phongsim {

namespace fs = std::filesystem;
using namespace explore;

SearchSpec load_search(const fs::path& file) {
  SearchSpec s;
  s.file = file;
  s.name = file.stem().string();
  const toml::table t = parse_toml(file);
  for (const auto& [k, v] : t) {
    const std::string key(k.str());
    if (key == "name" && v.is_string()) {
      s.name = *v.value<std::string>();
      // It names the found configuration's file: a name, never a path elsewhere.
      if (s.name.empty() || s.name == "." || s.name == ".." ||
          s.name.find_first_of("/\\") != std::string::npos ||
          std::any_of(s.name.begin(), s.name.end(),
                      [](char c) { return static_cast<unsigned char>(c) < 0x20; })) {
        fail_at(file, v,
                fmt::format("name '{}': a file name (no folders), e.g. \"min_4lsb\"", s.name));
      }
    } else if (key == "base" && v.is_string()) {
      s.base = resolve_path(file, *v.value<std::string>());
    } else if (key == "signals" && v.is_array()) {
      for (const auto& x : *v.as_array()) {
        if (!x.is_string()) fail_at(file, x, "signals: expected [format] key names");
        s.signals.push_back(*x.value<std::string>());
      }
    } else if (key == "min_frac" && v.is_integer() && *v.value<std::int64_t>() >= 0 &&
               *v.value<std::int64_t>() <= 62) {
      s.min_frac = static_cast<int>(*v.value<std::int64_t>());
    } else if (key == "max_lsb" && (v.is_floating_point() || v.is_integer()) &&
               *v.value<double>() > 0) {
      s.max_lsb = *v.value<double>();
    } else if (key == "min_colour_correctness" && (v.is_floating_point() || v.is_integer()) &&
               *v.value<double>() > 0 && *v.value<double>() <= 1) {
      s.min_colour_correctness = *v.value<double>();
    } else if (key == "scene" && v.is_string()) {
      s.scene = *v.value<std::string>();
    } else if (key == "method" && v.is_string()) {
      s.method = *v.value<std::string>();
    } else if (key == "scene_size" && v.is_integer() && *v.value<std::int64_t>() >= 1 &&
               *v.value<std::int64_t>() <= 2048) {
      s.scene_size = static_cast<int>(*v.value<std::int64_t>());
    } else if (key == "samples" && v.is_integer() && *v.value<std::int64_t>() >= 1) {
      if (static_cast<std::uint64_t>(*v.value<std::int64_t>()) > kMaxSearchSamples) {
        fail_at(
            file, v,
            fmt::format("samples = {}: at most {}", *v.value<std::int64_t>(), kMaxSearchSamples));
      }
      s.samples = static_cast<std::uint64_t>(*v.value<std::int64_t>());
    } else if (key == "seed" && v.is_integer() && *v.value<std::int64_t>() >= 0) {
      s.seed = static_cast<std::uint64_t>(*v.value<std::int64_t>());
    } else if (key == "verify_vectors" && v.is_integer() && *v.value<std::int64_t>() >= 1) {
      if (static_cast<std::uint64_t>(*v.value<std::int64_t>()) > kMaxVerifyVectors) {
        fail_at(file, v,
                fmt::format("verify_vectors = {}: at most {}", *v.value<std::int64_t>(),
                            kMaxVerifyVectors));
      }
      s.verify_vectors = static_cast<std::uint64_t>(*v.value<std::int64_t>());
    } else {
      fail_at(file, v,
              fmt::format("unexpected '{}' (expected name, base, signals, min_frac 0..62, "
                          "max_lsb > 0, min_colour_correctness in (0, 1], scene, method, "
                          "scene_size, samples, seed, verify_vectors)",
                          key));
    }
  }
  if (s.base.empty()) throw Error(fmt::format("{}: no base configuration", file.string()));
  if (std::isinf(s.max_lsb) && s.min_colour_correctness == 0) {
    throw Error(fmt::format("{}: no budget (max_lsb or min_colour_correctness)", file.string()));
  }
  if (s.min_colour_correctness > 0) {
    if (s.scene.empty() || s.method.empty()) {
      throw Error(fmt::format("{}: min_colour_correctness needs scene and method", file.string()));
    }
    const std::string pipeline = Config::load(s.base).pipeline();
    if (!method_runs_on(s.method, pipeline)) {
      throw Error(fmt::format("{}: method '{}' does not run on a {} unit", file.string(), s.method,
                              pipeline));
    }
  }
  if (s.signals.empty()) throw Error(fmt::format("{}: no signals to narrow", file.string()));
  if (s.signals.size() > kMaxSearchSignals) {
    throw Error(fmt::format("{}: {} signals, at most {}", file.string(), s.signals.size(),
                            kMaxSearchSignals));
  }
  const toml::table base = parse_toml(s.base);
  for (const auto& sig : s.signals) {
    if (!base["format"][sig].is_string()) {
      throw Error(fmt::format("{}: signal '{}' is not a [format] key of {}", file.string(), sig,
                              s.base.string()));
    }
  }
  return s;
}

SearchResult search_min_width(const SearchSpec& spec,
                              const std::function<void(std::string_view)>& note,
                              const std::function<void(std::size_t)>& progress) {
  const toml::table base = parse_toml(spec.base);
  std::map<std::string, fx::Format> formats;
  for (const auto& sig : spec.signals)
    formats[sig] = fx::Format::parse(*base["format"][sig].value<std::string>());
  SearchResult result;
  const auto candidate = [&](const std::map<std::string, fx::Format>& f) {
    std::vector<std::pair<std::string, std::string>> values;
    for (const auto& sig : spec.signals)
      values.emplace_back("format." + sig, fmt::format("\"{}\"", f.at(sig).str()));
    return values;
  };
  // Candidates are files (the renderer loads them): in a directory of their own.
  const TempDir scratch("search");
  const fs::path dir = scratch.path();
  struct Evaluation {
    ModelError error;
    double cc = NAN;
    [[nodiscard]] std::string str() const {
      return std::isnan(cc) ? fmt::format("max error {:.4g} LSB", error.max_lsb)
                            : fmt::format("max error {:.4g} LSB, colour correctness {:.5f}",
                                          error.max_lsb, cc);
    }
  };
  // Evaluates a candidate, or nothing when the pipeline refuses it.
  const auto try_formats =
      [&](const std::map<std::string, fx::Format>& f) -> std::optional<Evaluation> {
    ++result.evaluations;
    if (progress) progress(result.evaluations);
    try {
      const fs::path file = dir / (spec.name + ".toml");
      write_text(file, point_toml(spec.base, candidate(f), "", ""));
      const Config cfg = Config::load(file);
      const PipelineInfo& pipeline = find_pipeline(cfg.pipeline());
      (void)make_model(pipeline, cfg);
      Evaluation e{pipeline.float_error(cfg, spec.samples, spec.seed)};
      if (spec.min_colour_correctness > 0) {
        e.cc = scene_metrics(spec.scene, spec.method, spec.scene_size, file).colour_correctness;
      }
      return e;
    } catch (const Error&) {
      return std::nullopt;
    }
  };
  const auto within = [&](const Evaluation& e) {
    return e.error.max_lsb <= spec.max_lsb &&
           (std::isnan(e.cc) || e.cc >= spec.min_colour_correctness);
  };
  const auto first = try_formats(formats);
  if (!first)
    throw Error(fmt::format("{}: the base configuration does not evaluate", spec.file.string()));
  if (!within(*first)) {
    throw Error(fmt::format("{}: the base already misses the budget ({})", spec.file.string(),
                            first->str()));
  }
  result.error = first->error;
  result.colour_correctness = first->cc;
  note(fmt::format("base: {}", first->str()));
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& sig : spec.signals) {
      while (formats[sig].frac_bits > spec.min_frac) {
        auto next = formats;
        next[sig].frac_bits -= 1;
        const auto e = try_formats(next);
        if (!e || !within(*e)) break;
        formats = next;
        result.error = e->error;
        result.colour_correctness = e->cc;
        ++result.bits_saved;
        changed = true;
        note(fmt::format("{} -> {}: {}", sig, formats[sig].str(), e->str()));
      }
    }
  }
  for (const auto& sig : spec.signals) result.formats.emplace_back(sig, formats[sig].str());
  std::string values;
  for (const auto& [k, v] : result.formats)
    values += fmt::format("{}{} = {}", values.empty() ? "" : ", ", k, v);
  result.toml = point_toml(
      spec.base, candidate(formats),
      fmt::format("# Found by `phongsim sweep search {}`: the narrowest fraction "
                  "bits of {} within the budget ({} samples, seed {}).\n"
                  "# Base {}; {}; max error {:.4g} LSB{}.\n",
                  spec.file.filename().string(), fmt::join(spec.signals, ", "), spec.samples,
                  spec.seed, spec.base.filename().string(), values, result.error.max_lsb,
                  std::isnan(result.colour_correctness)
                      ? ""
                      : fmt::format(", colour correctness {:.5f} on {} ({})",
                                    result.colour_correctness, spec.scene, spec.method)),
      fmt::format("found by search {}: max error {:.4g} LSB", spec.name, result.error.max_lsb));
  return result;
}

}  // namespace phongsim
