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
  const std::int64_t tri = in[kProgramFields];
  if (walker_.plan().usable()) {  // the plan writes the number into each pixel itself
    return walker_.plan().walk(QuadModel::program(in.first(kProgramFields)), tri, out);
  }
  walked_.clear();
  const std::size_t n = walker_.eval(in.first(kProgramFields), walked_);
  const std::size_t at = out.size();
  out.resize(at + 6 * n);
  std::int64_t* o = out.data() + at;
  for (std::size_t p = 0; p < n; ++p, o += 6) {
    const std::int64_t* px = walked_.data() + 5 * p;
    o[0] = px[0];
    o[1] = px[1];
    o[2] = tri;
    o[3] = px[2];
    o[4] = px[3];
    o[5] = px[4];
  }
  return n;
}

}  // namespace phongsim
