// Bit-accurate model of rtl/lyon/lyon_top.sv: Lyon's reformulated Phong specular unit with the
// diffuse term (TR #43, Figs. 6-8). Stage names and order follow the RTL, so a mismatch points
// at a stage. Specification: docs/lyon.md.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "model/config.h"
#include "model/fixed.h"
#include "model/lyon_plan.h"
#include "model/pipeline.h"

namespace phongsim {

struct LyonFormats {
  // Structure ([param] in the configuration).
  int arrangement = 7;   // 7: shininess n, x from n·D·D;  8: m = sqrt(n), x from (m|D|)²
  bool halfway = false;  // D = H - (H·N)N with H = (L + V)/2 and n -> 4n, instead of R - L
  int norm = 2;          // approximate normalization of N': 0 none, 1 g1, 2 g2
  int h_norm = 0;        // the same for H (halfway only)
  int k = 2;             // shape function f_k: k squarings, 0..3
  fx::Round round = fx::Round::half_even;  // every requantization; all saturate

  // Formats ([format]); see docs/lyon.md for where each applies.
  fx::Format vec, a, shin, np, z, y, g, n, h, dot, r, d, dd, dabs, w, xf, sq, spec, diff;

  // Reads the keys this structure needs and rejects any other (Error naming file and line).
  static LyonFormats from_config(const Config& cfg);

  [[nodiscard]] bool uses_norm() const { return norm > 0 || (halfway && h_norm > 0); }
};

using Vec3Fx = std::array<fx::Fixed, 3>;

// One vector's approximate normalization (lyon_norm.sv): z, y, g are unused for order 0.
struct LyonNormStages {
  fx::Fixed z, y, g;
  Vec3Fx out;
};

// Every stage's value for one pixel, named as in the RTL.
struct LyonStages {
  Vec3Fx np;                    // stage 2: N' = LIRP(N0, N1, a)
  LyonNormStages n;             // stages 3-5: N
  Vec3Fx h;                     // stage 2 (halfway): H = (L + V)/2
  LyonNormStages hn;            // stages 3-5 (halfway): H normalized
  fx::Fixed dot;                // stage 6: N·V (reflect) or H·N (halfway)
  fx::Fixed diff;               // stage 6: the diffuse term N·L, clamped at 0 by saturation
  Vec3Fx r;                     // stage 7: R = 2(N·V)N - V, or the projection (H·N)N
  Vec3Fx d;                     // stage 8: D
  fx::Fixed dd;                 // stage 9 (arrangement 7): D·D
  Vec3Fx dabs, w;               // stage 9 (arrangement 8): |D| and the squarer inputs
  bool big = false;             // stage 9 (arrangement 8): some m|D_c|/2^s >= 1
  fx::Fixed xk;                 // stage 10: x/2^k, exact
  bool zero = false;            // stage 10: x/2^k >= 1, the output is forced to 0
  fx::Fixed xf;                 // stage 10: x/2^k requantized
  std::array<fx::Fixed, 4> sq;  // stage 11: sq[0] = 1 - xf; stages 12..: sq[j] = sq[j-1]²
  fx::Fixed spec;               // output
};

// One requantization of a pixel (LyonModel::stages with `sides`): the stage it writes (as in
// docs/lyon.md: "np", "n.z", "n", "dot", "sq_1", ...; a vector's three components share a name)
// and where its rounded value fell against the format's range (fx::resize_side: -1 saturated low,
// +1 saturated high, 0 inside), with both formats.
struct LyonRqSide {
  std::string_view point;
  int side = 0;
  fx::Format from, to;  // the exact value's format and the requantized one
};

class LyonModel final : public PipelineModel {
 public:
  // Evaluates one pixel of zeros to derive every stage format, so a configuration whose
  // intermediates would not fit the model's integers is refused here.
  explicit LyonModel(const LyonFormats& formats);

  [[nodiscard]] const LyonFormats& formats() const { return f_; }

  // Raw inputs in the formats of formats(): N0, N1, V, L as x, y, z.
  [[nodiscard]] LyonStages stages(const std::array<std::int64_t, 3>& n0,
                                  const std::array<std::int64_t, 3>& n1, std::int64_t a,
                                  const std::array<std::int64_t, 3>& v,
                                  const std::array<std::int64_t, 3>& l, std::int64_t shin,
                                  std::vector<LyonRqSide>* sides = nullptr) const;

  // Fields: inputs n0_{x,y,z} n1_{x,y,z} a v_{x,y,z} l_{x,y,z} shin; outputs spec diff.
  // Through the compiled plan (the stage path when the plan cannot be used).
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  std::size_t eval_batch(std::span<const std::int64_t> in, std::vector<std::int64_t>& out,
                         std::vector<std::uint32_t>* counts = nullptr) override;
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    return std::make_unique<LyonModel>(*this);
  }

  [[nodiscard]] const LyonPlan& plan() const { return plan_; }

  // Pipeline latency of the RTL in cycles (pipe_ctrl stages plus the output skid buffer).
  [[nodiscard]] int latency() const { return 13 + f_.k; }

 private:
  // rq(x, to), appending the requantization to `sides` when given.
  [[nodiscard]] fx::Fixed rq(fx::Fixed x, fx::Format to, std::string_view point,
                             std::vector<LyonRqSide>* sides) const;
  // N (h false) or H (h true) normalized by `order`.
  [[nodiscard]] LyonNormStages normalize(const Vec3Fx& in, fx::Format out, int order, bool h,
                                         std::vector<LyonRqSide>* sides) const;

  LyonFormats f_;
  LyonPlan plan_;
};

}  // namespace phongsim
