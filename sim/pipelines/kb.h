// The Kuijk-Blake engine in the registry (sim/pipelines/kb.cpp): its stimulus and the random
// angular spans it draws from, and `phongsim analyze kb` (the three-piece quadratic against
// cos^n, and the forward-differencing drift of the engine against the exact span for both
// transition policies).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "base/rng.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "sim/cosim/contract.h"
#include "sim/cosim/coverpoints.h"
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

// kb_program() of `span`, made to fit the header's count: fewer terms first, then a narrower
// sweep; `span` is left as the one the program is for.
[[nodiscard]] std::vector<std::vector<std::int64_t>> kb_fitting_program(
    KbSpan& span, const KbFormats& formats, const KbSetupOptions& setup);

// A random well-formed program: length log-uniform in 1..4096 (`pixels` 0) or `pixels`, up to
// `max_events` events at distinct increasing indices before the last pixel, values of plausible
// magnitude (f around [0, 1], d1 ~ 1/length, d2 ~ 1/length²) or, one time in four, arbitrary bits.
[[nodiscard]] std::vector<std::vector<std::int64_t>> kb_random_words(Rng& rng, const KbFormats& f,
                                                                     std::uint64_t max_events,
                                                                     int pixels = 0);

// The directed programs of kb's stimulus (make_kb_stimulus): every clamp corner, wrap-around, a
// 4096-pixel span, events at the first and consecutive pixels, a late event, events at and after
// the last pixel, left-over event words, back-to-back one-pixel spans, the largest count.
[[nodiscard]] std::vector<std::vector<std::int64_t>> kb_directed_words(const KbFormats& f);

[[nodiscard]] Stimulus make_kb_stimulus(const PipelineModel& model, const KbSetupOptions& setup);

// A stimulus of span programs: `directed` vectors, then random chunks of `chunk_words` vectors,
// chunk c being `chunk`(Rng(seed, kStimulusStream, c)) padded with `filler` (a one-pixel span
// without events, so that the pipeline is idle where a chunk ends); vector i is still a pure
// function of (seed, i). Groups start at 0, after the directed vectors and at every chunk.
[[nodiscard]] Stimulus span_stimulus(
    const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed,
    std::uint64_t chunk_words, std::function<std::vector<std::vector<std::int64_t>>(Rng&)> chunk,
    std::vector<std::int64_t> filler);

// The input contract of an engine of formats `f` (docs/kb.md, "Input contract"): clauses
// "f in [0, 1]", "|d1| <= 1, |d2| <= 2", "length <= L", "events ordered, before the last pixel",
// checked word by word following the engine's parse from reset.
[[nodiscard]] InputContract kb_input_contract(const KbFormats& f);

// The engine's coverpoints, counted on one engine's word stream: the output's clamp to [0, 1]
// (low, high, neither) and requantization (saturating high: a clamped 1.0 in an output without
// integer bits; not); programs without events and with the most the header counts; spans of
// length 1 and of the maximum (2^12); events applied as a section event (Δ²f only) and as a
// reload (Δf too), late (index below the current pixel), on the span's last pixel, beyond the
// span's end, and dropped after it (docs/kb.md). Declared once in a sampler; a copy counts
// another engine's stream into the same points (it mirrors the engine's parse).
class KbCoverpoints {
 public:
  KbCoverpoints(CoverpointSampler& sampler, const KbFormats& f);
  // Before the engine evaluates word `in` (n, count, f, d1, d2, reload).
  void word(std::span<const std::int64_t> in, Coverpoints& cp);
  // After: the accumulator of every pixel it emitted.
  void pixels(std::span<const std::int64_t> acc, Coverpoints& cp);

 private:
  struct State {  // the engine's, mirrored: in a span, its pixel and last, events still due
    bool running = false;
    std::int64_t remaining = 0, i = 0, last = 0;
  };
  Clamp01Output output_;
  std::int64_t max_events_ = 0, max_last_ = 0;
  std::size_t events_ = 0, span_ = 0, ev_ = 0;
  State st_;
};

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

// A configuration's output against the exact span (kb_exact, clamped to the output's range), in
// output LSBs, over the programs of `programs` random spans (kb_random_program with the
// configuration's setup) inside the input contract: a program with any word outside it is
// counted in out_of_contract and left out. `contract` is the configuration's, from reset.
struct KbOutputError {
  double max = 0, mean = 0;
  std::uint64_t programs = 0, pixels = 0, out_of_contract = 0;
};
[[nodiscard]] KbOutputError kb_output_error(const KbFormats& formats, const KbSetupOptions& setup,
                                            const InputContract& contract, int programs,
                                            std::uint64_t seed);

// The engine outside its input contract (docs/kb.md, "Input contract"): per clause, in-contract
// setup programs with that one clause broken (header f moved out of [0, 1]; a header difference
// or a reloading event's Δf beyond |d1| <= 1, |d2| <= 2; a span longer than the guard bits
// cover; an event moved after the last pixel or before its predecessor), then random
// well-formed programs with arbitrary values that break any clause. Every pixel's output
// against what the program was written for, clamped to the output range: the exact span for
// the length and event clauses, the program's own values accumulated without wrapping for the
// others. `samples` programs over all rows; rows with no programs say why in `note`.
struct KbContractRow {
  std::string clause;
  std::uint64_t programs = 0, pixels = 0;
  double max_error = 0;              // absolute
  double worst = 0, worst_want = 0;  // the output and the reference at the largest error
  std::uint64_t off = 0;             // pixels more than one output LSB off
  std::string note;
};
[[nodiscard]] std::vector<KbContractRow> kb_out_of_contract(const KbFormats& formats,
                                                            const KbSetupOptions& setup,
                                                            const InputContract& contract,
                                                            std::uint64_t samples,
                                                            std::uint64_t seed);

}  // namespace phongsim
