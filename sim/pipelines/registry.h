// The registry of pipelines the tools know: how to build each one's model from a configuration
// and its directed stimulus. Adding a pipeline = one entry here (docs/architecture.md).
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/stimulus.h"

namespace phongsim {

struct PipelineInfo {
  std::string_view name;     // as in --pipeline and configs/<name>/
  std::string_view summary;  // one line for --help
  // Builds the model, refusing configurations that are incomplete, have unknown keys, or whose
  // intermediates would not fit the model's integers (Error naming the config file).
  std::unique_ptr<PipelineModel> (*make_model)(const Config& cfg);
  // Directed corner vectors plus seeded random vectors for this pipeline.
  Stimulus (*make_stimulus)(const PipelineModel& model, const Config& cfg);
  // True when every output depends only on its own input vector, so one vector can be re-run
  // alone (--vector-index); false for pipelines with state between vectors.
  bool independent_vectors;
};

[[nodiscard]] std::span<const PipelineInfo> pipelines();

// Throws Error listing the known pipelines when `name` is not one of them.
[[nodiscard]] const PipelineInfo& find_pipeline(std::string_view name);

// Loads `cfg` for `pipeline`: checks that the file's `pipeline` key matches and builds the model.
[[nodiscard]] std::unique_ptr<PipelineModel> make_model(const PipelineInfo& pipeline,
                                                        const Config& cfg);

}  // namespace phongsim
