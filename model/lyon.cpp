#include "model/lyon.h"

#include <fmt/format.h>

#include "base/error.h"

namespace phongsim {
namespace {

const fx::Fixed kOne{1, fx::Format{false, 1, 0}};  // the constant 1 as the RTL writes it

fx::Fixed dot3(const Vec3Fx& a, const Vec3Fx& b) {
  // (x + y) + z, as rtl/common/fx_dot3.sv; exact (fx_dot3 then rounds once: rq(dot3(a, b), F)).
  return fx::add(fx::add(fx::mul(a[0], b[0]), fx::mul(a[1], b[1])), fx::mul(a[2], b[2]));
}

// x >= 1 for an unsigned value: any bit above the binary point.
bool at_least_one(fx::Fixed x) { return x.fmt.int_bits > 0 && (x.raw >> x.fmt.frac_bits) != 0; }

Vec3Fx vec(const std::array<std::int64_t, 3>& raw, fx::Format fmt) {
  return {fx::Fixed{raw[0], fmt}, fx::Fixed{raw[1], fmt}, fx::Fixed{raw[2], fmt}};
}

}  // namespace

LyonFormats LyonFormats::from_config(const Config& cfg) {
  LyonFormats f;
  f.arrangement = static_cast<int>(cfg.param("arrangement", 7, 8));
  f.halfway = cfg.param("halfway", 0, 1) != 0;
  f.norm = static_cast<int>(cfg.param("norm", 0, 2));
  f.k = static_cast<int>(cfg.param("k", 0, 3));
  if (f.halfway) f.h_norm = static_cast<int>(cfg.param("h_norm", 0, 2));
  f.round = cfg.round("round");

  f.vec = cfg.format("vec");
  f.a = cfg.format("a");
  f.shin = cfg.format("shin");
  f.np = cfg.format("np");
  f.n = cfg.format("n");
  f.dot = cfg.format("dot");
  f.r = cfg.format("r");
  f.d = cfg.format("d");
  f.xf = cfg.format("xf");
  f.sq = cfg.format("sq");
  f.spec = cfg.format("spec");
  f.diff = cfg.format("diff");
  if (f.uses_norm()) {
    f.z = cfg.format("z");
    f.y = cfg.format("y");
    f.g = cfg.format("g");
  }
  if (f.halfway) f.h = cfg.format("h");
  if (f.arrangement == 7) {
    f.dd = cfg.format("dd");
  } else {
    f.dabs = cfg.format("dabs");
    f.w = cfg.format("w");
  }
  cfg.check_all_used();

  // The shape path, shininess and outputs are magnitudes: the RTL treats them as unsigned.
  const std::pair<const char*, fx::Format> must_be_unsigned[] = {
      {"shin", f.shin},
      {"xf", f.xf},
      {"sq", f.sq},
      {"spec", f.spec},
      {"diff", f.diff},
      {"dd", f.arrangement == 7 ? f.dd : fx::Format{}},
      {"dabs", f.arrangement == 8 ? f.dabs : fx::Format{}},
      {"w", f.arrangement == 8 ? f.w : fx::Format{}}};
  for (const auto& [key, fmt] : must_be_unsigned) {
    if (fmt.is_signed)
      cfg.fail(fmt::format("[format] {} must be unsigned (got {})", key, fmt.str()));
  }
  return f;
}

LyonModel::LyonModel(const LyonFormats& formats) : f_(formats) {
  for (const char* v : {"n0", "n1"}) {
    for (const char* c : {"x", "y", "z"}) inputs_.push_back({fmt::format("{}_{}", v, c), f_.vec});
  }
  inputs_.push_back({"a", f_.a});
  for (const char* v : {"v", "l"}) {
    for (const char* c : {"x", "y", "z"}) inputs_.push_back({fmt::format("{}_{}", v, c), f_.vec});
  }
  inputs_.push_back({"shin", f_.shin});
  outputs_.push_back({"spec", f_.spec});
  outputs_.push_back({"diff", f_.diff});
  // Every operation's format is data-independent: one evaluation derives (and checks) them all.
  (void)stages({0, 0, 0}, {0, 0, 0}, 0, {0, 0, 0}, {0, 0, 0}, 0);
  plan_ = LyonPlan(f_);
}

constexpr std::string_view kSqNames[] = {"sq_0", "sq_1", "sq_2", "sq_3"};

fx::Fixed LyonModel::rq(fx::Fixed x, fx::Format to, std::string_view point,
                        std::vector<LyonRqSide>* sides) const {
  if (sides != nullptr)
    sides->push_back({point, fx::resize_side(x.raw, x.fmt, to, f_.round), x.fmt, to});
  return fx::resize(x, to, f_.round, fx::Overflow::saturate);
}

LyonNormStages LyonModel::normalize(const Vec3Fx& in, fx::Format out, int order, bool h,
                                    std::vector<LyonRqSide>* sides) const {
  LyonNormStages s;
  const std::string_view out_name = h ? "hn" : "n";
  if (order == 0) {
    for (int c = 0; c < 3; ++c) s.out[c] = rq(in[c], out, out_name, sides);
    return s;
  }
  s.z = rq(dot3(in, in), f_.z, h ? "hn.z" : "n.z", sides);
  s.y = rq(fx::sub(kOne, s.z), f_.y, h ? "hn.y" : "n.y", sides);
  const fx::Fixed poly = order == 1 ? s.y : fx::add(s.y, fx::mul(s.y, s.y));
  s.g = rq(fx::add(kOne, fx::scale(poly, -1)), f_.g, h ? "hn.g" : "n.g", sides);
  for (int c = 0; c < 3; ++c) s.out[c] = rq(fx::mul(s.g, in[c]), out, out_name, sides);
  return s;
}

LyonStages LyonModel::stages(const std::array<std::int64_t, 3>& n0,
                             const std::array<std::int64_t, 3>& n1, std::int64_t a,
                             const std::array<std::int64_t, 3>& v_raw,
                             const std::array<std::int64_t, 3>& l_raw, std::int64_t shin_raw,
                             std::vector<LyonRqSide>* sides) const {
  LyonStages s;
  const Vec3Fx v = vec(v_raw, f_.vec);
  const Vec3Fx l = vec(l_raw, f_.vec);
  const fx::Fixed shin{shin_raw, f_.shin};
  const fx::Fixed a_fx{a, f_.a};

  // Stages 0-2: N' = LIRP(N0, N1, a) = round(n0 + a·(n1 - n0)), as lirp_core.sv.
  for (int c = 0; c < 3; ++c) {
    const fx::Fixed p0{n0[c], f_.vec};
    const fx::Fixed delta = fx::sub(fx::Fixed{n1[c], f_.vec}, p0);
    s.np[c] = rq(fx::add(p0, fx::mul(a_fx, delta)), f_.np, "np", sides);
  }
  // Stages 3-5: N.
  s.n = normalize(s.np, f_.n, f_.norm, false, sides);
  const Vec3Fx& n = s.n.out;
  // Stage 6: diff, the diffuse term N·L (negative values saturate to 0).
  s.diff = rq(dot3(n, l), f_.diff, "diff", sides);

  // Stages 2-8: D.
  if (!f_.halfway) {
    s.dot = rq(dot3(n, v), f_.dot, "dot", sides);
    for (int c = 0; c < 3; ++c) {
      s.r[c] = rq(fx::sub(fx::scale(fx::mul(s.dot, n[c]), 1), v[c]), f_.r, "r", sides);
      s.d[c] = rq(fx::sub(s.r[c], l[c]), f_.d, "d", sides);
    }
  } else {
    for (int c = 0; c < 3; ++c) s.h[c] = rq(fx::scale(fx::add(l[c], v[c]), -1), f_.h, "h", sides);
    s.hn = normalize(s.h, f_.h, f_.h_norm, true, sides);
    const Vec3Fx& h = s.hn.out;
    s.dot = rq(dot3(h, n), f_.dot, "dot", sides);
    for (int c = 0; c < 3; ++c) {
      s.r[c] = rq(fx::mul(s.dot, n[c]), f_.r, "r", sides);
      s.d[c] = rq(fx::sub(h[c], s.r[c]), f_.d, "d", sides);
    }
  }

  // Stages 9-10: x/2^k.
  if (f_.arrangement == 7) {
    s.dd = rq(dot3(s.d, s.d), f_.dd, "dd", sides);
    const fx::Fixed x2 = fx::scale(fx::mul(shin, s.dd), f_.halfway ? 2 : 0);  // 2x (n -> 4n)
    s.xk = fx::scale(x2, -(f_.k + 1));
    s.zero = at_least_one(s.xk);
  } else {
    // (m|D|)² = 2x, so x/2^k = (m|D|/2^s)² · 2^e with s = ceil((k+1)/2), e = 2s - (k+1).
    const int shift = (f_.k + 2) / 2;
    const int e = 2 * shift - (f_.k + 1);
    for (int c = 0; c < 3; ++c) {
      s.dabs[c] = rq(fx::abs(s.d[c]), f_.dabs, "dabs", sides);
      const fx::Fixed u = fx::scale(fx::mul(shin, s.dabs[c]), (f_.halfway ? 1 : 0) - shift);
      s.big = s.big || at_least_one(u);
      s.w[c] = rq(u, f_.w, "w", sides);
    }
    s.xk = fx::scale(dot3(s.w, s.w), e);
    s.zero = s.big || at_least_one(s.xk);
  }
  s.xf = rq(s.xk, f_.xf, "xf", sides);

  // Stages 11..: sq_0 = 1 - x/2^k, sq_j = sq_(j-1)², spec = f_k = sq_k, zero when x/2^k >= 1.
  s.sq[0] = rq(fx::sub(kOne, s.xf), f_.sq, "sq_0", sides);
  for (int j = 1; j <= f_.k; ++j)
    s.sq[j] = rq(fx::mul(s.sq[j - 1], s.sq[j - 1]), f_.sq, kSqNames[j], sides);
  s.spec = s.zero ? fx::Fixed{0, f_.spec} : rq(s.sq[f_.k], f_.spec, "spec", sides);
  return s;
}

std::size_t LyonModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  if (plan_.usable()) {
    std::int64_t results[2];  // spec, diff
    plan_.run(in.data(), results, 1);
    out.insert(out.end(), results, results + 2);
    return 1;
  }
  const LyonStages s = stages({in[0], in[1], in[2]}, {in[3], in[4], in[5]}, in[6],
                              {in[7], in[8], in[9]}, {in[10], in[11], in[12]}, in[13]);
  out.push_back(s.spec.raw);
  out.push_back(s.diff.raw);
  return 1;
}

std::size_t LyonModel::eval_batch(std::span<const std::int64_t> in, std::vector<std::int64_t>& out,
                                  std::vector<std::uint32_t>* counts) {
  if (!plan_.usable()) return PipelineModel::eval_batch(in, out, counts);
  const std::size_t n = in.size() / 14;
  if (counts != nullptr) counts->insert(counts->end(), n, 1);
  const std::size_t at = out.size();
  out.resize(at + 2 * n);
  plan_.run(in.data(), out.data() + at, n);
  return n;
}

}  // namespace phongsim
