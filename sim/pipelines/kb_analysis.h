// `phongsim analyze kb`: the three-piece quadratic against cos^n, and the forward-differencing
// drift of the engine against the exact span for both transition policies.
#pragma once

#include <cstdint>
#include <vector>

#include "model/kb.h"
#include "model/kb_setup.h"

namespace phongsim {

// Max and RMS of |quad - cos^n| for one n, closed-form and least-squares (a, b).
struct KbFitRow {
  int n = 0;
  kb::QuadParams closed{}, lsq{};
  double closed_max = 0, closed_rms = 0, lsq_max = 0, lsq_rms = 0;
};
[[nodiscard]] std::vector<KbFitRow> kb_fit_table();

// Largest |clamp(accumulator) - clamp(exact)| (clamp to [0, 1], before the output rounding)
// over every pixel of `spans` random spans of `length` pixels, in LSBs of `out`, for an
// accumulator with `guard_bits` fraction bits below out's LSB and two integer bits. With many
// guard bits (40) what remains is the policy's own error.
[[nodiscard]] double kb_drift(int length, int guard_bits, KbPolicy policy, fx::Format out,
                              int spans, std::uint64_t seed);

// Guard bits that bound the accumulated rounding of f, Δf and Δ²f by half an output LSB over
// a span of `length` pixels: the smallest G with (L² - L + 2)/2 · 2^-(G+1) <= 1/2 (docs/kb.md).
[[nodiscard]] int kb_guard_bits_needed(int length);

}  // namespace phongsim
