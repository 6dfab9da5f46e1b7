// Lyon's specular unit in the registry (sim/pipelines/lyon.cpp): its stimulus and the random
// geometry it draws from, and `phongsim analyze lyon` (the numbers Lyon's report argues with,
// from the model and the float references in ref/lyon_float.h; each function returns data).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/rng.h"
#include "base/vec3.h"
#include "model/lyon.h"
#include "sim/cosim/stimulus.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& lyon_pipeline();

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
// The same into `out` (14 fields; no allocation: the stimulus makes one per random vector).
void quantize_lyon_pixel(const LyonPixel& p, const LyonFormats& f, std::span<std::int64_t> out);

// Directed corners and random vectors: half random_lyon_pixel, half arbitrary bit patterns.
[[nodiscard]] Stimulus make_lyon_stimulus(const PipelineModel& model);

// The input contract (docs/lyon.md): a in [0, 1]; |N'| = |(1 - a)·N0 + a·N1| in [1/sqrt 2, 1],
// where g1/g2 normalize (the lengths of interpolated unit normals up to 90 degrees apart); V and
// L unit vectors; shininess at least 1. Lengths within two LSBs of the vector format.
[[nodiscard]] InputContract lyon_contract(const LyonFormats& f);

// Waives coverpoint outcome `name` of Lyon's unit ("n.z.low", declared by the entry's
// coverpoints) in `c` with `reason`, and the RTL saturation arm of its requantization.
void waive_lyon_outcome(CoverpointSampler& c, const std::string& name, const std::string& reason);

// ---- analysis ----

// Length of a vector of `length` after approximate normalization: float g1 and g2, and the
// configured fixed-point unit (its norm order and formats; 0 if it does not normalize).
struct LyonNormRow {
  double length = 0;
  double g1 = 0;
  double g2 = 0;
  double fixed = 0;
};
[[nodiscard]] std::vector<LyonNormRow> lyon_norm_table(const LyonModel& model);

// max |f_k - cos^n alpha| over alpha, k = 0..3, for one shininess n.
struct LyonShapeRow {
  double n = 0;
  std::array<double, 4> max_error{};
};
[[nodiscard]] std::vector<LyonShapeRow> lyon_shape_table();

// The fixed-point unit against the same datapath in double precision (lyon::datapath), both fed
// the same quantized inputs, on `samples` random_lyon_pixel()s from `seed`: errors in output LSBs.
struct LyonOutputError {
  std::uint64_t samples = 0;          // pixels inside the input contract, the ones measured
  std::uint64_t out_of_contract = 0;  // pixels drawn but left out
  double spec_max = 0;                // LSBs of the spec format
  double spec_max_low_n = 0;          // the same over pixels with shininess n <= 256 (m <= 16)
  double spec_mean = 0;
  double diff_max = 0;  // LSBs of the diff format
  double diff_mean = 0;
  std::uint64_t spec_nonzero = 0;  // pixels with a visible highlight in the float reference
};
// exact_inputs: the reference sees the pixel before quantization instead, so the error also
// counts the input formats (what width exploration needs).
[[nodiscard]] LyonOutputError lyon_output_error(const LyonModel& model, std::uint64_t samples,
                                                std::uint64_t seed, bool exact_inputs = false);

// Outside the input contract: per clause, pixels that break it (and no clause before it), each
// an in-contract random_lyon_pixel with that one input moved out of its range; then a row of
// arbitrary bit patterns over the whole formats (any clause). The fixed-point unit against the
// float datapath on the same quantized inputs, clamped to the output formats' range (what a
// saturating output could give at best; the float g2 grows without bound for long N'),
// absolute (fractions of full scale), and the largest diffuse output (a unit normal's N·L never
// exceeds 1).
struct LyonContractRow {
  std::string clause;
  std::uint64_t samples = 0;
  double spec_max_error = 0;
  double worst_spec = 0, worst_spec_float = 0;  // at the largest spec error
  std::vector<std::int64_t> worst;              // its inputs, raw
  double diff_max_error = 0;
  double diff_max = 0;
  std::uint64_t diff_above_one = 0;
};
[[nodiscard]] std::vector<LyonContractRow> lyon_out_of_contract(const LyonModel& model,
                                                                std::uint64_t samples,
                                                                std::uint64_t seed);

// Every stage's format and width for the configuration (one pixel of zeros traces them).
[[nodiscard]] std::string lyon_stage_formats(const LyonModel& model);

}  // namespace phongsim
