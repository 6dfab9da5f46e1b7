// The Kuijk-Blake engine in the registry (sim/pipelines/kb.cpp): its stimulus and the random
// angular spans it draws from, and `phongsim analyze kb` (the three-piece quadratic against
// cos^n, and the forward-differencing drift of the engine against the exact span for both
// transition policies).
#pragma once

#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "sim/cosim/stimulus.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& kb_pipeline();

// A plausible span: 1..max_terms terms (n = 1..125 each, (a, b) from the options' source,
// scales summing to at most 1), each sweeping from a random angle to another within ±1.5 b, so
// every section and break point gets crossed; length log-uniform in 1..4096.
// `length` 0: log-uniform in 1..4096; otherwise that many pixels.
[[nodiscard]] KbSpan kb_random_span(Rng& rng, const KbSetupOptions& setup, int length = 0);

// kb_program() of a kb_random_span(); falls back to one term, then to shorter spans, when the
// program would need more events than the configuration's header can count.
[[nodiscard]] std::vector<std::vector<std::int64_t>> kb_random_program(Rng& rng,
                                                                       const KbFormats& formats,
                                                                       const KbSetupOptions& setup);

[[nodiscard]] Stimulus make_kb_stimulus(const PipelineModel& model, const KbSetupOptions& setup);

// ---- analysis ----

// Max and RMS of |quad - cos^n| over θ in [0, π] for one n, closed-form and least-squares (a, b):
// n = 1..125 (the paper's range), then 128, 256, 512, 1024, 4096.
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
