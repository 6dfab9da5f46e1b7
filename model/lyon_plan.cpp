#include "model/lyon_plan.h"

#include <algorithm>
#include <cstdlib>
#include <type_traits>

#include "model/lyon.h"

namespace phongsim {
namespace {

constexpr fx::Format kOneFmt{false, 1, 0};  // the constant 1 as the RTL writes it (raw 1)

}  // namespace

fx::Saturate LyonPlan::rq(fx::Format from, fx::Format to) {
  const fx::Saturate r(from, to, round_);
  usable_ = usable_ && r.fits_int64();
  return r;
}

LyonPlan::Norm LyonPlan::norm(fx::Format in, fx::Format out, int order, const LyonFormats& f) {
  Norm s;
  s.order = order;
  if (order == 0) {
    s.plain = rq(in, out);
    return s;
  }
  s.zz = Dot3Step::of(in, in);
  s.z = rq(s.zz.result(), f.z);
  s.y_sub = fx::AddStep::sub(kOneFmt, f.z);
  s.y = rq(s.y_sub.r, f.y);
  fx::Format poly = f.y;
  if (order == 2) {
    s.poly = fx::AddStep::add(f.y, fx::mul_format(f.y, f.y));
    poly = s.poly.r;
  }
  s.half = fx::ScaleStep::of(poly, -1);
  s.g_add = fx::AddStep::add(kOneFmt, s.half.r);
  s.g = rq(s.g_add.r, f.g);
  s.out = rq(fx::mul_format(f.g, in), out);
  return s;
}

LyonPlan::LyonPlan(const LyonFormats& f)
    : round_(f.round), halfway_(f.halfway), arrangement_(f.arrangement), k_(f.k) {
  delta_ = fx::AddStep::sub(f.vec, f.vec);
  lirp_ = fx::AddStep::add(f.vec, fx::mul_format(f.a, delta_.r));
  np_ = rq(lirp_.r, f.np);
  n_norm_ = norm(f.np, f.n, f.norm, f);
  nl_ = Dot3Step::of(f.n, f.vec);
  diff_ = rq(nl_.result(), f.diff);
  if (!f.halfway) {
    dot_in_ = Dot3Step::of(f.n, f.vec);
    dot_ = rq(dot_in_.result(), f.dot);
    r_two_ = fx::ScaleStep::of(fx::mul_format(f.dot, f.n), 1);
    r_sub_ = fx::AddStep::sub(r_two_.r, f.vec);
    r_ = rq(r_sub_.r, f.r);
    d_sub_ = fx::AddStep::sub(f.r, f.vec);
  } else {
    lv_ = fx::AddStep::add(f.vec, f.vec);
    lv_half_ = fx::ScaleStep::of(lv_.r, -1);
    h_ = rq(lv_half_.r, f.h);
    h_norm_ = norm(f.h, f.h, f.h_norm, f);
    dot_in_ = Dot3Step::of(f.h, f.n);
    dot_ = rq(dot_in_.result(), f.dot);
    r_ = rq(fx::mul_format(f.dot, f.n), f.r);
    d_sub_ = fx::AddStep::sub(f.h, f.r);
  }
  d_ = rq(d_sub_.r, f.d);
  fx::Format xk;
  if (f.arrangement == 7) {
    dd_in_ = Dot3Step::of(f.d, f.d);
    dd_ = rq(dd_in_.result(), f.dd);
    x2_ = fx::ScaleStep::of(fx::mul_format(f.shin, f.dd), f.halfway ? 2 : 0);
    xk_ = fx::ScaleStep::of(x2_.r, -(f.k + 1));
    xk = xk_.r;
  } else {
    const int shift = (f.k + 2) / 2;
    const int e = 2 * shift - (f.k + 1);
    dabs_ = rq(fx::abs_format(f.d), f.dabs);
    u_ = fx::ScaleStep::of(fx::mul_format(f.shin, f.dabs), (f.halfway ? 1 : 0) - shift);
    u_big_ = fx::AtLeastOne::of(u_.r);
    w_ = rq(u_.r, f.w);
    ww_ = Dot3Step::of(f.w, f.w);
    wk_ = fx::ScaleStep::of(ww_.result(), e);
    xk = wk_.r;
  }
  zero_ = fx::AtLeastOne::of(xk);
  xf_ = rq(xk, f.xf);
  sq_sub_ = fx::AddStep::sub(kOneFmt, f.xf);
  sq0_ = rq(sq_sub_.r, f.sq);
  sqj_ = rq(fx::mul_format(f.sq, f.sq), f.sq);
  spec_ = rq(f.sq, f.spec);
}

void LyonPlan::run(const std::int64_t* in, std::int64_t* out, std::size_t n) const {
  fx::on_kernel_isa([&] {
    fx::for_each_block<14, 2>(
        in, out, n,
        [this](const std::int64_t* const* soa_in, std::int64_t* const* soa_out, std::size_t m) {
          block(soa_in, soa_out, m);
        });
  });
}

void LyonPlan::Norm::run(const Block* src, Block* dst, std::size_t m) const {
  if (order == 0) {
    for (int c = 0; c < 3; ++c) {
      for (std::size_t i = 0; i < m; ++i) dst[c][i] = plain(src[c][i]);
    }
    return;
  }
  // The steps copied: as far as the compiler knows, dst may alias *this, and reloading every
  // step's constants after each store would keep the loop from vectorizing.
  const Norm s = *this;
  const auto each = [&](auto square) {
    for (std::size_t i = 0; i < m; ++i) {
      const std::int64_t x = src[0][i], y0 = src[1][i], z0 = src[2][i];
      const std::int64_t zv = s.z(s.zz(x, y0, z0, x, y0, z0));
      const std::int64_t yv = s.y(s.y_sub.diff(1, zv));
      std::int64_t p = yv;
      if constexpr (decltype(square)::value) p = s.poly.sum(yv, yv * yv);
      const std::int64_t gv = s.g(s.g_add.sum(1, s.half(p)));
      dst[0][i] = s.out(gv * x);
      dst[1][i] = s.out(gv * y0);
      dst[2][i] = s.out(gv * z0);
    }
  };
  if (order == 2) {
    each(std::true_type{});
  } else {
    each(std::false_type{});
  }
}

void LyonPlan::block(const std::int64_t* const* in, std::int64_t* const* out, std::size_t m) const {
  const std::int64_t* const* n0 = in;
  const std::int64_t* const* n1 = in + 3;
  const std::int64_t* a = in[6];
  const std::int64_t* const* v = in + 7;
  const std::int64_t* const* l = in + 10;
  const std::int64_t* shin = in[13];
  alignas(64) Block np[3], nv[3], h[3], hn[3], d[3], xf, zero, sq;

  // Stages 0-2: N' = LIRP(N0, N1, a).
  for (int c = 0; c < 3; ++c) {
    for (std::size_t i = 0; i < m; ++i) {
      np[c][i] = np_(lirp_.sum(n0[c][i], a[i] * delta_.diff(n1[c][i], n0[c][i])));
    }
  }
  // Stages 3-5: N. Stage 6: the diffuse term.
  n_norm_.run(np, nv, m);
  for (std::size_t i = 0; i < m; ++i) {
    out[1][i] = diff_(nl_(nv[0][i], nv[1][i], nv[2][i], l[0][i], l[1][i], l[2][i]));
  }
  // Stages 2-8: D.
  if (!halfway_) {
    for (std::size_t i = 0; i < m; ++i) {
      const std::int64_t dot =
          dot_(dot_in_(nv[0][i], nv[1][i], nv[2][i], v[0][i], v[1][i], v[2][i]));
      for (int c = 0; c < 3; ++c) {
        const std::int64_t r = r_(r_sub_.diff(r_two_(dot * nv[c][i]), v[c][i]));
        d[c][i] = d_(d_sub_.diff(r, l[c][i]));
      }
    }
  } else {
    for (int c = 0; c < 3; ++c) {
      for (std::size_t i = 0; i < m; ++i) h[c][i] = h_(lv_half_(lv_.sum(l[c][i], v[c][i])));
    }
    h_norm_.run(h, hn, m);
    for (std::size_t i = 0; i < m; ++i) {
      const std::int64_t dot =
          dot_(dot_in_(hn[0][i], hn[1][i], hn[2][i], nv[0][i], nv[1][i], nv[2][i]));
      for (int c = 0; c < 3; ++c) d[c][i] = d_(d_sub_.diff(hn[c][i], r_(dot * nv[c][i])));
    }
  }
  // Stages 9-10: x/2^k, the comparator, xf.
  if (arrangement_ == 7) {
    for (std::size_t i = 0; i < m; ++i) {
      const std::int64_t dd = dd_(dd_in_(d[0][i], d[1][i], d[2][i], d[0][i], d[1][i], d[2][i]));
      const std::int64_t xk = xk_(x2_(shin[i] * dd));
      zero[i] = zero_(xk) ? 1 : 0;
      xf[i] = xf_(xk);
    }
  } else {
    for (std::size_t i = 0; i < m; ++i) {
      std::int64_t w[3];
      bool big = false;  // | rather than ||: no branch in the loop
      for (int c = 0; c < 3; ++c) {
        const std::int64_t u = u_(shin[i] * dabs_(std::abs(d[c][i])));
        big = big | u_big_(u);
        w[c] = w_(u);
      }
      const std::int64_t xk = wk_(ww_(w[0], w[1], w[2], w[0], w[1], w[2]));
      zero[i] = big | zero_(xk) ? 1 : 0;
      xf[i] = xf_(xk);
    }
  }
  // Stages 11..: sq_0 = 1 - xf, sq_j = sq_(j-1)², spec = sq_k or 0.
  for (std::size_t i = 0; i < m; ++i) sq[i] = sq0_(sq_sub_.diff(1, xf[i]));
  for (int j = 1; j <= k_; ++j) {
    for (std::size_t i = 0; i < m; ++i) sq[i] = sqj_(sq[i] * sq[i]);
  }
  for (std::size_t i = 0; i < m; ++i) {
    const std::int64_t spec = spec_(sq[i]);
    sq[i] = zero[i] != 0 ? 0 : spec;
  }
  std::copy_n(sq, m, out[0]);
}

}  // namespace phongsim
