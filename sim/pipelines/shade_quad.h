// The quadratic colour interpolator as a triangle-in, pixels-out pipeline in the registry
// (sim/pipelines/shade_quad.cpp): quad's entry with the triangle's number carried to the pixels.
#pragma once

#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& shade_quad_pipeline();

}  // namespace phongsim
