#include "sim/pipelines/registry.h"

#include <fmt/format.h>

#include <algorithm>

#include "base/error.h"
#include "base/paths.h"
#include "sim/pipelines/kb.h"
#include "sim/pipelines/lirp.h"
#include "sim/pipelines/lyon.h"
#include "sim/pipelines/quad.h"
#include "sim/pipelines/shade_kb.h"
#include "sim/pipelines/shade_lyon.h"
#include "sim/pipelines/shade_quad.h"

namespace phongsim {

std::span<const PipelineInfo> pipelines() {
  static const std::vector<PipelineInfo> all{
      lirp_pipeline(),       lyon_pipeline(),       kb_pipeline(),      quad_pipeline(),
      shade_lyon_pipeline(), shade_quad_pipeline(), shade_kb_pipeline()};
  return all;
}

const PipelineInfo& find_pipeline(std::string_view name) {
  for (const auto& p : pipelines()) {
    if (p.name == name) return p;
  }
  std::string known;
  for (const auto& p : pipelines()) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw Error(fmt::format("unknown pipeline '{}' (known: {})", name, known));
}

std::unique_ptr<PipelineModel> make_model(const PipelineInfo& pipeline, const Config& cfg) {
  if (cfg.pipeline() != pipeline.name) {
    throw Error(fmt::format("{}: configures pipeline '{}', not '{}'", cfg.origin(), cfg.pipeline(),
                            pipeline.name));
  }
  return pipeline.make_model(cfg);
}

std::vector<std::filesystem::path> pipeline_configs(const PipelineInfo& pipeline) {
  const std::filesystem::path dir = data_root() / "configs" / pipeline.name;
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir)) {
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() == ".toml") files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

RtlDesign rtl_design(const PipelineInfo& pipeline, const Config& cfg,
                     std::vector<std::filesystem::path> files, std::string top) {
  RtlDesign d;
  d.name = std::string(pipeline.name);
  d.builtin_top = std::string(pipeline.top);
  d.config = cfg.name();
  d.top = top.empty() ? d.builtin_top : std::move(top);
  if (files.empty()) {
    for (const auto f : pipeline.rtl_files) files.push_back(data_root() / f);
  }
  d.files = rtl_files(files);
  d.params = cfg.rtl_parameters();
  d.ports = pipeline.ports;
  return d;
}

RtlDesign rtl_design(const PipelineInfo& pipeline, const Config& cfg, const RtlSources& sources,
                     std::string top) {
  RtlDesign d = rtl_design(pipeline, cfg, sources.files, std::move(top));
  d.include_dirs = sources.include_dirs;
  d.defines = sources.defines;
  return d;
}

}  // namespace phongsim
