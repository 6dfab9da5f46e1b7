// Bit-accurate model of rtl/shade_quad/shade_quad.sv: the quadratic walker (model/quad.h) with
// the triangle's number carried to its pixels. A program (the walker's fields, then `tri`) in,
// (x, y, tri, r, g, b) per covered pixel out. Specification: docs/quad.md, docs/system.md.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "model/pipeline.h"
#include "model/quad.h"

namespace phongsim {

class ShadeQuadModel final : public PipelineModel {
 public:
  explicit ShadeQuadModel(const QuadFormats& formats);

  [[nodiscard]] const QuadModel& walker() const { return walker_; }

  std::size_t eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) override;
  [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
    return std::make_unique<ShadeQuadModel>(*this);
  }

  static constexpr std::size_t kProgramFields = 40;  // the walker's, first in an input
  static constexpr int kTriBits = 16;

 private:
  QuadModel walker_;
  std::vector<std::int64_t> walked_;  // scratch: the walker's pixels of one program
};

}  // namespace phongsim
