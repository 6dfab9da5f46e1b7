// Bit-accurate model of rtl/lirp/lirp_unit.sv: p = (1 - a)·p0 + a·p1 on 3-component vectors,
// computed as p0 + a·(p1 - p0) with one rounding at the output. Stage names follow the RTL.
// Specification: docs/lirp.md.
#pragma once

#include <array>
#include <cstdint>

#include "model/config.h"
#include "model/fixed.h"
#include "model/pipeline.h"
#include "model/plan.h"

namespace phongsim {

struct LirpFormats {
  fx::Format p;    // components of p0 and p1
  fx::Format a;    // interpolation factor
  fx::Format out;  // components of the result
  fx::Round out_round = fx::Round::half_even;
  fx::Overflow out_overflow = fx::Overflow::saturate;

  // Reads [format] p, a, out and [mode] out_round, out_overflow; rejects anything else.
  static LirpFormats from_config(const Config& cfg);
};

// Every stage's value for one component, named as in the RTL.
struct LirpStages {
  fx::Fixed delta;  // stage delta: p1 - p0, exact
  fx::Fixed prod;   // stage prod:  a * delta, exact
  fx::Fixed sum;    // stage out:   p0 + prod, exact
  fx::Fixed p;      // stage out:   sum requantized to the output format
};

// The stages compiled for one configuration (model/plan.h): per component one subtraction, one
// multiplication, one aligned add and one requantization, all on int64_t.
class LirpPlan {
 public:
  explicit LirpPlan(const LirpFormats& f);

  // False when a step needs more than int64_t (formats near the 63-bit limit): use the stages.
  [[nodiscard]] bool usable() const { return out_.fits_int64(); }

  [[nodiscard]] std::int64_t component(std::int64_t p0, std::int64_t p1, std::int64_t a) const {
    return out_(sum(p0, p1, a));
  }

  // n transactions stored back to back (7 inputs each, inputs() order), 3 outputs each written
  // to `out`; a block at a time on structure-of-arrays temporaries.
  void run(const std::int64_t* in, std::int64_t* out, std::size_t n) const;

 private:
  [[nodiscard]] std::int64_t sum(std::int64_t p0, std::int64_t p1, std::int64_t a) const {
    return sum_.sum(p0, a * delta_.diff(p1, p0));
  }

  fx::AddStep delta_;  // p1 - p0
  fx::AddStep sum_;    // p0 + prod
  fx::Requant out_;    // sum -> out
};

class LirpModel final : public PipelineModel {
 public:
  // Derives every stage format up front, so a configuration whose intermediates would not fit
  // the model's integers is refused here (fx::Error naming the stage), not while running.
  explicit LirpModel(const LirpFormats& formats);

  [[nodiscard]] const LirpFormats& formats() const { return f_; }

  // One component through all stages; p0, p1 in formats().p, a in formats().a (raw values).
  [[nodiscard]] LirpStages component(std::int64_t p0, std::int64_t p1, std::int64_t a) const;

  // Fields: inputs p0_x p0_y p0_z p1_x p1_y p1_z a; outputs p_x p_y p_z. Through the plan.
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  std::size_t eval_batch(std::span<const std::int64_t> in, std::vector<std::int64_t>& out,
                         std::vector<std::uint32_t>* counts = nullptr) override;
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    return std::make_unique<LirpModel>(*this);
  }

  [[nodiscard]] const LirpPlan& plan() const { return plan_; }

 private:
  LirpFormats f_;
  LirpPlan plan_;
};

}  // namespace phongsim
