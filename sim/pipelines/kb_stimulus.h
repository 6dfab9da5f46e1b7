// Stimulus for the Kuijk–Blake engine, and the random angular spans it draws from (also used by
// `phongsim analyze kb`).
#pragma once

#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "sim/cosim/stimulus.h"

namespace phongsim {

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

}  // namespace phongsim
