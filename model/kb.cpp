#include "model/kb.h"

#include <fmt/format.h>

#include <type_traits>

namespace phongsim {

KbFormats KbFormats::from_config(const Config& cfg) {
  KbFormats f;
  f.acc = cfg.format("acc");
  f.out = cfg.format("out");
  f.out_round = cfg.round("out_round");
  f.event_bits = static_cast<int>(cfg.param("event_bits", 1, 16));
  if (!f.acc.is_signed) cfg.fail(fmt::format("[format] acc must be signed (got {})", f.acc.str()));
  return f;
}

KbPlan::KbPlan(const KbFormats& f)
    : wrap_shift_(64 - f.acc.width()),
      out_(f.acc, f.out, f.out_round),
      one_(f.acc.int_bits >= 1 ? std::int64_t{1} << f.acc.frac_bits : f.acc.max_raw()) {}

void KbPlan::run(std::int64_t& f, std::int64_t& d1, std::int64_t d2, std::size_t count,
                 std::int64_t* out) const {
  // The forward differences (f += d1, d1 += d2 per pixel, modulo 2^width(acc)) in closed form,
  // f at pixel k = f + k·d1 + d2·k(k - 1)/2: the same modular sums, but each pixel independent
  // of the last, so the loop vectorizes (QuadPlan::walk does the same for rows).
  const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
  const std::uint64_t f0 = u(f), g = u(d1), a = u(d2);
  fx::on_kernel_isa([&] {
    // Locals: stores to `out` may alias the plan and the captures as far as GCC knows.
    const KbPlan plan = *this;
    const std::size_t n = count;
    std::int64_t* const o = out;
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint64_t i = k;
      o[2 * k] = plan.output(plan.wrap(f0 + i * g + a * (i * (i - 1) / 2)));
      o[2 * k + 1] = 0;
    }
  });
  const std::uint64_t n = count;
  f = wrap(f0 + n * g + a * (n * (n - 1) / 2));
  d1 = wrap(g + n * a);
}

KbModel::KbModel(const KbFormats& formats, bool stages)
    : f_(formats), sum_(fx::add_format(f_.acc, f_.acc)), plan_(f_), stages_(stages) {
  if (!plan_.usable()) stages_ = true;
  inputs_ = {{"n", fx::Format{false, KbFormats::kIndexBits, 0}},
             {"count", fx::Format{false, f_.event_bits, 0}},
             {"f", f_.acc},
             {"d1", f_.acc},
             {"d2", f_.acc},
             {"reload", fx::Format{false, 1, 0}}};
  outputs_ = {{"value", f_.out}, {"last", fx::Format{false, 1, 0}}};
}

std::int64_t KbModel::Stages::wrap_add(std::int64_t a, std::int64_t b) const {
  return fx::resize_raw(a + b, m.sum_, m.f_.acc, fx::Round::truncate, fx::Overflow::wrap);
}

std::int64_t KbModel::output(std::int64_t f) const {
  return fx::resize_raw(fx::clamp01_raw(f, f_.acc), f_.acc, f_.out, f_.out_round,
                        fx::Overflow::saturate);
}

template <class Ops>
void KbModel::pixel(const Ops& ops, std::int64_t d1_step, std::int64_t d2_step,
                    std::vector<std::int64_t>& out) {
  out.push_back(ops.output(s_.f));
  out.push_back(s_.i == s_.last ? 1 : 0);
  if (trace_ != nullptr) trace_->push_back(s_.f);
  s_.f = ops.wrap_add(s_.f, d1_step);
  s_.d1 = ops.wrap_add(d1_step, d2_step);
  s_.d2 = d2_step;
  if (s_.i == s_.last) {
    s_.running = false;
  } else {
    ++s_.i;
  }
}

template <class Ops>
void KbModel::steady(const Ops& ops, std::int64_t stop, std::vector<std::int64_t>& out) {
  // pixel() with the span's own steps for pixels i .. stop - 1 (at most to the span's end),
  // written straight into `out`.
  const std::int64_t end = std::min(stop, s_.last + 1);
  if (!s_.running || s_.i >= end) return;
  const auto count = static_cast<std::size_t>(end - s_.i);
  const std::size_t at = out.size();
  out.resize(at + 2 * count);
  std::int64_t* o = out.data() + at;
  bool done = false;
  if constexpr (std::is_same_v<Ops, KbPlan>) {
    // The plan's vectorized run for runs long enough to pay for it (the trace needs each f).
    if (trace_ == nullptr && count >= 16) {
      ops.run(s_.f, s_.d1, s_.d2, count, o);
      done = true;
    }
  }
  if (!done) {
    std::int64_t f = s_.f, d1 = s_.d1;
    const std::int64_t d2 = s_.d2;
    for (std::size_t k = 0; k < count; ++k) {
      if (trace_ != nullptr) trace_->push_back(f);
      o[2 * k] = ops.output(f);
      o[2 * k + 1] = 0;
      f = ops.wrap_add(f, d1);
      d1 = ops.wrap_add(d1, d2);
    }
    s_.f = f;
    s_.d1 = d1;
  }
  if (end == s_.last + 1) {  // the span's last pixel
    o[2 * count - 1] = 1;
    s_.i = s_.last;
    s_.running = false;
  } else {
    s_.i = end;
  }
}

template <class Ops>
std::size_t KbModel::step(const Ops& ops, std::span<const std::int64_t> in,
                          std::vector<std::int64_t>& out) {
  const std::size_t before = out.size();
  const std::int64_t n = in[0];
  if (!s_.running && s_.remaining == 0) {  // a header
    s_.running = true;
    s_.remaining = in[1];
    s_.i = 0;
    s_.last = n;
    s_.f = in[2];
    s_.d1 = in[3];
    s_.d2 = in[4];
  } else if (!s_.running) {  // an event word left over after its span: dropped
    --s_.remaining;
  } else {  // an event word: pixels before its index go out without it
    steady(ops, n, out);
    if (s_.running) {
      pixel(ops, in[5] != 0 ? in[3] : s_.d1, in[4], out);
    }
    --s_.remaining;
  }
  // Once no event can be due, the rest of the span goes out.
  if (s_.running && s_.remaining == 0) steady(ops, s_.last + 1, out);
  return (out.size() - before) / 2;
}

std::size_t KbModel::eval(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  return stages_ ? step(Stages{*this}, in, out) : step(plan_, in, out);
}

}  // namespace phongsim
