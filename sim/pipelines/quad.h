// The quadratic colour interpolator in the registry (sim/pipelines/quad.cpp): its stimulus
// (random triangles through the setup, every size from slivers and one-pixel triangles to
// 1024-pixel boxes, both windings, colours that leave [0, 1] now and then; arbitrary program
// words over small boxes; directed corner cases) and `phongsim analyze quad` (accumulated
// forward-differencing drift of the walker against direct evaluation of eq. 4.1 with eq. 4.3's
// (s, t), by triangle size and guard bits).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "base/rng.h"
#include "model/fixed.h"
#include "model/quad.h"
#include "model/quad_setup.h"
#include "ref/quad_float.h"
#include "sim/cosim/contract.h"
#include "sim/cosim/stimulus.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& quad_pipeline();

// [setup] mode: quadratic (six samples per channel) or linear (three vertex values).
[[nodiscard]] QuadMode quad_mode(const Config& cfg);

// A random triangle in subpixel units within the screen: box side log-uniform up to 64 pixels,
// one time in 128 up to 1024; one in 32 degenerate (collinear); random winding.
[[nodiscard]] quad::SubpixelTri random_triangle(Rng& rng, int sub_bits);

// Random colour coefficients for one channel: quadratic from six samples in [-0.2, 1.2] (mostly
// in [0, 1]), or linear from three.
[[nodiscard]] quad::Coeffs random_colour(Rng& rng, QuadMode mode);

[[nodiscard]] Stimulus make_quad_stimulus(const PipelineModel& model, QuadMode mode);

// The walker's program ports (quad_walker_core's in_bbox_i, in_edge<k>_i and the three channel
// ports `channel_ports`, whose fields are `<prefix>_{f,gy,gx,a,b,c}` for `prefixes`), bound to
// QuadModel's field names: every pipeline built on the walker binds them alike.
[[nodiscard]] std::vector<PortBinding> walker_program_ports(
    const std::array<std::string, 3>& channel_ports, const std::array<std::string, 3>& prefixes);

// The cycle model of the walker (quad_walker_core; PipelineInfo::cycles): programs `in` (the
// walker's program fields first in each), their pixels `out` (`out_fields` values each, y
// second) and each program's pixel count. Fill: the walker's input and output registers.
[[nodiscard]] FrameCycles walker_cycles(std::span<const std::int64_t> in,
                                        std::span<const std::int64_t> out, std::size_t out_fields,
                                        std::span<const std::uint32_t> counts,
                                        std::vector<FrameCycles>* per_vector);

// ---- analysis ----

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
// With `contract` (the configuration's), programs outside it are counted in out_of_contract and
// left out.
struct QuadOutputError {
  double max = 0;
  double mean = 0;
  std::uint64_t pixels = 0;
  std::uint64_t out_of_contract = 0;
};
[[nodiscard]] QuadOutputError quad_output_error(const QuadFormats& formats, QuadMode mode,
                                                int triangles, std::uint64_t seed,
                                                const InputContract* contract = nullptr);

// The walker outside its input contract (docs/quad.md, "Input contract"): per clause, random
// in-contract setup programs with that one clause broken (one used edge's words changed: a
// remainder or remainder step not below the divisor, a divisor off the subpixel grid or out of
// range, an edge kind of 3; or a triangle whose box is larger than the guard bits cover), then,
// though no clause checks it, in-contract programs whose colour samples are too large for the
// accumulator (in [-8, 9]). Pixels against the triangle the program was written for: pixels the
// walker emits that the triangle does not cover (extra) or misses (missing), and every emitted
// pixel's channels against r(s, t) evaluated directly at its centre, clamped to the output
// range, absolute. `samples` programs over all rows; rows with no programs say why in `note`.
struct QuadContractRow {
  std::string clause;
  std::uint64_t programs = 0, pixels = 0;
  std::uint64_t extra = 0, missing = 0;  // coverage against the triangle's
  std::uint64_t worst_extra = 0;         // most extra pixels in one program
  double max_error = 0;                  // channels, absolute
  std::uint64_t off = 0;                 // channel values more than one output LSB off
  std::string note;
};
[[nodiscard]] std::vector<QuadContractRow> quad_out_of_contract(const QuadFormats& formats,
                                                                QuadMode mode,
                                                                const InputContract& contract,
                                                                std::uint64_t samples,
                                                                std::uint64_t seed);

}  // namespace phongsim
