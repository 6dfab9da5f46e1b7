// Lyon's shading pipeline from triangle to pixels in the registry (sim/pipelines/shade_lyon.cpp):
// random triangles with a unit normal per vertex and V, L and shininess drawn as Lyon's stimulus
// draws them; the composed model against the float datapath on exactly interpolated normals.
#pragma once

#include <cstdint>

#include "base/rng.h"
#include "model/shade_lyon.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& shade_lyon_pipeline();

// A random triangle (quad's random_triangle) with vertex normals up to about 80 degrees apart and
// V, L and shininess from random_lyon_pixel (V near the mirror of L about the first normal).
[[nodiscard]] ShadeLyonTriangle random_shade_lyon_triangle(Rng& rng, const ShadeLyonFormats& f);

// Every covered pixel of `triangles` random triangles (boxes up to 64 pixels) against the float
// datapath (ref/lyon_float.h) fed the normal interpolated exactly at the pixel's centre and the
// exact V, L and shininess: spec and diff errors in LSBs of their formats. Triangles whose program
// breaks the input contract are left out and counted.
struct ShadeLyonError {
  std::uint64_t triangles = 0, pixels = 0, out_of_contract = 0;
  double spec_max = 0, spec_mean = 0, diff_max = 0, diff_mean = 0;
  double spec_max_low_n = 0;  // over triangles with shininess n <= 256 (m <= 16)
};
[[nodiscard]] ShadeLyonError shade_lyon_error(const ShadeLyonModel& model, std::uint64_t triangles,
                                              std::uint64_t seed);

}  // namespace phongsim
