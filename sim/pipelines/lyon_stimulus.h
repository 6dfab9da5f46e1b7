// Stimulus for the Lyon pipeline, and the random geometry it draws from (also used by
// `phongsim analyze lyon`, so the error figures come from the same kind of pixels).
#pragma once

#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "base/vec3.h"
#include "model/lyon.h"
#include "sim/cosim/stimulus.h"

namespace phongsim {

// One pixel's inputs as reals.
struct LyonPixel {
  Vec3 n0, n1;
  double a = 0;
  Vec3 v, l;
  double shin = 1;  // n (arrangement 7) or m (arrangement 8)
};

// Plausible geometry: unit N0, N1 up to 90 degrees apart, a in [0, 1], a unit L, V placed so the
// reflection lands within a few highlight radii (1/sqrt(n)) of L, shininess log-uniform over
// the format's range.
[[nodiscard]] LyonPixel random_lyon_pixel(Rng& rng, const LyonFormats& f);

// The pixel quantized (nearest, ties to even, saturating) to the unit's input formats, in the
// model's inputs() order.
[[nodiscard]] std::vector<std::int64_t> quantize_lyon_pixel(const LyonPixel& p,
                                                            const LyonFormats& f);

// Directed corners and random vectors: half random_lyon_pixel, half arbitrary bit patterns.
[[nodiscard]] Stimulus make_lyon_stimulus(const PipelineModel& model);

}  // namespace phongsim
