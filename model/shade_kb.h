// Bit-accurate model of rtl/shade_kb/shade_kb_top.sv: Kuijk–Blake shading of scanline spans in
// colour, three kb engines (model/kb.h, one per channel) behind a demux of span-program words
// and a join that emits (x, y, R, G, B). Specification: docs/shade_kb.md. The programs come from
// the host-side setup, model/kb_setup.h, one per channel.
#pragma once

#include <array>
#include <cstdint>
#include <deque>

#include "model/config.h"
#include "model/kb.h"
#include "model/pipeline.h"

namespace phongsim {

class ShadeKbModel final : public PipelineModel {
 public:
  static constexpr int kCoordBits = 11;  // x and y: screens up to 2048 x 2048
  static constexpr int kChannels = 3;

  // Input fields, in inputs() order (docs/shade_kb.md, "Input: span words").
  enum In : std::size_t {
    kN,
    kX,
    kY,
    kCount,           // count_r, count_g, count_b
    kF = kCount + 3,  // f_r, f_g, f_b
    kD1 = kF + 3,     // d1_r, d1_g, d1_b
    kD2 = kD1 + 3,    // d2_r, d2_g, d2_b
    kReload = kD2 + 3,
    kInputs
  };

  // `stages`: the engines evaluate through the fixed-point core operation by operation instead
  // of their compiled plans (KbModel's; tests/plan_test.cpp compares the two).
  explicit ShadeKbModel(const KbFormats& formats, bool stages = false);

  [[nodiscard]] const KbFormats& formats() const { return engines_[0].formats(); }

  // Fields: inputs n, x0, y0, count_{r,g,b}, f_{r,g,b}, d1_{r,g,b}, d2_{r,g,b}, reload; outputs
  // x, y, r, g, b.
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  void reset() override;
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    return std::make_unique<ShadeKbModel>(*this);
  }

  // The demux's decision for the next word (its parse state; nothing advances): a header goes to
  // every channel (targets 0b111), an event to the first channel with events still due.
  struct Route {
    bool header = true;
    unsigned targets = 0b111;  // bit c: channel c takes the word
  };
  [[nodiscard]] Route route() const;
  // The kb_engine word (n, count, f, d1, d2, reload) channel `ch` sees of shade word `in`.
  [[nodiscard]] static std::array<std::int64_t, 6> channel_word(std::span<const std::int64_t> in,
                                                                int ch) {
    const auto c = static_cast<std::size_t>(ch);
    return {in[kN], in[kCount + c], in[kF + c], in[kD1 + c], in[kD2 + c], in[kReload]};
  }
  // Channel `ch`'s engine (stage values and coverpoints trace its accumulator).
  [[nodiscard]] KbModel& engine(int ch) { return engines_[static_cast<std::size_t>(ch)]; }

 private:
  struct Span {
    std::int64_t x = 0, y = 0;
  };
  std::array<KbModel, kChannels> engines_;
  std::array<std::int64_t, kChannels> left_{};  // demux: events still due per channel
  // Each engine's outputs, (value, last) pairs as KbModel::eval writes them; the join has taken
  // the first taken_[c] numbers of pixels_[c].
  std::array<std::vector<std::int64_t>, kChannels> pixels_;
  std::array<std::size_t, kChannels> taken_{};
  std::deque<Span> spans_;  // span queue: x0, y of spans in flight
  std::int64_t i_ = 0;      // join: pixel index in the span
};

}  // namespace phongsim
