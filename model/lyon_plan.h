// Lyon's specular unit (model/lyon.h) compiled for one configuration: every stage of
// LyonModel::stages() as precomputed steps (model/plan.h), run a block of pixels at a time,
// stage after stage, on structure-of-arrays temporaries, so the per-pixel work is integer
// arithmetic the compiler vectorizes (fx::on_kernel_isa, model/plan.h). Bit-identical to the
// stage path in every configuration and instruction set (tests/plan_test.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "model/plan.h"

namespace phongsim {

struct LyonFormats;

// a·b of 3-vectors: exact products summed (x + y) + z, as fx_dot3 before its rounding.
struct Dot3Step {
  fx::AddStep xy;   // x + y
  fx::AddStep xyz;  // (x + y) + z

  [[nodiscard]] static Dot3Step of(fx::Format a, fx::Format b) {
    const fx::Format m = fx::mul_format(a, b);
    const fx::AddStep xy = fx::AddStep::add(m, m);
    return {xy, fx::AddStep::add(xy.r, m)};
  }
  [[nodiscard]] fx::Format result() const { return xyz.r; }
  [[nodiscard]] std::int64_t operator()(std::int64_t a0, std::int64_t a1, std::int64_t a2,
                                        std::int64_t b0, std::int64_t b1, std::int64_t b2) const {
    return xyz.sum(xy.sum(a0 * b0, a1 * b1), a2 * b2);
  }
};

class LyonPlan {
 public:
  LyonPlan() = default;
  explicit LyonPlan(const LyonFormats& f);

  // False when a requantization needs more than int64_t: the model keeps the stage path.
  [[nodiscard]] bool usable() const { return usable_; }

  // n pixels stored back to back (14 inputs each, LyonModel's inputs() order: n0, n1, a, v, l,
  // shin), 2 outputs each (spec, diff) written to `out`.
  void run(const std::int64_t* in, std::int64_t* out, std::size_t n) const;

 private:
  using Block = std::int64_t[fx::kBlock];

  // A block of m <= fx::kBlock pixels, structure of arrays: in[f][i] is input field f of
  // pixel i; out[0] spec, out[1] diff. Always inlined (as Norm::run), so that run() compiles
  // it for each instruction set (fx::on_kernel_isa).
  [[gnu::always_inline]] inline void block(const std::int64_t* const* in, std::int64_t* const* out,
                                           std::size_t m) const;

  // lyon_norm: order 0 requantizes only; otherwise z = N'·N', y = 1 - z, g = 1 + poly/2,
  // out = g·N'.
  struct Norm {
    int order = 0;
    fx::Saturate plain;  // order 0
    Dot3Step zz;
    fx::Saturate z;
    fx::AddStep y_sub;  // 1 - z
    fx::Saturate y;
    fx::AddStep poly;  // y + y·y (order 2)
    fx::ScaleStep half;
    fx::AddStep g_add;  // 1 + poly/2
    fx::Saturate g;
    fx::Saturate out;

    [[gnu::always_inline]] inline void run(const Block* src, Block* dst, std::size_t m) const;
  };

  fx::Saturate rq(fx::Format from, fx::Format to);
  Norm norm(fx::Format in, fx::Format out, int order, const LyonFormats& f);

  bool usable_ = true;
  fx::Round round_ = fx::Round::half_even;
  bool halfway_ = false;
  int arrangement_ = 7;
  int k_ = 0;

  fx::AddStep delta_, lirp_;  // stages 0-2
  fx::Saturate np_;
  Norm n_norm_, h_norm_;  // stages 3-5
  Dot3Step nl_;           // stage 6: diffuse
  fx::Saturate diff_;
  fx::AddStep lv_;  // stage 2 (halfway): H = (L + V)/2
  fx::ScaleStep lv_half_;
  fx::Saturate h_;
  Dot3Step dot_in_;  // stage 6: N·V or H·N
  fx::Saturate dot_;
  fx::ScaleStep r_two_;  // stage 7 (reflect): 2(N·V)N - V
  fx::AddStep r_sub_;
  fx::Saturate r_;
  fx::AddStep d_sub_;  // stage 8
  fx::Saturate d_;
  Dot3Step dd_in_;  // stages 9-10, arrangement 7
  fx::Saturate dd_;
  fx::ScaleStep x2_, xk_;
  fx::Saturate dabs_;  // stages 9-10, arrangement 8
  fx::ScaleStep u_;
  fx::AtLeastOne u_big_;
  fx::Saturate w_;
  Dot3Step ww_;
  fx::ScaleStep wk_;
  fx::AtLeastOne zero_;  // x/2^k >= 1
  fx::Saturate xf_;
  fx::AddStep sq_sub_;  // stages 11..: 1 - xf, then squarings
  fx::Saturate sq0_, sqj_, spec_;
};

}  // namespace phongsim
