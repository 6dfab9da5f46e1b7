// Bit-accurate model of rtl/quad/quad_walker.sv: one triangle program in, its covered pixels
// (x, y, R, G, B) out, row by row. The setup that writes programs is model/quad_setup.h.
// Specification: docs/quad.md.
#pragma once

#include <array>
#include <cstdint>

#include "model/config.h"
#include "model/fixed.h"
#include "model/pipeline.h"
#include "model/plan.h"

namespace phongsim {

struct QuadFormats {
  fx::Format acc;  // channel accumulators (signed)
  fx::Format out;  // colour output
  fx::Round out_round = fx::Round::half_even;
  int sub_bits = 4;  // subpixel bits of the vertices (1..8): sets the edge DDA widths

  static constexpr int kCoordBits = 11;                           // screens up to 2048 x 2048
  [[nodiscard]] int q_bits() const { return 26 + 2 * sub_bits; }  // DDA quotient, signed
  [[nodiscard]] int r_bits() const { return 12 + 2 * sub_bits; }  // DDA remainder and divisor

  // Reads [format] acc, out; [mode] out_round; [param] sub_bits.
  static QuadFormats from_config(const Config& cfg);
};

// One edge's DDA words (quad_walker: {kind, q, r, d, dq, dr}).
struct QuadEdge {
  int kind = 0;  // 0 unused, 1 lower bound (x >= -q), 2 upper bound (x <= q)
  std::int64_t q = 0, r = 0, d = 1, dq = 0, dr = 0;
};

// One channel's words: value, row difference, column difference at the origin pixel, and the
// quadratic coefficients a, b, c (pixel units), all raw in QuadFormats::acc.
struct QuadChannel {
  std::int64_t f = 0, gy = 0, gx = 0, a = 0, b = 0, c = 0;
};

struct QuadProgram {
  int x0 = 0, y0 = 1, x1 = 0, y1 = 0;  // pixel box; y0 > y1: no rows
  std::array<QuadEdge, 3> edges{};
  std::array<QuadChannel, 3> channels{};  // R, G, B
};

// The walker's arithmetic compiled for one configuration (model/plan.h): wrap-around of the
// accumulators and DDA quotients as precomputed sign extensions, the output's clamp and
// requantization as one step; walk() is QuadModel::walk() with those, writing each row's pixels
// straight into the output, each pixel's accumulators in closed form (the row's forward
// differences summed, modulo the accumulator's width: the same values, vectorized), on the
// kernel instruction set (fx::on_kernel_isa).
class QuadPlan {
 public:
  QuadPlan() = default;
  explicit QuadPlan(const QuadFormats& f);

  [[nodiscard]] bool usable() const { return out_.fits_int64(); }
  std::size_t walk(const QuadProgram& p, std::vector<std::int64_t>& out) const;
  // The same with `number` after x and y in every pixel (shade_quad's triangle number).
  std::size_t walk(const QuadProgram& p, std::int64_t number, std::vector<std::int64_t>& out) const;

 private:
  template <bool Numbered>
  std::size_t walk_rows(const QuadProgram& p, std::int64_t number,
                        std::vector<std::int64_t>& out) const;
  [[nodiscard]] std::int64_t wrap(std::uint64_t bits) const {  // modulo 2^width(acc), signed
    return static_cast<std::int64_t>(bits << acc_shift_) >> acc_shift_;
  }
  [[nodiscard]] std::int64_t output(std::int64_t f) const {
    return out_(std::min(std::max(f, std::int64_t{0}), one_));
  }

  fx::Saturate out_;
  std::int64_t one_ = 0;  // clamp01's upper bound
  int acc_shift_ = 0;     // 64 - width(acc)
  int q_shift_ = 0;       // 64 - q_bits
  std::uint64_t r_mask_ = 0;
};

// One row of a walk (QuadModel::walk with `rows`): its span (lower > upper: an empty row) and
// which edge set each end (-1: the box's x0 or x1, no edge narrower), with that edge's DDA
// remainder and divisor in the row.
struct QuadRowTrace {
  std::int64_t y = 0, lower = 0, upper = 0;
  int lower_edge = -1, upper_edge = -1;
  std::int64_t lower_r = 0, lower_d = 1, upper_r = 0, upper_d = 1;
};

class QuadModel final : public PipelineModel {
 public:
  explicit QuadModel(const QuadFormats& formats);

  [[nodiscard]] const QuadFormats& formats() const { return f_; }

  // Fields: x0 y0 x1 y1; e<k>_{kind,q,r,d,dq,dr} for k = 0..2; {r,g,b}_{f,gy,gx,a,b,c};
  // outputs x y r g b.
  // Through the compiled plan (QuadPlan::walk).
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    return std::make_unique<QuadModel>(*this);
  }
  [[nodiscard]] const QuadPlan& plan() const { return plan_; }

  // The same from a program, operation by operation through the fixed-point core (the stage
  // path the plan is tested against); `accumulators` (optional) receives each pixel's three channel
  // accumulator values before clamping and rounding (for the drift analysis); `rows` (optional)
  // each row's span.
  std::size_t walk(const QuadProgram& p, std::vector<std::int64_t>& out,
                   std::vector<std::int64_t>* accumulators = nullptr,
                   std::vector<QuadRowTrace>* rows = nullptr) const;

  // Program <-> input words (inputs() order).
  [[nodiscard]] static QuadProgram program(std::span<const std::int64_t> in);
  [[nodiscard]] static std::vector<std::int64_t> words(const QuadProgram& p);

 private:
  // a + b modulo 2^width(acc), as the RTL's adders and multipliers.
  [[nodiscard]] std::int64_t wrap(std::uint64_t bits) const { return fx::from_bits(bits, f_.acc); }

  QuadFormats f_;
  QuadPlan plan_;
};

}  // namespace phongsim
