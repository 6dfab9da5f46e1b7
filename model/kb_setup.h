// Span setup for the Kuijk–Blake engine (model/kb.h): from one or several angular terms along a
// scanline to the engine's program words, with either transition policy. The float reference
// is kb_exact(); docs/kb.md derives the error of each policy and the guard bits it needs.
#pragma once

#include <cstdint>
#include <vector>

#include "model/config.h"
#include "model/kb.h"
#include "ref/kb_float.h"

namespace phongsim {

enum class KbPolicy {
  d2_only,       // the paper: at a section change only Δ²f changes (one event per crossing)
  exact_reload,  // Δf is reloaded with the exact difference wherever Δ²f changes
};

// Where (a, b) come from: the corrected closed forms or the project's least-squares table.
enum class KbAbSource { closed_form, least_squares };

// [setup] keys of a kb configuration: policy, ab, terms (the most terms a random span sums).
struct KbSetupOptions {
  KbPolicy policy = KbPolicy::exact_reload;
  KbAbSource ab = KbAbSource::least_squares;
  int max_terms = 2;
  static KbSetupOptions from_config(const Config& cfg);
};

[[nodiscard]] kb::QuadParams kb_params(double n, KbAbSource source);

// One term: f_t(i) = scale · quad(theta0 + i·dtheta) (angles in radians per pixel).
struct KbTerm {
  double theta0 = 0;
  double dtheta = 0;
  kb::QuadParams ab{};
  double scale = 1;
};

struct KbSpan {
  std::vector<KbTerm> terms;
  int length = 1;  // pixels, 1..4096
};

// The exact span value at pixel i: the sum of the terms.
[[nodiscard]] double kb_exact(const KbSpan& span, int i);

// kb_exact(span, i) for pixels i = 0 .. n - 1 (n >= 1) into `exact`, and into `changes` (n - 1
// of them) whether pixel i + 1 is on another quadratic than pixel i in some term
// (kb::section_of); the same values, a span at a time on the kernel instruction set. Throws
// Error as kb_exact and kb::section_of do (invalid (a, b), NaN θ).
void kb_span_values(const KbSpan& span, int n, double* exact, std::uint8_t* changes);

// The program (header, then events; each word n, count, f, d1, d2, reload) that makes the engine
// evaluate `span` with `policy`, values rounded to nearest (ties to even) in the accumulator
// format. Throws Error when the span needs more events than the header's count can hold.
[[nodiscard]] std::vector<std::vector<std::int64_t>> kb_program(const KbSpan& span, KbPolicy policy,
                                                                const KbFormats& formats);

}  // namespace phongsim
