// Bit-accurate model of rtl/kb/kb_engine.sv, the Kuijk–Blake forward-differencing engine: a
// stream of span programs (a header word, then `count` event words) in, one pixel per step
// out. Specification: docs/kb.md. The setup that writes programs is model/kb_setup.h.
#pragma once

#include <cstdint>

#include "model/config.h"
#include "model/fixed.h"
#include "model/pipeline.h"

namespace phongsim {

struct KbFormats {
  fx::Format acc;  // f, Δf, Δ²f (signed; wraps like the RTL's adders)
  fx::Format out;  // output value
  fx::Round out_round = fx::Round::half_even;
  int event_bits = 5;  // width of the header's event count

  static constexpr int kIndexBits = 12;  // span length up to 4096

  // Reads [format] acc, out; [mode] out_round; [param] event_bits. [setup] keys are read by the
  // setup (KbSetupOptions::from_config); from_config does not check for unknown keys.
  static KbFormats from_config(const Config& cfg);
};

class KbModel final : public PipelineModel {
 public:
  explicit KbModel(const KbFormats& formats);

  [[nodiscard]] const KbFormats& formats() const { return f_; }

  // Fields: inputs n, count, f, d1, d2, reload (one word); outputs value, last.
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  void reset() override { s_ = State{}; }

  // The output value of an accumulator value: clamp to [0, 1], round to the output format.
  [[nodiscard]] std::int64_t output(std::int64_t f) const;

  // When set, every pixel also appends its accumulator f (before clamping and rounding) here:
  // the drift analysis compares it with the exact span.
  void trace_accumulator(std::vector<std::int64_t>* trace) { trace_ = trace; }

 private:
  struct State {
    bool running = false;
    std::int64_t remaining = 0;  // event words still to read for the current span
    std::int64_t i = 0, last = 0;
    std::int64_t f = 0, d1 = 0, d2 = 0;
  };
  // Emits pixel s_.i and steps with (d1_step, d2_step); ends the span after its last pixel.
  void pixel(std::int64_t d1_step, std::int64_t d2_step, std::vector<std::int64_t>& out);
  [[nodiscard]] std::int64_t wrap_add(std::int64_t a, std::int64_t b) const;

  KbFormats f_;
  fx::Format sum_;  // f + d1 before wrapping; refused at construction if over the model's limit
  State s_;
  std::vector<std::int64_t>* trace_ = nullptr;
};

}  // namespace phongsim
