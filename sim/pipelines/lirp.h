// The LIRP unit's registry entry and its float-reference error (sim/pipelines/lirp.cpp).
#pragma once

#include <cstdint>

#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& lirp_pipeline();

// The model against p0 + a (p1 - p0) in float: components uniform in [-1, 1], a in [0, 1].
[[nodiscard]] ModelError lirp_float_error(const Config& cfg, std::uint64_t samples,
                                          std::uint64_t seed);

}  // namespace phongsim
