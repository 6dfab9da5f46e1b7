// The quadratic walker by hand, every width a constant: the native kernel (PipelineInfo::native,
// `phongsim bench`'s yardstick) of each pipeline built on the walker, for its default
// configuration. The walk is QuadModel's; `phongsim bench` checks each kernel bit-identical to
// its model on the bench vectors.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "model/plan.h"

namespace phongsim {

// Programs of `Stride` fields (the walker's 40 first; with `Numbered`, the last is the
// triangle's number, carried to each pixel as its third field) to pixels (x, y[, tri], c0, c1,
// c2) appended to `out`: accumulators of AccWidth bits with AccFrac fraction bits, wrapping; each
// output the accumulator clamped to [0, 1], rounded half_even to OutFrac fraction bits and
// saturated to OutWidth unsigned bits; sub_bits 4 (DDA quotient 34 bits, remainder 20). Returns
// the pixels. Call it inside fx::on_kernel_isa, so that it runs the plans' instruction set.
template <int AccWidth, int AccFrac, int OutWidth, int OutFrac, std::size_t Stride, bool Numbered>
std::size_t native_walker(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  using u64 = std::uint64_t;
  constexpr std::size_t kOut = Numbered ? 6 : 5;
  constexpr std::size_t kC = kOut - 3;  // the first channel's field
  constexpr int kDrop = AccFrac - OutFrac;
  const auto wrap = [](u64 v) {
    return static_cast<std::int64_t>(v << (64 - AccWidth)) >> (64 - AccWidth);
  };
  const auto value = [](std::int64_t f) {
    f = std::clamp<std::int64_t>(f, 0, std::int64_t{1} << AccFrac);
    return std::min<std::int64_t>(
        (f + (std::int64_t{1} << (kDrop - 1)) - 1 + ((f >> kDrop) & 1)) >> kDrop,
        (std::int64_t{1} << OutWidth) - 1);
  };
  std::size_t pixels = 0;
  for (std::size_t at = 0; at + Stride <= in.size(); at += Stride) {
    const std::int64_t* w = in.data() + at;
    const std::int64_t x0 = w[0], y0 = w[1], x1 = w[2], y1 = w[3];
    const std::int64_t tri = Numbered ? w[Stride - 1] : 0;
    if (y0 > y1) continue;
    std::int64_t kind[3], q[3], r[3], d[3], dq[3], dr[3];
    for (int k = 0; k < 3; ++k) {
      const std::int64_t* e = w + 4 + 6 * k;
      kind[k] = e[0], q[k] = e[1], r[k] = e[2], d[k] = e[3], dq[k] = e[4], dr[k] = e[5];
    }
    std::int64_t col_f[3], col_gy[3], g0[3], a[3], b[3], c2[3];
    for (int c = 0; c < 3; ++c) {
      const std::int64_t* ch = w + 22 + 6 * c;
      col_f[c] = ch[0], col_gy[c] = ch[1], g0[c] = ch[2], a[c] = ch[3], b[c] = ch[4];
      c2[c] = static_cast<std::int64_t>(static_cast<u64>(ch[5]) << 1);
    }
    for (std::int64_t y = y0;; ++y) {
      std::int64_t lower = x0, upper = x1;
      for (int k = 0; k < 3; ++k) {
        if (kind[k] == 1) lower = std::max(lower, -q[k]);
        if (kind[k] == 2) upper = std::min(upper, q[k]);
      }
      if (lower <= upper) {
        const auto count = static_cast<std::size_t>(upper - lower + 1);
        const std::size_t base = out.size();
        out.resize(base + kOut * count);
        std::int64_t* o = out.data() + base;
        for (std::size_t j = 0; j < count; ++j) {
          o[kOut * j] = lower + static_cast<std::int64_t>(j);
          o[kOut * j + 1] = y;
          if constexpr (Numbered) o[kOut * j + 2] = tri;
        }
        // Laid out as QuadPlan's walk: each pixel's accumulator in closed form, a block of a
        // row's pixels at a time per channel (vectorized), then interleaved.
        const auto i0 = static_cast<u64>(lower - x0);
        constexpr std::size_t kRow = 64;
        alignas(64) std::int64_t v[3][kRow];
        for (std::size_t j0 = 0; j0 < count; j0 += kRow) {
          const std::size_t m = std::min(kRow, count - j0);
#pragma GCC unroll 3
          for (int c = 0; c < 3; ++c) {
            const auto f = static_cast<u64>(col_f[c]), g = static_cast<u64>(g0[c]),
                       ac = static_cast<u64>(a[c]);
            for (std::size_t j = 0; j < m; ++j) {
              const u64 i = i0 + j0 + j;
              v[c][j] = value(wrap(f + i * g + ac * (i * (i - 1))));
            }
          }
          for (std::size_t j = 0; j < m; ++j) {
            for (std::size_t c = 0; c < 3; ++c) o[kOut * (j0 + j) + kC + c] = v[c][j];
          }
        }
        pixels += count;
      }
      if (y == y1) break;
      for (int c = 0; c < 3; ++c) {
        col_f[c] = wrap(static_cast<u64>(col_f[c]) + static_cast<u64>(col_gy[c]));
        col_gy[c] = wrap(static_cast<u64>(col_gy[c]) + static_cast<u64>(c2[c]));
        g0[c] = wrap(static_cast<u64>(g0[c]) + static_cast<u64>(b[c]));
      }
      for (int k = 0; k < 3; ++k) {
        const std::int64_t sum = r[k] + dr[k];
        const bool carry = static_cast<u64>(sum) >= static_cast<u64>(d[k]);
        q[k] = static_cast<std::int64_t>(
                   (static_cast<u64>(q[k]) + static_cast<u64>(dq[k]) + (carry ? 1U : 0U)) << 30) >>
               30;
        r[k] = static_cast<std::int64_t>(static_cast<u64>(carry ? sum - d[k] : sum) & 0xfffff);
      }
    }
  }
  return pixels;
}

}  // namespace phongsim
