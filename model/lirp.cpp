#include "model/lirp.h"

#include <fmt/format.h>

#include <algorithm>

#include "base/error.h"

namespace phongsim {

LirpFormats LirpFormats::from_config(const Config& cfg) {
  LirpFormats f;
  f.p = cfg.format("p");
  f.a = cfg.format("a");
  f.out = cfg.format("out");
  f.out_round = cfg.round("out_round");
  f.out_overflow = cfg.overflow("out_overflow");
  cfg.check_all_used();
  return f;
}

LirpPlan::LirpPlan(const LirpFormats& f)
    : delta_(fx::AddStep::sub(f.p, f.p)),
      sum_(fx::AddStep::add(f.p, fx::mul_format(f.a, delta_.r))),
      out_(sum_.r, f.out, f.out_round, f.out_overflow) {}

void LirpPlan::run(const std::int64_t* in, std::int64_t* out, std::size_t n) const {
  // The plan copied: as far as the compiler knows, the outputs may alias *this, and reloading
  // its constants after each store would keep the loop from vectorizing.
  const LirpPlan plan = *this;
  const auto blocks = [&](auto component) {
    fx::for_each_block<7, 3>(
        in, out, n,
        [&](const std::int64_t* const* soa_in, std::int64_t* const* soa_out, std::size_t m) {
          const std::int64_t* a = soa_in[6];
          for (int c = 0; c < 3; ++c) {
            const std::int64_t* p0 = soa_in[c];
            const std::int64_t* p1 = soa_in[3 + c];
            alignas(64) std::int64_t p[fx::kBlock];  // a local: no aliasing, so it vectorizes
            for (std::size_t i = 0; i < m; ++i) p[i] = component(p0[i], p1[i], a[i]);
            std::copy_n(p, m, soa_out[c]);
          }
        });
  };
  fx::on_kernel_isa([&] {
    if (plan.out_.saturates()) {  // the wrap's operations left out
      blocks([&](std::int64_t p0, std::int64_t p1, std::int64_t a) {
        return plan.out_.saturated(plan.sum(p0, p1, a));
      });
    } else {
      blocks([&](std::int64_t p0, std::int64_t p1, std::int64_t a) {
        return plan.component(p0, p1, a);
      });
    }
  });
}

namespace {

// The exact stage formats, as the RTL derives them; each must fit the model's integers.
const LirpFormats& validated(const LirpFormats& f) {
  const auto stage = [](const char* name, auto&& derive) {
    try {
      return derive();
    } catch (const Error& e) {
      throw Error(fmt::format("stage {}: {}", name, e.what()));
    }
  };
  const fx::Format delta = stage("delta (p1 - p0)", [&] { return fx::sub_format(f.p, f.p); });
  const fx::Format prod = stage("prod (a * delta)", [&] { return fx::mul_format(f.a, delta); });
  (void)stage("out (p0 + prod)", [&] { return fx::add_format(f.p, prod); });
  return f;
}

}  // namespace

LirpModel::LirpModel(const LirpFormats& formats) : f_(validated(formats)), plan_(f_) {
  for (const char* v : {"p0", "p1"}) {
    for (const char* c : {"x", "y", "z"}) inputs_.push_back({fmt::format("{}_{}", v, c), f_.p});
  }
  inputs_.push_back({"a", f_.a});
  for (const char* c : {"x", "y", "z"}) outputs_.push_back({fmt::format("p_{}", c), f_.out});
}

LirpStages LirpModel::component(std::int64_t p0, std::int64_t p1, std::int64_t a) const {
  LirpStages s;
  const fx::Fixed p0_v{p0, f_.p};
  s.delta = fx::sub(fx::Fixed{p1, f_.p}, p0_v);
  s.prod = fx::mul(fx::Fixed{a, f_.a}, s.delta);
  s.sum = fx::add(p0_v, s.prod);
  s.p = fx::resize(s.sum, f_.out, f_.out_round, f_.out_overflow);
  return s;
}

std::size_t LirpModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  for (int c = 0; c < 3; ++c) {
    out.push_back(plan_.usable() ? plan_.component(in[c], in[3 + c], in[6])
                                 : component(in[c], in[3 + c], in[6]).p.raw);
  }
  return 1;
}

std::size_t LirpModel::eval_batch(std::span<const std::int64_t> in, std::vector<std::int64_t>& out,
                                  std::vector<std::uint32_t>* counts) {
  if (!plan_.usable()) return PipelineModel::eval_batch(in, out, counts);
  const std::size_t n = in.size() / 7;
  if (counts != nullptr) counts->insert(counts->end(), n, 1);
  const std::size_t at = out.size();
  out.resize(at + 3 * n);
  plan_.run(in.data(), out.data() + at, n);
  return n;
}

}  // namespace phongsim
