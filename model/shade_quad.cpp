#include "model/shade_quad.h"

namespace phongsim {

ShadeQuadModel::ShadeQuadModel(const QuadFormats& formats) : walker_(formats) {
  const Field tri{"tri", fx::Format{false, kTriBits, 0}};
  inputs_ = walker_.inputs();
  inputs_.push_back(tri);
  const auto& w = walker_.outputs();  // x y r g b
  outputs_ = {w[0], w[1], tri, w[2], w[3], w[4]};
}

std::size_t ShadeQuadModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  std::vector<std::int64_t> walked;
  const std::size_t n = walker_.eval(in.first(kProgramFields), walked);
  const std::int64_t tri = in[kProgramFields];
  for (std::size_t p = 0; p < n; ++p) {
    const std::int64_t* px = walked.data() + 5 * p;
    out.insert(out.end(), {px[0], px[1], tri, px[2], px[3], px[4]});
  }
  return n;
}

}  // namespace phongsim
