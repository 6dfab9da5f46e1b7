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

void ShadeLyonModel::lyon_inputs(const std::int64_t* walked, std::size_t n,
                                 std::span<const std::int64_t> in, std::int64_t* v) const {
  const std::int64_t half = std::int64_t{1} << f_.lyon.vec.frac_bits;       // 2c - 1 = C - 2^F
  const std::span<const std::int64_t> vls = in.subspan(kProgramFields, 7);  // v, l, shin
  for (std::size_t p = 0; p < n; ++p, v += 14) {                            // n0, n1, a, v, l, shin
    const std::int64_t* px = walked + 5 * p;
    for (int c = 0; c < 3; ++c) v[c] = v[3 + c] = px[2 + c] - half;
    v[6] = 0;
    std::copy(vls.begin(), vls.end(), v + 7);
  }
}

std::size_t ShadeLyonModel::walk(std::span<const std::int64_t> in,
                                 std::vector<std::int64_t>& walker_out) const {
  const QuadProgram program = QuadModel::program(in.first(kProgramFields));
  return walker_.plan().usable() ? walker_.plan().walk(program, walker_out)
                                 : walker_.walk(program, walker_out);
}

std::size_t ShadeLyonModel::pixels(std::span<const std::int64_t> in,
                                   std::vector<std::int64_t>& walker_out,
                                   std::vector<std::int64_t>& lyon_in) const {
  const std::size_t base = walker_out.size();
  const std::size_t n = walk(in, walker_out);
  const std::size_t at = lyon_in.size();
  lyon_in.resize(at + 14 * n);
  lyon_inputs(walker_out.data() + base, n, in, lyon_in.data() + at);
  return n;
}

std::size_t ShadeLyonModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  return eval_batch(in.first(inputs_.size()), out);
}

// Programs walked until they have about kGroup pixels, then Lyon's unit on all of them in one
// call (whole blocks of its plan, not a part-filled block per triangle), then their outputs;
// a group's scratch stays in the caches.
std::size_t ShadeLyonModel::eval_batch(std::span<const std::int64_t> in,
                                       std::vector<std::int64_t>& out,
                                       std::vector<std::uint32_t>* counts) {
  constexpr std::size_t kGroup = 512;
  const std::size_t n_in = inputs_.size();
  const std::size_t programs = in.size() / n_in;
  std::size_t total = 0;
  for (std::size_t first = 0; first < programs;) {
    walked_.clear();
    sizes_.clear();
    std::size_t end = first;
    while (end < programs && walked_.size() < 5 * kGroup) {
      sizes_.push_back(static_cast<std::uint32_t>(walk(in.subspan(end * n_in, n_in), walked_)));
      ++end;
    }
    const std::size_t n = walked_.size() / 5;
    // Grown, never cleared: every element read below is written first, so no zero-filling.
    if (lyon_in_.size() < 14 * n) lyon_in_.resize(14 * n);
    for (std::size_t k = first, p = 0; k < end; p += sizes_[k - first], ++k) {
      lyon_inputs(walked_.data() + 5 * p, sizes_[k - first], in.subspan(k * n_in, n_in),
                  lyon_in_.data() + 14 * p);
    }
    shaded_.clear();
    (void)lyon_.eval_batch(std::span(lyon_in_).first(14 * n), shaded_);
    const std::size_t at = out.size();
    out.resize(at + 5 * n);
    std::int64_t* o = out.data() + at;
    const std::int64_t* px = walked_.data();
    const std::int64_t* shade = shaded_.data();
    for (std::size_t k = first; k < end; ++k) {
      const std::int64_t tri = in[k * n_in + kProgramFields + 7];
      for (std::uint32_t p = 0; p < sizes_[k - first]; ++p, o += 5, px += 5, shade += 2) {
        o[0] = px[0];
        o[1] = px[1];
        o[2] = tri;
        o[3] = shade[0];
        o[4] = shade[1];
      }
    }
    if (counts != nullptr) counts->insert(counts->end(), sizes_.begin(), sizes_.end());
    total += n;
    first = end;
  }
  return total;
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
