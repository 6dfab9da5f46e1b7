#include "model/kb_setup.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "model/plan.h"

namespace phongsim {
namespace {

// inline: kb_span_values calls it on the kernel instruction set (fx::on_kernel_isa).
inline double theta(const KbTerm& t, int i) { return t.theta0 + i * t.dtheta; }

}  // namespace

KbSetupOptions KbSetupOptions::from_config(const Config& cfg) {
  KbSetupOptions o;
  o.policy = cfg.setup("policy", {"d2_only", "exact_reload"}) == "d2_only" ? KbPolicy::d2_only
                                                                           : KbPolicy::exact_reload;
  o.ab = cfg.setup("ab", {"closed_form", "least_squares"}) == "closed_form"
             ? KbAbSource::closed_form
             : KbAbSource::least_squares;
  o.max_terms = static_cast<int>(cfg.setup_integer("terms", 1, 4));
  return o;
}

kb::QuadParams kb_params(double n, KbAbSource source) {
  return source == KbAbSource::closed_form ? kb::closed_form(n)
                                           : kb::least_squares(static_cast<int>(n));
}

double kb_exact(const KbSpan& span, int i) {
  double sum = 0;
  for (const auto& t : span.terms) sum += t.scale * kb::quad(theta(t, i), t.ab);
  return sum;
}

// A term at a time, so that the loops over pixels vectorize (fx::on_kernel_isa, the sections'
// formulas branch-free; this file is compiled without FMA contraction): per pixel what kb_exact
// and kb::section_of compute. A span's setup did them one pixel at a time, which was most of a
// kb co-simulation's stimulus.
void kb_span_values(const KbSpan& span, int n, double* exact, std::uint8_t* changes) {
  for (const KbTerm& t : span.terms) kb::check_params(t.ab);
  std::fill(exact, exact + n, 0.0);
  std::fill(changes, changes + n - 1, 0);
  bool nan = false;
  fx::on_kernel_isa([&] {
    std::vector<int> section(static_cast<std::size_t>(n));
    int* const sec = section.data();
    for (const KbTerm& term : span.terms) {
      const KbTerm t = term;  // a copy: the stores to exact[] may alias the span's terms
      bool term_nan = false;
      for (int i = 0; i < n; ++i) {
        const double th = theta(t, i);
        exact[i] += t.scale * kb::detail::quad_unchecked(th, t.ab);
        sec[i] = kb::detail::section_unchecked(th, t.ab);
        term_nan |= th != th;
      }
      for (int i = 0; i + 1 < n; ++i) changes[i] |= sec[i] != sec[i + 1] ? 1 : 0;
      nan |= term_nan;
    }
  });
  if (nan) kb::detail::nan_theta();  // as kb::section_of would have
}

std::vector<std::vector<std::int64_t>> kb_program(const KbSpan& span, KbPolicy policy,
                                                  const KbFormats& formats) {
  const int length = span.length;
  if (length < 1 || length > 4096) {
    throw Error(fmt::format("a span has 1 to 4096 pixels, not {}", length));
  }
  const auto q = [&formats](double x) {
    return fx::quantize(x, formats.acc, fx::Round::half_even, fx::Overflow::saturate);
  };
  std::vector<double> exact(static_cast<std::size_t>(length) + 2);
  std::vector<std::uint8_t> changed(static_cast<std::size_t>(length) + 1);
  kb_span_values(span, length + 2, exact.data(), changed.data());
  const auto second = [&exact](int i) { return exact[i + 2] - 2 * exact[i + 1] + exact[i]; };
  // Pixel i + 1's sections (which quadratic each term is on) differ from pixel i's.
  const auto changes = [&changed](int i) { return changed[static_cast<std::size_t>(i)] != 0; };

  std::vector<std::vector<std::int64_t>> events;
  std::int64_t f0 = q(exact[0]);
  std::int64_t d1 = 0;
  std::int64_t d2 = 0;
  if (policy == KbPolicy::exact_reload) {
    // Δ²f changes wherever the three pixels a second difference spans change sections; there
    // Δf is reloaded with the exact difference, so f is exact at every pixel (before rounding).
    d1 = q(exact[1] - exact[0]);
    d2 = q(second(0));
    for (int i = 1; i + 1 < length; ++i) {
      // The second difference at i spans pixels i..i+2: it changes when their sections do.
      if (changes(i - 1) || changes(i) || changes(i + 1)) {
        events.push_back({i, 0, 0, q(exact[i + 1] - exact[i]), q(second(i)), 1});
      }
    }
  } else {
    // The paper: Δf starts as the first section's difference and is never reloaded; where a
    // term enters another section between pixels i and i + 1, Δ²f becomes the new sections'
    // second difference (2·c2·Δθ² per term) for the steps from pixel i on.
    const auto pure_d2 = [&span](int i) {
      double sum = 0;
      for (const auto& t : span.terms) {
        const kb::Section p = kb::section_poly(kb::section_of(theta(t, i), t.ab), t.ab);
        sum += t.scale * 2 * p.c2 * t.dtheta * t.dtheta;
      }
      return sum;
    };
    double first_d1 = 0;
    for (const auto& t : span.terms) {
      const kb::Section p = kb::section_poly(kb::section_of(theta(t, 0), t.ab), t.ab);
      const auto poly = [&p](double x) { return (p.c2 * x + p.c1) * x + p.c0; };
      first_d1 += t.scale * (poly(theta(t, 1)) - poly(theta(t, 0)));
    }
    d1 = q(first_d1);
    d2 = q(pure_d2(0));
    for (int i = 0; i + 1 < length; ++i) {
      if (changes(i)) {
        events.push_back({i, 0, 0, 0, q(pure_d2(i + 1)), 0});
      }
    }
  }
  const std::uint64_t max_events = (std::uint64_t{1} << formats.event_bits) - 1;
  if (events.size() > max_events) {
    throw Error(fmt::format("the span needs {} events; event_bits = {} allows {}", events.size(),
                            formats.event_bits, max_events));
  }
  std::vector<std::vector<std::int64_t>> words{
      {length - 1, static_cast<std::int64_t>(events.size()), f0, d1, d2, 0}};
  words.insert(words.end(), events.begin(), events.end());
  return words;
}

}  // namespace phongsim
