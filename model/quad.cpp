#include "model/quad.h"

#include <fmt/format.h>

#include <algorithm>

namespace phongsim {

QuadFormats QuadFormats::from_config(const Config& cfg) {
  QuadFormats f;
  f.acc = cfg.format("acc");
  f.out = cfg.format("out");
  f.out_round = cfg.round("out_round");
  f.sub_bits = static_cast<int>(cfg.param("sub_bits", 1, 8));
  if (!f.acc.is_signed) cfg.fail(fmt::format("[format] acc must be signed (got {})", f.acc.str()));
  return f;
}

QuadPlan::QuadPlan(const QuadFormats& f)
    : out_(f.acc, f.out, f.out_round),
      one_(f.acc.int_bits >= 1 ? std::int64_t{1} << f.acc.frac_bits : f.acc.max_raw()),
      acc_shift_(64 - f.acc.width()),
      q_shift_(64 - f.q_bits()),
      r_mask_((std::uint64_t{1} << f.r_bits()) - 1) {}

template <bool Numbered>
std::size_t QuadPlan::walk_rows(const QuadProgram& p, std::int64_t number,
                                std::vector<std::int64_t>& out) const {
  constexpr std::size_t kStride = Numbered ? 6 : 5;  // x, y, [number,] r, g, b
  constexpr std::size_t kColour = kStride - 3;
  if (p.y0 > p.y1) return 0;
  // The plan copied: stores to `out` may alias *this as far as the compiler knows.
  const QuadPlan plan = *this;
  const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
  std::int64_t col_f[3], col_gy[3], g0[3], c2[3], b[3];
  std::uint64_t a[3];
  for (int c = 0; c < 3; ++c) {
    const QuadChannel& ch = p.channels[c];
    col_f[c] = ch.f;
    col_gy[c] = ch.gy;
    g0[c] = ch.gx;
    a[c] = u(ch.a);
    c2[c] = static_cast<std::int64_t>(u(ch.c) << 1);
    b[c] = ch.b;
  }
  std::int64_t q[3], r[3];
  for (int k = 0; k < 3; ++k) {
    q[k] = p.edges[k].q;
    r[k] = p.edges[k].r;
  }
  std::size_t pixels = 0;
  for (int y = p.y0;; ++y) {
    std::int64_t lower = p.x0;
    std::int64_t upper = p.x1;
    for (int k = 0; k < 3; ++k) {
      if (p.edges[k].kind == 1) lower = std::max(lower, -q[k]);
      if (p.edges[k].kind == 2) upper = std::min(upper, q[k]);
    }
    if (lower <= upper) {
      const auto count = static_cast<std::size_t>(upper - lower + 1);
      const std::size_t at = out.size();
      out.resize(at + kStride * count);
      std::int64_t* o = out.data() + at;
      for (std::size_t j = 0; j < count; ++j) {
        o[kStride * j] = lower + static_cast<std::int64_t>(j);
        o[kStride * j + 1] = y;
        if constexpr (Numbered) o[kStride * j + 2] = number;
      }
      // The row's forward differences (f += g, g += 2a per pixel, all modulo 2^width(acc)) in
      // closed form, f at column i = f + i·gx + a·i·(i - 1): the same modular sums, but each
      // pixel independent of the last, so the loop vectorizes.
      const std::uint64_t i0 = u(lower - p.x0);
      constexpr std::size_t kRow = 64;
      alignas(64) std::int64_t v[3][kRow];
      for (std::size_t j0 = 0; j0 < count; j0 += kRow) {
        const std::size_t m = std::min(kRow, count - j0);
#pragma GCC unroll 3
        for (int c = 0; c < 3; ++c) {
          const std::uint64_t f = u(col_f[c]), g = u(g0[c]), ac = a[c];
          for (std::size_t j = 0; j < m; ++j) {
            const std::uint64_t i = i0 + j0 + j;
            v[c][j] = plan.output(plan.wrap(f + i * g + ac * (i * (i - 1))));
          }
        }
        for (std::size_t j = 0; j < m; ++j) {
          for (std::size_t c = 0; c < 3; ++c) o[kStride * (j0 + j) + kColour + c] = v[c][j];
        }
      }
      pixels += count;
    }
    if (y == p.y1) break;
    for (int c = 0; c < 3; ++c) {
      col_f[c] = plan.wrap(u(col_f[c]) + u(col_gy[c]));
      col_gy[c] = plan.wrap(u(col_gy[c]) + u(c2[c]));
      g0[c] = plan.wrap(u(g0[c]) + u(b[c]));
    }
    for (int k = 0; k < 3; ++k) {
      const QuadEdge& e = p.edges[k];
      const std::int64_t sum = r[k] + e.dr;
      const bool carry = u(sum) >= u(e.d);
      q[k] = static_cast<std::int64_t>((u(q[k]) + u(e.dq) + (carry ? 1U : 0U)) << plan.q_shift_) >>
             plan.q_shift_;
      r[k] = static_cast<std::int64_t>(u(carry ? sum - e.d : sum) & plan.r_mask_);
    }
  }
  return pixels;
}

std::size_t QuadPlan::walk(const QuadProgram& p, std::vector<std::int64_t>& out) const {
  std::size_t n = 0;
  fx::on_kernel_isa([&] { n = walk_rows<false>(p, 0, out); });
  return n;
}

std::size_t QuadPlan::walk(const QuadProgram& p, std::int64_t number,
                           std::vector<std::int64_t>& out) const {
  std::size_t n = 0;
  fx::on_kernel_isa([&] { n = walk_rows<true>(p, number, out); });
  return n;
}

QuadModel::QuadModel(const QuadFormats& formats) : f_(formats), plan_(f_) {
  const fx::Format coord{false, QuadFormats::kCoordBits, 0};
  const fx::Format q{true, f_.q_bits() - 1, 0};
  const fx::Format r{false, f_.r_bits(), 0};
  for (const char* n : {"x0", "y0", "x1", "y1"}) inputs_.push_back({n, coord});
  for (int k = 0; k < 3; ++k) {
    inputs_.push_back({fmt::format("e{}_kind", k), fx::Format{false, 2, 0}});
    inputs_.push_back({fmt::format("e{}_q", k), q});
    inputs_.push_back({fmt::format("e{}_r", k), r});
    inputs_.push_back({fmt::format("e{}_d", k), r});
    inputs_.push_back({fmt::format("e{}_dq", k), q});
    inputs_.push_back({fmt::format("e{}_dr", k), r});
  }
  for (const char* ch : {"r", "g", "b"}) {
    for (const char* w : {"f", "gy", "gx", "a", "b", "c"}) {
      inputs_.push_back({fmt::format("{}_{}", ch, w), f_.acc});
    }
  }
  outputs_ = {{"x", coord}, {"y", coord}, {"r", f_.out}, {"g", f_.out}, {"b", f_.out}};
}

QuadProgram QuadModel::program(std::span<const std::int64_t> in) {
  QuadProgram p;
  p.x0 = static_cast<int>(in[0]);
  p.y0 = static_cast<int>(in[1]);
  p.x1 = static_cast<int>(in[2]);
  p.y1 = static_cast<int>(in[3]);
  for (int k = 0; k < 3; ++k) {
    const auto w = in.subspan(4 + 6 * k, 6);
    p.edges[k] = {static_cast<int>(w[0]), w[1], w[2], w[3], w[4], w[5]};
  }
  for (int c = 0; c < 3; ++c) {
    const auto w = in.subspan(22 + 6 * c, 6);
    p.channels[c] = {w[0], w[1], w[2], w[3], w[4], w[5]};
  }
  return p;
}

std::vector<std::int64_t> QuadModel::words(const QuadProgram& p) {
  std::vector<std::int64_t> w{p.x0, p.y0, p.x1, p.y1};
  for (const auto& e : p.edges) w.insert(w.end(), {e.kind, e.q, e.r, e.d, e.dq, e.dr});
  for (const auto& c : p.channels) w.insert(w.end(), {c.f, c.gy, c.gx, c.a, c.b, c.c});
  return w;
}

std::size_t QuadModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  const QuadProgram p = program(in);
  return plan_.usable() ? plan_.walk(p, out) : walk(p, out);
}

std::size_t QuadModel::walk(const QuadProgram& p, std::vector<std::int64_t>& out,
                            std::vector<std::int64_t>* accumulators,
                            std::vector<QuadRowTrace>* rows) const {
  if (p.y0 > p.y1) return 0;
  const fx::Format qf{true, f_.q_bits() - 1, 0};
  const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
  // Column accumulators per channel (at offset i = 0): F, GY, G0.
  std::array<std::int64_t, 3> col_f{}, col_gy{}, g0{};
  for (int c = 0; c < 3; ++c) {
    col_f[c] = p.channels[c].f;
    col_gy[c] = p.channels[c].gy;
    g0[c] = p.channels[c].gx;
  }
  std::array<std::int64_t, 3> q{}, r{};
  for (int k = 0; k < 3; ++k) {
    q[k] = p.edges[k].q;
    r[k] = p.edges[k].r;
  }
  std::size_t pixels = 0;
  for (int y = p.y0;; ++y) {
    // The row's span.
    std::int64_t lower = p.x0;
    std::int64_t upper = p.x1;
    QuadRowTrace row{.y = y};
    for (int k = 0; k < 3; ++k) {
      if (p.edges[k].kind == 1 && -q[k] > lower) {
        lower = -q[k];
        row.lower_edge = k;
        row.lower_r = r[k];
        row.lower_d = p.edges[k].d;
      }
      if (p.edges[k].kind == 2 && q[k] < upper) {
        upper = q[k];
        row.upper_edge = k;
        row.upper_r = r[k];
        row.upper_d = p.edges[k].d;
      }
    }
    if (rows != nullptr) {
      row.lower = lower;
      row.upper = upper;
      rows->push_back(row);
    }
    if (lower <= upper) {
      const std::int64_t i0 = lower - p.x0;  // the row's first pixel, from the box's left column
      std::array<std::int64_t, 3> f{}, g{};
      for (int c = 0; c < 3; ++c) {
        const QuadChannel& ch = p.channels[c];
        // f = F + i0·G0 + a·i0(i0 - 1);  g = G0 + 2a·i0   (modulo 2^width, as the RTL)
        f[c] = wrap(u(col_f[c]) + u(i0) * u(g0[c]) + u(ch.a) * (u(i0) * (u(i0) - 1)));
        g[c] = wrap(u(g0[c]) + ((u(ch.a) * u(i0)) << 1));
      }
      for (std::int64_t x = lower; x <= upper; ++x) {
        out.push_back(x);
        out.push_back(y);
        for (int c = 0; c < 3; ++c) {
          out.push_back(fx::resize_raw(fx::clamp01_raw(f[c], f_.acc), f_.acc, f_.out, f_.out_round,
                                       fx::Overflow::saturate));
          if (accumulators != nullptr) accumulators->push_back(f[c]);
          f[c] = wrap(u(f[c]) + u(g[c]));
          g[c] = wrap(u(g[c]) + (u(p.channels[c].a) << 1));
        }
        ++pixels;
      }
    }
    if (y == p.y1) break;
    // Next row: column accumulators and edge DDAs.
    for (int c = 0; c < 3; ++c) {
      col_f[c] = wrap(u(col_f[c]) + u(col_gy[c]));
      col_gy[c] = wrap(u(col_gy[c]) + (u(p.channels[c].c) << 1));
      g0[c] = wrap(u(g0[c]) + u(p.channels[c].b));
    }
    for (int k = 0; k < 3; ++k) {
      const QuadEdge& e = p.edges[k];
      const std::int64_t sum = r[k] + e.dr;  // r, dr < 2^r_bits: no overflow
      const bool carry = static_cast<std::uint64_t>(sum) >= static_cast<std::uint64_t>(e.d);
      q[k] = fx::from_bits(u(q[k]) + u(e.dq) + (carry ? 1U : 0U), qf);
      r[k] = carry ? sum - e.d : sum;
      r[k] = static_cast<std::int64_t>(static_cast<std::uint64_t>(r[k]) &
                                       ((std::uint64_t{1} << f_.r_bits()) - 1));
    }
  }
  return pixels;
}

}  // namespace phongsim
