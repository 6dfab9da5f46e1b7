// Bit-accurate model of rtl/shade_lyon/shade_lyon.sv: a triangle program in, its covered pixels
// (x, y, tri, spec, diff) out. The quadratic walker (model/quad.h) interpolates the normal's three
// components, encoded as c = (n + 1)/2; each pixel's N' = 2c - 1 goes into Lyon's unit
// (model/lyon.h) with N0 = N1 = N', a = 0 and the triangle's V, L and shininess; the triangle's
// number rides along.
// Specification: docs/shade_lyon.md.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "model/config.h"
#include "model/lyon.h"
#include "model/pipeline.h"
#include "model/quad.h"
#include "model/quad_setup.h"

namespace phongsim {

struct ShadeLyonFormats {
  LyonFormats lyon;
  QuadFormats walker;  // acc, sub_bits from the configuration; out = U1.(F+1) for vec = S*.F

  // Reads Lyon's keys, [format] acc and [param] sub_bits; vec must be signed with an integer bit.
  static ShadeLyonFormats from_config(const Config& cfg);
  // The encoded component format U1.(F+1) for `vec` = S*.F.
  [[nodiscard]] static fx::Format channel_format(fx::Format vec);
};

// One triangle as the host's setup sees it: subpixel vertices, a unit normal per vertex (in the
// triangle's vertex order), the triangle's V, L (unit) and shininess, and its number.
struct ShadeLyonTriangle {
  quad::SubpixelTri tri;
  std::array<std::array<double, 3>, 3> normal{};  // normal[vertex][component]
  std::array<double, 3> v{}, l{};
  double shin = 1;
  std::int64_t id = 0;  // 0 .. 2^16 - 1
};

class ShadeLyonModel final : public PipelineModel {
 public:
  explicit ShadeLyonModel(const ShadeLyonFormats& formats);

  [[nodiscard]] const ShadeLyonFormats& formats() const { return f_; }
  [[nodiscard]] const QuadModel& walker() const { return walker_; }
  [[nodiscard]] const LyonModel& lyon() const { return lyon_; }

  // Fields: the walker's program (x0 y0 x1 y1, e<k>_{kind,q,r,d,dq,dr}) with its channels named
  // n{x,y,z}_{f,gy,gx,a,b,c}, then v_{x,y,z} l_{x,y,z} shin tri; outputs x y tri spec diff.
  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  std::size_t eval_batch(std::span<const std::int64_t> in, std::vector<std::int64_t>& out,
                         std::vector<std::uint32_t>* counts = nullptr) override;
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    return std::make_unique<ShadeLyonModel>(*this);
  }

  // The walker's pixels of program `in` (x, y, and the three encoded components each) and, for
  // each, the input vector of Lyon's unit (its inputs() order). Both vectors are appended to.
  std::size_t pixels(std::span<const std::int64_t> in, std::vector<std::int64_t>& walker_out,
                     std::vector<std::int64_t>& lyon_in) const;

  // The program words for `t` (the walker's setup, model/quad_setup.h, on the encoded
  // components; V, L and shininess quantized nearest, ties to even, saturating; the number).
  [[nodiscard]] std::vector<std::int64_t> words(const ShadeLyonTriangle& t,
                                                QuadScreen screen = {}) const;

  // Number of the walker's program fields (the first fields of an input); the triangle's
  // number's bits.
  static constexpr std::size_t kProgramFields = 40;
  static constexpr int kTriBits = 16;

 private:
  // The walker's pixels of program `in`, appended to walker_out.
  std::size_t walk(std::span<const std::int64_t> in, std::vector<std::int64_t>& walker_out) const;
  // Lyon's input vectors (14 fields each, to `v`) for the n walker pixels at `walked` of
  // program `in`.
  void lyon_inputs(const std::int64_t* walked, std::size_t n, std::span<const std::int64_t> in,
                   std::int64_t* v) const;

  ShadeLyonFormats f_;
  QuadModel walker_;
  LyonModel lyon_;
  // Scratch of eval_batch: a group's walker pixels, pixels per program, Lyon inputs and
  // Lyon outputs.
  std::vector<std::int64_t> walked_;
  std::vector<std::uint32_t> sizes_;
  std::vector<std::int64_t> lyon_in_, shaded_;
};

}  // namespace phongsim
