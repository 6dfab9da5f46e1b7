// `phongsim analyze quad`: accumulated forward-differencing drift of the walker against direct
// evaluation of eq. 4.1 (with eq. 4.3's (s, t)), by triangle size and guard bits.
#pragma once

#include <cstdint>

#include "model/fixed.h"
#include "model/quad.h"
#include "model/quad_setup.h"

namespace phongsim {

// Largest |clamp(accumulator) - clamp(r(s, t))| (clamp to [0, 1], before the output rounding)
// over every covered pixel and channel of `triangles` random triangles with vertices in a
// `size` x `size` box (quadratic colours from six samples in [0, 1]), in LSBs of `out`, for an
// accumulator with `guard_bits` fraction bits below out's LSB and two integer bits.
[[nodiscard]] double quad_drift(int size, int guard_bits, fx::Format out, int triangles,
                                std::uint64_t seed);

// A configuration's output against direct evaluation: |output - r(s, t)|, r clamped to the
// output's range [0, max], in output LSBs
// over every covered pixel and channel of `triangles` random triangles (random_triangle: every
// size up to 1024-pixel boxes) with random colours of `mode`.
struct QuadOutputError {
  double max = 0;
  double mean = 0;
  std::uint64_t pixels = 0;
};
[[nodiscard]] QuadOutputError quad_output_error(const QuadFormats& formats, QuadMode mode,
                                                int triangles, std::uint64_t seed);

}  // namespace phongsim
