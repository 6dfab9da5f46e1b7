// The Kuijk–Blake engine model (model/kb.h) on hand-computed programs, the span setup
// (model/kb_setup.h) against the exact span, and the drift figures docs/kb.md states.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "base/error.h"
#include "base/rng.h"
#include "model/config.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "model/plan.h"
#include "sim/pipelines/kb.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

KbFormats Formats(int guard_bits, int out_frac = 8) {
  KbFormats f;
  f.acc = fx::Format{true, 2, out_frac + guard_bits};
  f.out = fx::Format{false, 0, out_frac};
  f.event_bits = 6;
  return f;
}

// Runs words through the engine; returns (value, last) pairs flattened.
std::vector<std::int64_t> Feed(KbModel& m, const std::vector<std::vector<std::int64_t>>& words) {
  std::vector<std::int64_t> out;
  for (const auto& w : words) m.eval(w, out);
  return out;
}

// acc S2.8 (no guard bits) and out 0.8: raw accumulator values are output LSBs.
TEST(KbEngine, ForwardDifferencesWithoutEvents) {
  KbModel m(Formats(0));
  // f = 10, d1 = 3, d2 = 1: 10, 13, 17, 22 (f += d1, d1 += d2).
  EXPECT_EQ(Feed(m, {{3, 0, 10, 3, 1, 0}}),
            (std::vector<std::int64_t>{10, 0, 13, 0, 17, 0, 22, 1}));
}

TEST(KbEngine, EventsChangeTheStepAfterTheirPixel) {
  KbModel m(Formats(0));
  // Event at pixel 1: d2 <- -2, d1 <- 5 (reload). Pixels: 10, 13 (event), 18, 21, 22.
  // Step 1->2 uses d1 = 5, then d1 = 5 - 2 = 3; 2->3: 18 + 3 = 21, d1 = 1; 3->4: 22.
  EXPECT_EQ(Feed(m, {{4, 1, 10, 3, 1, 0}, {1, 0, 0, 5, -2, 1}}),
            (std::vector<std::int64_t>{10, 0, 13, 0, 18, 0, 21, 0, 22, 1}));
  // The same event without reload keeps d1 = 4 (3 + 1): 10, 13, 17, 19, 19.
  KbModel m2(Formats(0));
  EXPECT_EQ(Feed(m2, {{4, 1, 10, 3, 1, 0}, {1, 0, 0, 5, -2, 0}}),
            (std::vector<std::int64_t>{10, 0, 13, 0, 17, 0, 19, 0, 19, 1}));
}

TEST(KbEngine, OutputsWaitForTheNextEventWord) {
  KbModel m(Formats(0));
  std::vector<std::int64_t> out;
  EXPECT_EQ(m.eval(std::vector<std::int64_t>{4, 2, 0, 1, 0, 0}, out), 0u);  // an event may be due
  EXPECT_EQ(m.eval(std::vector<std::int64_t>{2, 0, 0, 0, 0, 0}, out), 3u);  // pixels 0..2
  EXPECT_EQ(m.eval(std::vector<std::int64_t>{9, 0, 0, 0, 0, 0}, out), 2u);  // beyond: the rest
  EXPECT_EQ(m.eval(std::vector<std::int64_t>{0, 0, 7, 0, 0, 0}, out), 1u);  // next span
}

TEST(KbEngine, LeftOverEventWordsAreDropped) {
  KbModel m(Formats(0));
  // A 1-pixel span announcing 2 events: both event words are read and dropped after it.
  EXPECT_EQ(
      Feed(m, {{0, 2, 5, 0, 0, 0}, {0, 0, 0, 9, 9, 1}, {0, 0, 0, 9, 9, 1}, {0, 0, 6, 0, 0, 0}}),
      (std::vector<std::int64_t>{5, 1, 6, 1}));
}

TEST(KbEngine, ClampsToZeroAndOneAndWraps) {
  KbModel m(Formats(0));
  const std::int64_t one = 256;  // 1.0 in S2.8
  EXPECT_EQ(m.output(-1), 0);
  EXPECT_EQ(m.output(one + 1), 255);  // clamped to 1.0, which 0.8 saturates to 255/256
  EXPECT_EQ(m.output(one / 2), 128);
  // S2.8 wraps at 4.0: f = 3.99..., d1 = 1/256: the next f is -4.0 -> clamped to 0.
  EXPECT_EQ(Feed(m, {{1, 0, 1023, 1, 0, 0}}), (std::vector<std::int64_t>{255, 0, 0, 1}));
}

// A single term n = 10 swept across all four break points.
KbSpan Sweep(int length) {
  const kb::QuadParams ab = kb::least_squares(10);
  return KbSpan{{KbTerm{-1.5 * ab.b, 3 * ab.b / length, ab, 1.0}}, length};
}

TEST(KbSetup, ExactReloadReproducesTheSpan) {
  const KbFormats f = Formats(40);
  KbModel m(f);
  std::vector<std::int64_t> trace;
  m.trace_accumulator(&trace);
  const KbSpan span = Sweep(100);
  const auto program = kb_program(span, KbPolicy::exact_reload, f);
  (void)Feed(m, program);
  ASSERT_EQ(trace.size(), 100u);
  for (int i = 0; i < 100; ++i) {
    // 40 guard bits: rounding alone is far below 1e-6 of an 8-bit LSB over 100 pixels.
    EXPECT_NEAR(fx::to_real(trace[i], f.acc), kb_exact(span, i), 1e-6 / 256) << i;
  }
  // Each break point changes the second difference at three consecutive pixels at most.
  EXPECT_LE(program.size() - 1, 12u);
  EXPECT_GE(program.size() - 1, 4u);
}

TEST(KbSetup, D2OnlyChangesOnlyTheSecondDifferenceOncePerCrossing) {
  const auto program = kb_program(Sweep(100), KbPolicy::d2_only, Formats(24));
  ASSERT_EQ(program.size(), 5u);  // header + one event per break point (-b, -a, a, b)
  for (std::size_t e = 1; e < program.size(); ++e) EXPECT_EQ(program[e][5], 0);  // no reload
}

TEST(KbSetup, RefusesSpansThatNeedTooManyEvents) {
  KbFormats f = Formats(24);
  f.event_bits = 1;  // one event at most
  EXPECT_THROW((void)kb_program(Sweep(100), KbPolicy::d2_only, f), Error);
}

// kb_span_values on every instruction set this CPU runs: bit for bit kb_exact at every pixel, and
// a change exactly where some term's kb::section_of changes, on random spans of one to four terms
// that cross the break points (including exactly at them: theta0 on ±a or ±b, dtheta 0).
TEST(KbSetup, SpanValuesAreKbExactAndSectionOf) {
  const fx::Isa chosen = fx::kernel_isa();
  for (const fx::Isa isa : fx::supported_isas()) {
    fx::set_kernel_isa(isa);
    for (std::uint64_t s = 0; s < 300; ++s) {
      Rng rng(11, kStimulusStream, s);
      KbSpan span;
      span.length = 1 + static_cast<int>(rng.below(s < 30 ? 8 : 3000));
      const auto terms = static_cast<int>(1 + rng.below(4));
      for (int t = 0; t < terms; ++t) {
        KbTerm term;
        term.ab = kb::closed_form(1 + static_cast<double>(rng.below(200)));
        const double ends[] = {term.ab.a, -term.ab.a, term.ab.b, -term.ab.b};
        term.theta0 = s % 7 == 0 ? ends[rng.below(4)] : 3 * rng.symmetric();
        term.dtheta = s % 11 == 0 ? 0.0 : 4 * rng.symmetric() / span.length;
        term.scale = rng.uniform();
        span.terms.push_back(term);
      }
      const int n = span.length + 2;
      std::vector<double> exact(static_cast<std::size_t>(n));
      std::vector<std::uint8_t> changes(static_cast<std::size_t>(n) - 1);
      kb_span_values(span, n, exact.data(), changes.data());
      for (int i = 0; i < n; ++i) {
        ASSERT_EQ(std::bit_cast<std::uint64_t>(exact[i]),
                  std::bit_cast<std::uint64_t>(kb_exact(span, i)))
            << fx::isa_name(isa) << " span " << s << " pixel " << i;
        if (i + 1 == n) break;
        bool want = false;
        for (const KbTerm& t : span.terms) {
          want = want || kb::section_of(t.theta0 + i * t.dtheta, t.ab) !=
                             kb::section_of(t.theta0 + (i + 1) * t.dtheta, t.ab);
        }
        ASSERT_EQ(changes[i] != 0, want) << fx::isa_name(isa) << " span " << s << " pixel " << i;
      }
    }
    KbSpan nan_span{{KbTerm{std::nan(""), 0.01, kb::closed_form(8), 1}}, 4};
    std::vector<double> exact(6);
    std::vector<std::uint8_t> changes(5);
    EXPECT_THROW(kb_span_values(nan_span, 6, exact.data(), changes.data()), Error);
    nan_span.terms[0] = KbTerm{0.1, 0.01, kb::QuadParams{0.2, 0.1}, 1};  // a > b
    EXPECT_THROW(kb_span_values(nan_span, 6, exact.data(), changes.data()), Error);
  }
  fx::set_kernel_isa(chosen);
}

// docs/kb.md: the guard bits the bound asks for are enough, and on these spans one fewer is not
// (the bound is tight for long spans).
TEST(KbAnalysis, GuardBitBoundHoldsAndIsTight) {
  const fx::Format out{false, 0, 8};
  EXPECT_EQ(kb_guard_bits_needed(4096), 23);
  EXPECT_EQ(kb_guard_bits_needed(1024), 19);
  EXPECT_EQ(kb_guard_bits_needed(16), 7);
  EXPECT_LE(kb_drift(4096, 23, KbPolicy::exact_reload, out, 50, 1), 0.5);
  EXPECT_GT(kb_drift(4096, 22, KbPolicy::exact_reload, out, 50, 1), 0.5);
  EXPECT_LE(kb_drift(1024, 19, KbPolicy::exact_reload, out, 50, 1), 0.5);
  EXPECT_GT(kb_drift(1024, 18, KbPolicy::exact_reload, out, 50, 1), 0.5);
}

// docs/kb.md: the paper's policy carries its own error, independent of the guard bits.
TEST(KbAnalysis, D2OnlyErrorIsTheDocumentedOne) {
  const fx::Format out{false, 0, 8};
  EXPECT_NEAR(kb_drift(4096, 40, KbPolicy::d2_only, out, 50, 1), 0.6336, 0.00005);
  EXPECT_NEAR(kb_drift(256, 40, KbPolicy::d2_only, out, 50, 1), 13.2025, 0.00005);
  EXPECT_NEAR(kb_drift(16, 40, KbPolicy::d2_only, out, 50, 1), 189.8002, 0.00005);
  EXPECT_LT(kb_drift(4096, 40, KbPolicy::exact_reload, out, 50, 1), 1e-4);
}

std::string ErrorOf(const std::string& toml) {
  try {
    (void)make_model(find_pipeline("kb"), Config::parse(toml, "mine.toml"));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(KbConfig, RefusesBadValues) {
  const std::string ok =
      "pipeline = \"kb\"\n[param]\nevent_bits = 5\n[mode]\nout_round = \"half_even\"\n"
      "[format]\nacc = \"S2.32\"\nout = \"0.8\"\n[setup]\npolicy = \"d2_only\"\n"
      "ab = \"least_squares\"\nterms = 2\n";
  EXPECT_EQ(ErrorOf(ok), "");
  std::string bad = ok;
  bad.replace(bad.find("S2.32"), 5, "2.32");
  EXPECT_EQ(ErrorOf(bad), "mine.toml: [format] acc must be signed (got 2.32)");
  bad = ok;
  bad.replace(bad.find("d2_only"), 7, "lazy");
  EXPECT_EQ(ErrorOf(bad),
            "mine.toml:10: [setup] policy = 'lazy' (expected one of: d2_only, exact_reload)");
  bad = ok;
  bad.replace(bad.find("terms = 2"), 9, "terms = 9");
  EXPECT_EQ(ErrorOf(bad), "mine.toml:12: [setup] terms = 9 must be an integer in [1, 4]");
}

}  // namespace
}  // namespace phongsim
