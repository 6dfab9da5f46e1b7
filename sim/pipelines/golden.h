// phongsim as a library: the golden model of one pipeline configuration, for your own
// testbenches (C++, through find_package(phongsim)) and scripts (the Python module wraps this).
// docs/library.md shows both with examples.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/cosim.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

class GoldenModel {
 public:
  // A configuration file (configs/<pipeline>/<name>.toml or yours). Error naming the problem.
  explicit GoldenModel(const std::filesystem::path& config);
  // A configuration given as TOML text; `origin` names it in messages and gives its name.
  static GoldenModel from_toml(std::string_view text, const std::string& origin);

  [[nodiscard]] const PipelineInfo& pipeline() const { return *pipeline_; }
  [[nodiscard]] const Config& config() const { return cfg_; }
  [[nodiscard]] const std::vector<Field>& inputs() const { return model_->inputs(); }
  [[nodiscard]] const std::vector<Field>& outputs() const { return model_->outputs(); }

  // The outputs one input vector produces (raw values in inputs() order in; outputs() order out,
  // flattened: zero or more output transactions). Stateful pipelines (kb) carry their state from
  // one call to the next; reset() starts over.
  [[nodiscard]] std::vector<std::int64_t> eval(std::span<const std::int64_t> in);
  // Many vectors, row-major (inputs().size() values each): every output, row-major.
  [[nodiscard]] std::vector<std::int64_t> eval_batch(std::span<const std::int64_t> rows);
  void reset() { model_->reset(); }

  // Every stage value one input vector goes through, named as in the RTL and the pipeline's spec
  // (for debugging a mismatch stage by stage). Evaluates the vector like eval().
  [[nodiscard]] std::vector<StageValue> stages(std::span<const std::int64_t> in);

  // The co-simulation stimulus: directed corners, then seeded random vectors.
  [[nodiscard]] Stimulus stimulus() const;

  // phongsim's RTL for this configuration, or yours (files and folders; top: the built-in name).
  [[nodiscard]] RtlDesign rtl_design(std::vector<std::filesystem::path> files = {},
                                     std::string top = {}) const;
  // DUTs of `design`: built on demand (or refused under RtlBuild::never) into the content-keyed
  // cache; `label` (optional) receives what to call it in a summary.
  [[nodiscard]] DutFactory rtl(const RtlDesign& design, RtlBuild policy, std::FILE* log,
                               std::string* label = nullptr);

  [[nodiscard]] PipelineModel& model() { return *model_; }

 private:
  explicit GoldenModel(Config cfg);
  Config cfg_;
  const PipelineInfo* pipeline_ = nullptr;
  std::shared_ptr<PipelineModel> model_;
};

}  // namespace phongsim
