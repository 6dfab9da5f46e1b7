// Bit-accurate model of rtl/kb/kb_engine.sv, the Kuijk–Blake forward-differencing engine: a
// stream of span programs (a header word, then `count` event words) in, one pixel per step
// out. Specification: docs/kb.md. The setup that writes programs is model/kb_setup.h.
#pragma once

#include <cstdint>

#include "model/config.h"
#include "model/fixed.h"
#include "model/pipeline.h"
#include "model/plan.h"

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

// The engine's arithmetic compiled for one configuration (model/plan.h): the accumulator adders'
// wrap-around and the output's clamp and requantization as precomputed integer steps.
class KbPlan {
 public:
  KbPlan() = default;
  explicit KbPlan(const KbFormats& f);

  [[nodiscard]] bool usable() const { return out_.fits_int64(); }
  // a + b wrapped to acc: the sum has acc's binary point, so wrapping keeps its low width bits,
  // sign-extended (two shifts; both operands are in acc's range, so the sum fits int64_t).
  [[nodiscard]] std::int64_t wrap_add(std::int64_t a, std::int64_t b) const {
    return wrap(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
  }
  // v modulo 2^width(acc), read signed.
  [[nodiscard]] std::int64_t wrap(std::uint64_t v) const {
    return static_cast<std::int64_t>(v << wrap_shift_) >> wrap_shift_;
  }
  [[nodiscard]] std::int64_t output(std::int64_t f) const {
    return out_(std::min(std::max(f, std::int64_t{0}), one_));
  }
  // `count` pixels of a run without events from accumulators (f, d1, d2): writes each pixel's
  // (value, last = 0) pair to `out` and leaves f and d1 as the engine's after them.
  void run(std::int64_t& f, std::int64_t& d1, std::int64_t d2, std::size_t count,
           std::int64_t* out) const;

 private:
  int wrap_shift_ = 0;    // 64 - acc's width
  fx::Saturate out_;      // clamped accumulator to the output format
  std::int64_t one_ = 0;  // clamp01's upper bound (acc has no integer bit: never reached)
};

class KbModel final : public PipelineModel {
 public:
  // `stages`: evaluate through the fixed-point core operation by operation (the reference the
  // plan is tested against) instead of the compiled plan.
  explicit KbModel(const KbFormats& formats, bool stages = false);

  [[nodiscard]] const KbFormats& formats() const { return f_; }

  // Fields: inputs n, count, f, d1, d2, reload (one word); outputs value, last.
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  void reset() override { s_ = State{}; }
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    auto copy = std::make_unique<KbModel>(*this);
    copy->trace_ = nullptr;
    return copy;
  }

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
  // Arithmetic through the fixed-point core (Stages) or the plan.
  struct Stages {
    const KbModel& m;
    [[nodiscard]] std::int64_t wrap_add(std::int64_t a, std::int64_t b) const;
    [[nodiscard]] std::int64_t output(std::int64_t f) const { return m.output(f); }
  };
  template <class Ops>
  std::size_t step(const Ops& ops, std::span<const std::int64_t> in,
                   std::vector<std::int64_t>& out);
  // Emits pixel s_.i and steps with (d1_step, d2_step); ends the span after its last pixel.
  template <class Ops>
  void pixel(const Ops& ops, std::int64_t d1_step, std::int64_t d2_step,
             std::vector<std::int64_t>& out);
  // Emits pixels s_.i .. stop - 1 with the span's own steps (no event word applies to them),
  // ending the span if its last pixel is among them.
  template <class Ops>
  void steady(const Ops& ops, std::int64_t stop, std::vector<std::int64_t>& out);

  KbFormats f_;
  fx::Format sum_;  // f + d1 before wrapping; refused at construction if over the model's limit
  KbPlan plan_;
  bool stages_ = false;
  State s_;
  std::vector<std::int64_t>* trace_ = nullptr;
};

}  // namespace phongsim
