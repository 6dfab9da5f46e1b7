#include "sim/pipelines/kb_analysis.h"

#include <algorithm>
#include <cmath>

#include "sim/pipelines/kb_stimulus.h"

namespace phongsim {

std::vector<KbFitRow> kb_fit_table() {
  std::vector<KbFitRow> rows;
  for (int n = 1; n <= 125; ++n) {
    KbFitRow r;
    r.n = n;
    r.closed = kb::closed_form(n);
    r.lsq = kb::least_squares(n);
    r.closed_max = kb::max_error(r.closed, n);
    r.closed_rms = kb::rms_error(r.closed, n);
    r.lsq_max = kb::max_error(r.lsq, n);
    r.lsq_rms = kb::rms_error(r.lsq, n);
    rows.push_back(r);
  }
  return rows;
}

double kb_drift(int length, int guard_bits, KbPolicy policy, fx::Format out, int spans,
                std::uint64_t seed) {
  KbFormats f;
  f.acc = fx::Format{true, 2, out.frac_bits + guard_bits};
  f.out = out;
  f.event_bits = 6;
  KbModel engine(f);
  std::vector<std::int64_t> trace;
  std::vector<std::int64_t> outputs;
  engine.trace_accumulator(&trace);
  const KbSetupOptions options{policy, KbAbSource::least_squares, 2};
  const double out_lsb = std::ldexp(1.0, -out.frac_bits);
  double worst = 0;
  for (int s = 0; s < spans; ++s) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(s));
    const KbSpan span = kb_random_span(rng, options, length);
    trace.clear();
    engine.reset();
    for (const auto& word : kb_program(span, policy, f)) engine.eval(word, outputs);
    // What reaches the output: both sides clamped to [0, 1] (before the output rounding).
    const auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
    for (int i = 0; i < length; ++i) {
      const double drift =
          std::abs(clamp01(fx::to_real(trace[i], f.acc)) - clamp01(kb_exact(span, i))) / out_lsb;
      worst = std::max(worst, drift);
    }
  }
  return worst;
}

int kb_guard_bits_needed(int length) {
  const double l = length;
  return static_cast<int>(std::ceil(std::log2((l * l - l + 2) / 2)));
}

}  // namespace phongsim
