#include "model/shade_lyon.h"

#include <fmt/format.h>

#include <algorithm>

namespace phongsim {

fx::Format ShadeLyonFormats::channel_format(fx::Format vec) {
  return fx::Format{false, 1, vec.frac_bits + 1};
}

ShadeLyonFormats ShadeLyonFormats::from_config(const Config& cfg) {
  ShadeLyonFormats f;
  // The walker's keys first: Lyon's reader refuses every key it has not seen read.
  f.walker.acc = cfg.format("acc");
  f.walker.sub_bits = static_cast<int>(cfg.param("sub_bits", 1, 8));
  f.lyon = LyonFormats::from_config(cfg);
  if (!f.lyon.vec.is_signed || f.lyon.vec.int_bits < 1) {
    cfg.fail(
        fmt::format("[format] vec must be signed with an integer bit, for normals in [-1, 1] "
                    "(got {})",
                    f.lyon.vec.str()));
  }
  if (!f.walker.acc.is_signed)
    cfg.fail(fmt::format("[format] acc must be signed (got {})", f.walker.acc.str()));
  f.walker.out = channel_format(f.lyon.vec);
  f.walker.out_round = f.lyon.round;
  return f;
}

ShadeLyonModel::ShadeLyonModel(const ShadeLyonFormats& formats)
    : f_(formats), walker_(formats.walker), lyon_(formats.lyon) {
  const auto& program = walker_.inputs();
  for (std::size_t i = 0; i < kProgramFields; ++i) {
    Field field = program[i];
    // The walker's channels r, g, b carry the normal's x, y, z.
    if (i >= 22) field.name = fmt::format("n{}", "xyz"[(i - 22) / 6]) + field.name.substr(1);
    inputs_.push_back(field);
  }
  for (const auto& field : lyon_.inputs()) {
    if (field.name[0] == 'v' || field.name[0] == 'l' || field.name == "shin")
      inputs_.push_back(field);
  }
  const Field tri{"tri", fx::Format{false, kTriBits, 0}};
  inputs_.push_back(tri);
  outputs_ = {walker_.outputs()[0], walker_.outputs()[1], tri, lyon_.outputs()[0],
              lyon_.outputs()[1]};
}

std::size_t ShadeLyonModel::pixels(std::span<const std::int64_t> in,
                                   std::vector<std::int64_t>& walker_out,
                                   std::vector<std::int64_t>& lyon_in) const {
  const std::size_t base = walker_out.size();
  const QuadProgram program = QuadModel::program(in.first(kProgramFields));
  const std::size_t n = walker_.plan().usable() ? walker_.plan().walk(program, walker_out)
                                                : walker_.walk(program, walker_out);
  const std::int64_t half = std::int64_t{1} << f_.lyon.vec.frac_bits;       // 2c - 1 = C - 2^F
  const std::span<const std::int64_t> vls = in.subspan(kProgramFields, 7);  // v, l, shin
  const std::size_t at = lyon_in.size();
  lyon_in.resize(at + 14 * n);
  std::int64_t* v = lyon_in.data() + at;
  for (std::size_t p = 0; p < n; ++p, v += 14) {  // n0, n1, a, v, l, shin
    const std::int64_t* px = walker_out.data() + base + 5 * p;
    for (int c = 0; c < 3; ++c) v[c] = v[3 + c] = px[2 + c] - half;
    v[6] = 0;
    std::copy(vls.begin(), vls.end(), v + 7);
  }
  return n;
}

std::size_t ShadeLyonModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  walked_.clear();
  lyon_in_.clear();
  shaded_.clear();
  const std::size_t n = pixels(in, walked_, lyon_in_);
  (void)lyon_.eval_batch(lyon_in_, shaded_);
  const std::int64_t tri = in[kProgramFields + 7];
  const std::size_t at = out.size();
  out.resize(at + 5 * n);
  std::int64_t* o = out.data() + at;
  for (std::size_t p = 0; p < n; ++p, o += 5) {
    o[0] = walked_[5 * p];
    o[1] = walked_[5 * p + 1];
    o[2] = tri;
    o[3] = shaded_[2 * p];
    o[4] = shaded_[2 * p + 1];
  }
  return n;
}

std::vector<std::int64_t> ShadeLyonModel::words(const ShadeLyonTriangle& t,
                                                QuadScreen screen) const {
  std::array<quad::Coeffs, 3> encoded;
  for (int c = 0; c < 3; ++c) {
    const auto e = [&](int v) { return (t.normal[v][c] + 1) / 2; };
    encoded[c] = quad::linear_coefficients(e(0), e(1), e(2));
  }
  std::vector<std::int64_t> w = QuadModel::words(quad_program(t.tri, encoded, f_.walker, screen));
  const auto q = [](double x, fx::Format fmt) {
    return fx::quantize(x, fmt, fx::Round::half_even, fx::Overflow::saturate);
  };
  for (const auto& vec : {t.v, t.l}) {
    for (double x : vec) w.push_back(q(x, f_.lyon.vec));
  }
  w.push_back(q(t.shin, f_.lyon.shin));
  w.push_back(t.id);
  return w;
}

}  // namespace phongsim
