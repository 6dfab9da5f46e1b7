// Kuijk–Blake shading of scanline spans in colour in the registry (sim/pipelines/shade_kb.cpp):
// three kb engines, one per channel, behind a demux of span words and a join that emits
// (x, y, R, G, B) (rtl/shade_kb, model/shade_kb.h, docs/shade_kb.md). The stimulus, contract
// and coverpoints are kb's (sim/pipelines/kb.h), per channel, plus the span's x0 and y.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "base/rng.h"
#include "model/kb.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

[[nodiscard]] const PipelineInfo& shade_kb_pipeline();

// The span words of one span: `programs` are the three channels' kb programs (each a header,
// then its events; the headers' n are the span's, the same), put side by side in one header word
// (x0, y) followed by red's events, then green's, then blue's. An event word's fields that its
// channel does not read get `filler` (the hardware must ignore them).
[[nodiscard]] std::vector<std::vector<std::int64_t>> shade_kb_span_words(
    const std::array<std::vector<std::vector<std::int64_t>>, 3>& programs, std::int64_t x,
    std::int64_t y, std::int64_t filler = 0);

}  // namespace phongsim
