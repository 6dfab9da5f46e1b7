#include "model/lirp.h"

#include <fmt/format.h>

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

LirpModel::LirpModel(const LirpFormats& formats) : f_(formats) {
  // The exact stage formats, as the RTL derives them; each must fit the model's integers.
  const auto stage = [](const char* name, auto&& derive) {
    try {
      return derive();
    } catch (const Error& e) {
      throw Error(fmt::format("stage {}: {}", name, e.what()));
    }
  };
  const fx::Format delta = stage("delta (p1 - p0)", [&] { return fx::sub_format(f_.p, f_.p); });
  const fx::Format prod = stage("prod (a * delta)", [&] { return fx::mul_format(f_.a, delta); });
  (void)stage("out (p0 + prod)", [&] { return fx::add_format(f_.p, prod); });
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
  for (int c = 0; c < 3; ++c) out.push_back(component(in[c], in[3 + c], in[6]).p.raw);
  return 1;
}

}  // namespace phongsim
