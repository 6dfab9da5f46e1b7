#include "sim/pipelines/registry.h"

#include <fmt/format.h>

#include <array>

#include "base/error.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "model/lirp.h"
#include "model/lyon.h"
#include "model/quad.h"
#include "sim/pipelines/kb_stimulus.h"
#include "sim/pipelines/lyon_stimulus.h"
#include "sim/pipelines/quad_stimulus.h"

namespace phongsim {
namespace {

// ---- lirp ----

std::unique_ptr<PipelineModel> make_lirp_model(const Config& cfg) {
  const LirpFormats formats = LirpFormats::from_config(cfg);
  try {
    return std::make_unique<LirpModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

// Corner values of a and of the vector components, crossed so that every component sees every
// corner against every other one, plus a values that make exact rounding ties (a = 1/4, 1/2,
// 3/4 times an odd difference leaves exactly half an output LSB when a has more fraction bits).
Stimulus make_lirp_stimulus(const PipelineModel& model, const Config&) {
  const auto& f = dynamic_cast<const LirpModel&>(model).formats();
  const auto pc = corner_values(f.p);
  auto ac = corner_values(f.a);
  for (int quarter = 1; quarter <= 3; ++quarter) {
    if (f.a.frac_bits >= 2) ac.push_back(std::int64_t{quarter} << (f.a.frac_bits - 2));
  }
  std::vector<std::vector<std::int64_t>> directed;
  const std::size_t n = pc.size();
  for (const std::int64_t a : ac) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        directed.push_back({pc[i], pc[j], pc[(i + j) % n], pc[j], pc[i], pc[(i * j + 1) % n], a});
      }
    }
  }
  return Stimulus(model, std::move(directed));
}

// ---- lyon ----

std::unique_ptr<PipelineModel> make_lyon_model(const Config& cfg) {
  const LyonFormats formats = LyonFormats::from_config(cfg);
  try {
    return std::make_unique<LyonModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

Stimulus make_lyon_stimulus_for(const PipelineModel& model, const Config&) {
  return make_lyon_stimulus(model);
}

// ---- kb ----

std::unique_ptr<PipelineModel> make_kb_model(const Config& cfg) {
  const KbFormats formats = KbFormats::from_config(cfg);
  (void)KbSetupOptions::from_config(cfg);  // the stimulus reads it; check it here
  cfg.check_all_used();
  try {
    return std::make_unique<KbModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

Stimulus make_kb_stimulus_for(const PipelineModel& model, const Config& cfg) {
  return make_kb_stimulus(model, KbSetupOptions::from_config(cfg));
}

// ---- quad ----

std::unique_ptr<PipelineModel> make_quad_model(const Config& cfg) {
  const QuadFormats formats = QuadFormats::from_config(cfg);
  (void)quad_mode(cfg);  // the stimulus reads it; check it here
  cfg.check_all_used();
  return std::make_unique<QuadModel>(formats);
}

Stimulus make_quad_stimulus_for(const PipelineModel& model, const Config& cfg) {
  return make_quad_stimulus(model, quad_mode(cfg));
}

constexpr std::array kPipelines{
    PipelineInfo{"lirp", "LIRP unit: p = (1 - a)·p0 + a·p1 on 3-vectors (Lyon Fig. 7a)",
                 make_lirp_model, make_lirp_stimulus, true},
    PipelineInfo{"lyon",
                 "Lyon specular unit: LIRP, g1/g2 normalization, D, x, f_k (Figs. 7, 8), diffuse",
                 make_lyon_model, make_lyon_stimulus_for, true},
    PipelineInfo{"kb",
                 "Kuijk-Blake forward-differencing engine: piecewise-quadratic cos^n along spans",
                 make_kb_model, make_kb_stimulus_for, false},
    PipelineInfo{"quad",
                 "Quadratic/linear colour interpolator: triangle walker, forward differencing",
                 make_quad_model, make_quad_stimulus_for, true},
};

}  // namespace

std::span<const PipelineInfo> pipelines() { return kPipelines; }

const PipelineInfo& find_pipeline(std::string_view name) {
  for (const auto& p : kPipelines) {
    if (p.name == name) return p;
  }
  std::string known;
  for (const auto& p : kPipelines) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw Error(fmt::format("unknown pipeline '{}' (known: {})", name, known));
}

std::unique_ptr<PipelineModel> make_model(const PipelineInfo& pipeline, const Config& cfg) {
  if (cfg.pipeline() != pipeline.name) {
    throw Error(fmt::format("{}: configures pipeline '{}', not '{}'", cfg.origin(), cfg.pipeline(),
                            pipeline.name));
  }
  return pipeline.make_model(cfg);
}

}  // namespace phongsim
