// The registry of pipelines: everything phongsim knows about a pipeline besides its RTL, model,
// configurations and spec lives in its entry, sim/pipelines/<name>.cpp. Nothing outside
// sim/pipelines/ names a pipeline or casts to its model; adding one is docs/architecture.md's
// short list.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/contract.h"
#include "sim/cosim/coverpoints.h"
#include "sim/cosim/frame_cycles.h"
#include "sim/cosim/report.h"
#include "sim/cosim/rtl_args.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/stimulus.h"

namespace phongsim {

// The model against the pipeline's float reference on random in-range inputs (the reference sees
// the exact reals, the model their quantization), in LSBs of the output format (Lyon: its spec
// output) and absolutely.
struct ModelError {
  double max_lsb = 0;
  double mean_lsb = 0;
  double max_abs = 0;
  std::uint64_t samples = 0;  // outputs compared
};

// A ModelError built up one compared output at a time.
class ErrorTally {
 public:
  // One output `abs_error` off, in a format whose LSB is `lsb`.
  void add(double abs_error, double lsb) {
    e_.max_abs = std::max(e_.max_abs, abs_error);
    e_.max_lsb = std::max(e_.max_lsb, abs_error / lsb);
    sum_lsb_ += abs_error / lsb;
    ++e_.samples;
  }
  [[nodiscard]] std::uint64_t samples() const { return e_.samples; }
  [[nodiscard]] ModelError result() const {
    ModelError e = e_;
    e.mean_lsb = e.samples == 0 ? 0 : sum_lsb_ / static_cast<double>(e.samples);
    return e;
  }

 private:
  ModelError e_;
  double sum_lsb_ = 0;
};

// A deliberate RTL bug that co-simulation must catch: `from` (which must occur exactly once in
// `file`) replaced by `to`, co-simulated with configs/<pipeline>/<config>.toml.
struct Mutant {
  std::string_view name;
  std::string_view config;
  std::string_view file;  // relative to the tree, e.g. "rtl/common/fx_resize.sv"
  std::string_view from;
  std::string_view to;
  std::string_view breaks;  // what it breaks, one line
  // When set: text the failure report must contain (a mutant only an assertion can see).
  std::string_view report = {};
};

struct PipelineInfo {
  std::string_view name;     // as in --pipeline and configs/<name>/
  std::string_view summary;  // one line for listings

  // ---- RTL: the port contract a design of this pipeline implements (docs/<name>.md) ----
  std::string_view top;  // top module of rtl/
  // Relative to the tree; a folder stands for its *.sv files (rtl_files(): packages first).
  std::vector<std::string_view> rtl_files;
  std::vector<PortBinding> ports;  // data ports besides the stream handshake

  // ---- model ----
  // Builds the model, refusing configurations that are incomplete, have unknown keys, or whose
  // intermediates would not fit the model's integers (Error naming the config file).
  std::unique_ptr<PipelineModel> (*make_model)(const Config& cfg);
  // Directed corner vectors plus seeded random vectors.
  Stimulus (*make_stimulus)(const PipelineModel& model, const Config& cfg);
  // True when every output depends only on its own input vector, so one vector can be re-run
  // alone; false for pipelines with state between vectors.
  bool independent_vectors;
  // Random vectors of a default co-simulation: about a million outputs.
  std::uint64_t default_vectors;
  // Cycles from an input's handshake to its first output in phongsim's RTL, stall-free (depends
  // on [param] only). The test suite checks it against what the harness measures; other RTL
  // (--rtl) may take longer.
  int (*latency)(const Config& cfg);
  // True when phongsim's RTL takes one input and gives one output per clock, stall-free.
  bool one_per_clock;
  // The cycle model: the stall-free FrameCycles of the stream `in` through phongsim's RTL from
  // reset, from the stream and the model's outputs for it (`out`; `counts`: each vector's
  // number of outputs) — what the RTL measures, exactly (tests/pipeline_test.cpp), without it.
  // `per_vector` (may be null) gets each vector's own cycles, fill excluded (a span's header word
  // carries the span's; a triangle program its rows, its pixels and the cycle that loads it).
  FrameCycles (*cycles)(const Config& cfg, std::span<const std::int64_t> in,
                        std::span<const std::int64_t> out, std::span<const std::uint32_t> counts,
                        std::vector<FrameCycles>* per_vector);
  // Every stage value of one input vector (evaluated like eval(): stateful models advance).
  std::vector<StageValue> (*stages)(PipelineModel& model, std::span<const std::int64_t> in);
  // The functional coverpoints of `cfg` (sim/cosim/coverpoints.h, docs/verification.md): each
  // requantization saturating low, high and not, and the pipeline's corner events, declared for
  // what the configuration uses and counted on the model, vector by vector. `phongsim cosim
  // --coverage` counts them over its runs; tests/coverpoint_test.cpp checks that the stimulus
  // hits every one.
  CoverpointSampler (*coverpoints)(const PipelineModel& model, const Config& cfg);

  // A hand-written kernel of configs/<name>/default.toml, its widths and modes as constants (no
  // runtime formats): `phongsim bench`'s yardstick for the model, run on every configuration with
  // the default's RTL parameters and checked bit-identical to the model there. The contract of
  // PipelineModel::eval_batch (vectors back to back in, every output appended), from the reset
  // state.
  std::size_t (*native)(std::span<const std::int64_t> in, std::vector<std::int64_t>& out);

  // ---- accuracy ----
  // The input contract of `cfg` (docs/<name>.md, "Input contract"): the domain on which the
  // accuracy claims below and in the spec hold, as named clauses in the order they are checked
  // and a check returning the first clause a vector breaks (sim/cosim/contract.h). Stateful
  // pipelines check each word in stream order from reset. `eval` and `cosim` count vectors
  // against it; `analyze` measures accuracy inside it and the worst behaviour outside.
  InputContract (*contract)(const PipelineModel& model, const Config& cfg);

  ModelError (*float_error)(const Config& cfg, std::uint64_t samples, std::uint64_t seed);
  // `phongsim analyze <name>`: the approximations and fixed-point error of `configs`, as text
  // and, for JSON, its tables (sim/cosim/report.h).
  void (*analyze)(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
                  AnalysisReport& out);

  std::vector<Mutant> mutants;
};

// PipelineInfo::cycles of a pipeline whose RTL takes one vector per clock, `Latency` cycles deep.
template <int (*Latency)(const Config&)>
FrameCycles one_per_clock(const Config& cfg, std::span<const std::int64_t>,
                          std::span<const std::int64_t>, std::span<const std::uint32_t> counts,
                          std::vector<FrameCycles>* per_vector) {
  return one_per_clock_cycles(Latency(cfg), counts.size(), per_vector);
}

[[nodiscard]] std::span<const PipelineInfo> pipelines();

// Throws Error listing the known pipelines when `name` is not one of them.
[[nodiscard]] const PipelineInfo& find_pipeline(std::string_view name);

// Loads `cfg` for `pipeline`: checks that the file's `pipeline` key matches and builds the model.
[[nodiscard]] std::unique_ptr<PipelineModel> make_model(const PipelineInfo& pipeline,
                                                        const Config& cfg);

// configs/<name>/*.toml, sorted.
[[nodiscard]] std::vector<std::filesystem::path> pipeline_configs(const PipelineInfo& pipeline);

// The design of `cfg` from phongsim's rtl/, or from the user's `files` with top `top` (empty:
// the built-in top).
[[nodiscard]] RtlDesign rtl_design(const PipelineInfo& pipeline, const Config& cfg,
                                   std::vector<std::filesystem::path> files = {},
                                   std::string top = {});
// The same from the user's sources as a file list names them (files, include folders, defines;
// sim/cosim/rtl_args.h); no files: phongsim's rtl/.
[[nodiscard]] RtlDesign rtl_design(const PipelineInfo& pipeline, const Config& cfg,
                                   const RtlSources& sources, std::string top);

}  // namespace phongsim
