// Tests for the bit-accurate fixed-point core (model/fixed.*): the arithmetic and requantization.
//
// Three layers: exhaustive comparison against the independent exact reference in
// tests/fx_reference.h (small formats, every operand, every mode), sampled comparison for the
// widest (63-bit) formats, and directed corners whose expected values are literals derived by
// hand from the definitions in model/fixed.h. The directed tables are also run through the
// reference, so the reference itself is checked against hand arithmetic. Formats, reals, port
// bits and mode names: fixed_format_test.cpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "model/fixed.h"
#include "tests/fixed_helpers.h"
#include "tests/fx_reference.h"

namespace {

using namespace phongsim::testing;  // tests/fixed_helpers.h

// gtest parameter names allow only [A-Za-z0-9_].
std::string Ident(Format f) {
  return fmt::format("{}{}_{}", f.is_signed ? "S" : "U", f.int_bits, f.frac_bits);
}

// Result formats exactly as the comment in fixed.h states them.
Format DocAdd(Format a, Format b) {
  return {a.is_signed || b.is_signed, std::max(a.int_bits, b.int_bits) + 1,
          std::max(a.frac_bits, b.frac_bits)};
}
Format DocSub(Format a, Format b) {
  return {true, std::max(a.int_bits, b.int_bits) + 1, std::max(a.frac_bits, b.frac_bits)};
}
Format DocMul(Format a, Format b) {
  return {a.is_signed || b.is_signed,
          a.int_bits + b.int_bits + (a.is_signed && b.is_signed ? 1 : 0),
          a.frac_bits + b.frac_bits};
}
Format DocNeg(Format a) { return {true, a.int_bits + (a.is_signed ? 1 : 0), a.frac_bits}; }
Format DocAbs(Format a) { return {false, a.int_bits + (a.is_signed ? 1 : 0), a.frac_bits}; }
Format DocScale(Format a, int k) {
  return k >= 0 ? Format{a.is_signed, a.int_bits + k, std::max(a.frac_bits - k, 0)}
                : Format{a.is_signed, std::max(a.int_bits + k, 0), a.frac_bits - k};
}

// "" when `got` is exactly `want` in the documented format `want_fmt` and lies in its range.
std::string CheckExact(const Fixed& got, fxref::Value want, Format want_fmt) {
  if (got.fmt != want_fmt) return "format " + Name(got.fmt) + ", documented " + Name(want_fmt);
  if (!fxref::equal(fxref::value_of(got.raw, got.fmt), want)) {
    return "raw " + std::to_string(got.raw) + " in " + Name(got.fmt) + ", exact value is " +
           fxref::to_string(want);
  }
  const fxref::Range r = fxref::range(want_fmt);
  if (got.raw < r.lo || got.raw > r.hi) return "raw " + std::to_string(got.raw) + " out of range";
  return "";
}

// ---------------------------------------------------------------------------------------------
// Exhaustive add / sub / mul / neg against the reference.

class ArithExhaustive : public ::testing::TestWithParam<std::tuple<Format, Format>> {};

TEST_P(ArithExhaustive, EveryOperandPairIsExact) {
  const auto [fa, fb] = GetParam();
  const std::string pair = Name(fa) + " op " + Name(fb);
  ASSERT_EQ(fx::add_format(fa, fb), DocAdd(fa, fb)) << pair;
  ASSERT_EQ(fx::sub_format(fa, fb), DocSub(fa, fb)) << pair;
  ASSERT_EQ(fx::mul_format(fa, fb), DocMul(fa, fb)) << pair;
  // Multiplication widths simply add (the doc's "width wa + wb").
  ASSERT_EQ(fxref::width(DocMul(fa, fb)), fxref::width(fa) + fxref::width(fb)) << pair;

  Mismatches bad;
  for (const std::int64_t a : AllRaws(fa)) {
    for (const std::int64_t b : AllRaws(fb)) {
      const Fixed x = fx::from_raw(a, fa);
      const Fixed y = fx::from_raw(b, fb);
      const fxref::Value va = fxref::value_of(a, fa);
      const fxref::Value vb = fxref::value_of(b, fb);
      const struct {
        const char* op;
        Fixed got;
        fxref::Value want;
        Format fmt;
      } results[] = {
          {"+", fx::add(x, y), fxref::add(va, vb), DocAdd(fa, fb)},
          {"-", fx::sub(x, y), fxref::sub(va, vb), DocSub(fa, fb)},
          {"*", fx::mul(x, y), fxref::mul(va, vb), DocMul(fa, fb)},
      };
      for (const auto& r : results) {
        const std::string err = CheckExact(r.got, r.want, r.fmt);
        if (!err.empty() && bad.Report(Name(fa) + " raw " + std::to_string(a) + " " + r.op + " " +
                                       Name(fb) + " raw " + std::to_string(b) + ": " + err)) {
          return;
        }
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(SmallFormats, ArithExhaustive,
                         ::testing::Combine(::testing::ValuesIn(kSmall),
                                            ::testing::ValuesIn(kSmall)),
                         [](const auto& info) {
                           return Ident(std::get<0>(info.param)) + "_x_" +
                                  Ident(std::get<1>(info.param));
                         });

TEST(ArithExhaustive, NegOfEveryValueIsExact) {
  Mismatches bad;
  for (const Format f : kSmall) {
    ASSERT_EQ(fx::neg_format(f), DocNeg(f)) << Name(f);
    for (const std::int64_t a : AllRaws(f)) {
      const std::string err =
          CheckExact(fx::neg(fx::from_raw(a, f)), fxref::neg(fxref::value_of(a, f)), DocNeg(f));
      if (!err.empty() && bad.Report("-(" + Name(f) + " raw " + std::to_string(a) + "): " + err)) {
        return;
      }
    }
  }
}

TEST(ArithExhaustive, AbsOfEveryValueIsExact) {
  Mismatches bad;
  for (const Format f : kSmall) {
    ASSERT_EQ(fx::abs_format(f), DocAbs(f)) << Name(f);
    for (const std::int64_t a : AllRaws(f)) {
      const fxref::Value v = fxref::value_of(a, f);
      const fxref::Value want = v.num < 0 ? fxref::neg(v) : v;
      const std::string err = CheckExact(fx::abs(fx::from_raw(a, f)), want, DocAbs(f));
      if (!err.empty() && bad.Report(fmt::format("|{} raw {}|: {}", Name(f), a, err))) {
        return;
      }
    }
  }
}

// x · 2^k for k across both edges: the point passing the last fraction bit (zeros appended)
// and the first integer bit (the format widens).
TEST(ArithExhaustive, ScaleOfEveryValueIsExact) {
  Mismatches bad;
  for (const Format f : kSmall) {
    for (int k = -9; k <= 9; ++k) {
      ASSERT_EQ(fx::scale_format(f, k), DocScale(f, k)) << Name(f) << " k=" << k;
      for (const std::int64_t a : AllRaws(f)) {
        const fxref::Value v = fxref::value_of(a, f);
        // Exactly v · 2^k, kept with a non-negative exponent as the reference requires.
        const fxref::Value want = v.exp - k >= 0 ? fxref::Value{v.num, v.exp - k}
                                                 : fxref::mul(v, fxref::Value{fxref::pow2(k), 0});
        const std::string err = CheckExact(fx::scale(fx::from_raw(a, f), k), want, DocScale(f, k));
        if (!err.empty() &&
            bad.Report(fmt::format("scale({} raw {}, {}): {}", Name(f), a, k, err))) {
          return;
        }
      }
    }
  }
}

TEST(ArithCorners, AbsAndScale) {
  // |S3.4 min| = |-8| = 8 needs the 4th integer bit: 4.4 raw 128.
  EXPECT_EQ(fx::abs(fx::from_raw(-128, S(3, 4))), (Fixed{128, U(4, 4)}));
  // 1.5 in S1.2 (raw 6) times 2^3 = 12: S4.0 raw 12 (one zero appended below the point).
  EXPECT_EQ(fx::scale(fx::from_raw(6, S(1, 2)), 3), (Fixed{12, S(4, 0)}));
  // -1.5 / 2^3 = -0.1875: S0.5 raw -6 (bits unchanged, the point moved past the integer bit).
  EXPECT_EQ(fx::scale(fx::from_raw(-6, S(1, 2)), -3), (Fixed{-6, S(0, 5)}));
}

// ---------------------------------------------------------------------------------------------
// Exhaustive resize_raw against the reference.

// Targets for requantizing from `f`: drop 1, 2 and 5 fraction bits, add fraction bits, drop
// integer bits (overflow), flip signedness, zero fraction bits, combinations, 1-bit formats.
std::vector<Format> ResizeTargets(Format f) {
  const bool s = f.is_signed;
  const int i = f.int_bits;
  const int m = f.frac_bits;
  const std::vector<Format> candidates{
      {s, i, m - 1}, {s, i, m - 2},  {s, i, m - 5},     {s, i, m + 3},      {s, i, m + 9},
      {s, i - 2, m}, {s, i - 5, m},  {!s, i, m},        {!s, i - 1, m + 1}, {!s, i + 1, m - 3},
      {s, i, 0},     {!s, i + 1, 0}, {s, i - 3, m - 2}, {s, i + 1, m - 1},  {true, 0, 0},
      {false, 0, 1}, {false, 1, 0},  {true, 0, 3},      {true, 2, m + 20},  {false, 3, m + 30},
  };
  std::vector<Format> out;
  for (const Format t : candidates) {
    if (Valid(t) && std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  return out;
}

void CheckResizeEverywhere(Format from, const std::vector<Format>& targets) {
  const std::vector<std::int64_t> raws = AllRaws(from);
  Mismatches bad;
  for (const Format to : targets) {
    for (const Round r : kRounds) {
      for (const Overflow o : kOverflows) {
        for (const std::int64_t raw : raws) {
          const std::int64_t got = fx::resize_raw(raw, from, to, r, o);
          const fxref::i128 want = fxref::requantize(fxref::value_of(raw, from), to, r, o);
          if (got != want && bad.Report("resize_raw(" + std::to_string(raw) + ", " + Name(from) +
                                        " -> " + Name(to) + ", " + Mode(r, o) + ") = " +
                                        std::to_string(got) + ", want " + fxref::to_string(want))) {
            return;
          }
        }
      }
    }
  }
}

class ResizeExhaustive : public ::testing::TestWithParam<Format> {};

TEST_P(ResizeExhaustive, EveryRawEveryModeMatchesReference) {
  CheckResizeEverywhere(GetParam(), ResizeTargets(GetParam()));
}

// 16-bit inputs include the products of 8-bit formats (S3.4*S3.4 = S7.8, 4.4*4.4 = 8.8).
INSTANTIATE_TEST_SUITE_P(Formats, ResizeExhaustive,
                         ::testing::Values(S(7, 8), U(8, 8), S(15, 0), U(0, 16), S(3, 4), U(4, 4),
                                           S(0, 7), U(8, 0), S(0, 0), U(0, 1)),
                         [](const auto& info) { return Ident(info.param); });

TEST(ResizeExhaustive, EverySmallFormatToEverySmallFormat) {
  for (const Format from : kSmall) {
    CheckResizeEverywhere(from, std::vector<Format>(kSmall.begin(), kSmall.end()));
  }
}

TEST(ResizeExhaustive, ResizeWrapsResizeRaw) {
  for (const Format from : kSmall) {
    for (const Format to : kSmall) {
      for (const Round r : kRounds) {
        for (const Overflow o : kOverflows) {
          for (const std::int64_t raw : AllRaws(from)) {
            const Fixed got = fx::resize(fx::from_raw(raw, from), to, r, o);
            const auto want =
                static_cast<std::int64_t>(fxref::requantize(fxref::value_of(raw, from), to, r, o));
            ASSERT_EQ(got, (Fixed{want, to}))
                << Name(from) << " raw " << raw << " -> " << Name(to) << " " << Mode(r, o);
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Widest formats (kWide): sampled raws (edges, exact ties, random) against the reference.

std::vector<std::int64_t> SampleRaws(Format f, std::mt19937_64& rng, int random_count) {
  const fxref::Range rg = fxref::range(f);
  const auto lo = static_cast<std::int64_t>(rg.lo);
  const auto hi = static_cast<std::int64_t>(rg.hi);
  std::vector<std::int64_t> out;
  for (const std::int64_t v :
       {lo, lo + 1, lo + 2, std::int64_t{-2}, std::int64_t{-1}, std::int64_t{0}, std::int64_t{1},
        std::int64_t{2}, hi - 2, hi - 1, hi}) {
    if (v >= lo && v <= hi) out.push_back(v);
  }
  std::uniform_int_distribution<std::int64_t> dist(lo, hi);
  for (int n = 0; n < random_count; ++n) {
    const std::int64_t v = dist(rng);
    out.push_back(v);
    // Exact ties and near-ties for dropping d fraction bits: floor(v / 2^d) * 2^d + 2^(d-1) +- 1.
    for (const int d : {1, 2, 5, 20, 40, 62}) {
      const fxref::i128 base = fxref::floor_divmod(v, fxref::pow2(d)).q * fxref::pow2(d);
      for (const fxref::i128 delta : {fxref::i128{-1}, fxref::i128{0}, fxref::i128{1}}) {
        const fxref::i128 t = base + fxref::pow2(d - 1) + delta;
        if (t >= rg.lo && t <= rg.hi) out.push_back(static_cast<std::int64_t>(t));
      }
    }
  }
  std::sort(out.begin(), out.end());  // duplicates would only repeat failure messages
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

TEST(WideFormats, ResizeSamplesMatchReference) {
  std::mt19937_64 rng(20240611);
  Mismatches bad;
  for (const Format from : kWide) {
    const std::vector<std::int64_t> raws = SampleRaws(from, rng, 200);
    for (const Format to : kWide) {
      for (const Round r : kRounds) {
        for (const Overflow o : kOverflows) {
          for (const std::int64_t raw : raws) {
            const std::int64_t got = fx::resize_raw(raw, from, to, r, o);
            const fxref::i128 want = fxref::requantize(fxref::value_of(raw, from), to, r, o);
            if (got != want &&
                bad.Report("resize_raw(" + std::to_string(raw) + ", " + Name(from) + " -> " +
                           Name(to) + ", " + Mode(r, o) + ") = " + std::to_string(got) + ", want " +
                           fxref::to_string(want))) {
              return;
            }
          }
        }
      }
    }
  }
}

// Operand pairs whose results reach exactly 63 bits, plus pairs whose results would not fit.
TEST(WideFormats, ArithmeticSamplesMatchReferenceOrAreRefused) {
  const std::array<std::pair<Format, Format>, 8> pairs{{
      {S(30, 31), S(30, 31)},  // add/sub -> S31.31 (63 bits); mul refused
      {U(30, 31), S(20, 31)},  // add/sub -> S31.31
      {U(61, 0), U(0, 1)},     // add -> 62.1 (63); sub -> S62.1 (64) refused
      {S(15, 15), U(16, 16)},  // mul -> S31.31
      {U(31, 0), U(0, 32)},    // mul -> 31.32
      {S(30, 0), S(0, 31)},    // mul -> S31.31 (extra integer bit for two signed operands)
      {S(0, 62), S(0, 0)},     // mul -> S1.62
      {U(62, 0), U(62, 0)},    // add -> 63.0; sub, mul refused
  }};
  std::mt19937_64 rng(7);
  Mismatches bad;
  for (const auto& [fa, fb] : pairs) {
    const std::vector<std::int64_t> as = SampleRaws(fa, rng, 30);
    const std::vector<std::int64_t> bs = SampleRaws(fb, rng, 30);
    const struct {
      const char* op;
      Format fmt;
      std::function<Fixed(Fixed, Fixed)> impl;
      std::function<fxref::Value(fxref::Value, fxref::Value)> ref;
    } ops[] = {
        {"+", DocAdd(fa, fb), fx::add, fxref::add},
        {"-", DocSub(fa, fb), fx::sub, fxref::sub},
        {"*", DocMul(fa, fb), fx::mul, fxref::mul},
    };
    for (const auto& op : ops) {
      const std::string where = Name(fa) + " " + op.op + " " + Name(fb);
      if (!Valid(op.fmt)) {
        EXPECT_TRUE(
            ThrowsError([&] { (void)op.impl(fx::from_raw(0, fa), fx::from_raw(0, fb)); }, where))
            << where << " (" << fxref::width(op.fmt) << " bits)";
        continue;
      }
      for (const std::int64_t a : as) {
        for (const std::int64_t b : bs) {
          const Fixed got = op.impl(fx::from_raw(a, fa), fx::from_raw(b, fb));
          const std::string err =
              CheckExact(got, op.ref(fxref::value_of(a, fa), fxref::value_of(b, fb)), op.fmt);
          if (!err.empty() && bad.Report(where + " with raws " + std::to_string(a) + ", " +
                                         std::to_string(b) + ": " + err)) {
            return;
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Directed corners. Every expected value below is worked out by hand from the definitions.

struct ArithCase {
  char op;  // '+', '-', '*', 'n' (neg, b ignored)
  Format fa;
  std::int64_t a;
  Format fb;
  std::int64_t b;
  Fixed want;
};

const ArithCase kArithCases[] = {
    // S3.4 min is -8 (raw -128): (-8)(-8) = 64 = 16384 / 2^8 needs S7.8 (S6.8 tops out below 64).
    {'*', S(3, 4), -128, S(3, 4), -128, {16384, S(7, 8)}},
    {'*', S(3, 4), -128, S(3, 4), 127, {-16256, S(7, 8)}},
    {'*', U(4, 4), 255, S(3, 4), -128, {-32640, S(7, 8)}},  // 15.9375 * -8
    {'*', U(4, 4), 255, U(4, 4), 255, {65025, U(8, 8)}},
    {'*', S(0, 7), -128, S(0, 7), -128, {16384, S(1, 14)}},  // (-1)(-1) = 1
    {'*', S(0, 0), -1, S(0, 0), -1, {1, S(1, 0)}},           // 1-bit formats: (-1)(-1) = 1
    {'*', S(7, 0), -128, U(8, 0), 255, {-32640, S(15, 0)}},
    // Negating the most negative value needs one more integer bit.
    {'n', S(3, 4), -128, {}, 0, {128, S(4, 4)}},
    {'n', U(4, 4), 255, {}, 0, {-255, S(4, 4)}},
    {'n', S(0, 0), -1, {}, 0, {1, S(1, 0)}},
    {'+', S(3, 4), -128, S(3, 4), -128, {-256, S(4, 4)}},
    {'+', U(4, 4), 255, U(4, 4), 255, {510, U(5, 4)}},
    {'+', S(1, 2), 3, U(0, 3), 5, {11, S(2, 3)}},           // 0.75 + 0.625 = 1.375
    {'+', S(7, 0), -128, S(0, 7), 127, {-16257, S(8, 7)}},  // -128 + 127/128
    {'+', S(0, 0), -1, U(1, 0), 1, {0, S(2, 0)}},
    {'-', U(0, 3), 0, U(0, 3), 7, {-7, S(1, 3)}},  // unsigned - unsigned is signed
    {'-', S(3, 4), -128, U(4, 4), 255, {-383, S(5, 4)}},
    {'-', U(4, 4), 255, S(3, 4), -128, {383, S(5, 4)}},
    {'-', S(0, 0), -1, S(0, 0), -1, {0, S(1, 0)}},
};

TEST(Directed, ArithmeticCorners) {
  for (const ArithCase& c : kArithCases) {
    const std::string where = std::string(1, c.op) + " " + Name(c.fa) + " raw " +
                              std::to_string(c.a) + ", " + Name(c.fb) + " raw " +
                              std::to_string(c.b);
    const Fixed x = fx::from_raw(c.a, c.fa);
    const fxref::Value va = fxref::value_of(c.a, c.fa);
    Fixed got;
    fxref::Value ref;
    if (c.op == 'n') {
      got = fx::neg(x);
      ref = fxref::neg(va);
    } else {
      const Fixed y = fx::from_raw(c.b, c.fb);
      const fxref::Value vb = fxref::value_of(c.b, c.fb);
      got = c.op == '+' ? fx::add(x, y) : c.op == '-' ? fx::sub(x, y) : fx::mul(x, y);
      ref = c.op == '+'   ? fxref::add(va, vb)
            : c.op == '-' ? fxref::sub(va, vb)
                          : fxref::mul(va, vb);
    }
    EXPECT_EQ(got.raw, c.want.raw) << where;
    EXPECT_EQ(Name(got.fmt), Name(c.want.fmt)) << where;
    EXPECT_TRUE(fxref::equal(ref, fxref::value_of(c.want.raw, c.want.fmt)))
        << "reference: " << where;
    EXPECT_TRUE(fxref::fits(ref, c.want.fmt)) << "reference: " << where;
  }
  // Without the extra integer bit the S3.4 min product would not fit.
  EXPECT_FALSE(fxref::fits(fxref::Value{16384, 8}, S(6, 8)));
}

// Requantizations that stay in range: one expected raw per rounding mode, same for wrap and
// saturate.
struct RoundCase {
  Format from;
  std::int64_t raw;
  Format to;
  std::int64_t truncate, half_up, half_even;
};

const RoundCase kRoundCases[] = {
    // One fraction bit dropped: exact ties.
    {S(3, 1), 1, S(3, 0), 0, 1, 0},      // 0.5
    {S(3, 1), -1, S(3, 0), -1, 0, 0},    // -0.5
    {S(3, 1), 3, S(3, 0), 1, 2, 2},      // 1.5
    {S(3, 1), 5, S(3, 0), 2, 3, 2},      // 2.5
    {S(3, 1), -3, S(3, 0), -2, -1, -2},  // -1.5
    {S(3, 1), -5, S(3, 0), -3, -2, -2},  // -2.5
    {S(3, 1), 7, S(3, 0), 3, 4, 4},      // 3.5
    {S(3, 1), -7, S(3, 0), -4, -3, -4},  // -3.5
    {S(3, 1), 4, S(3, 0), 2, 2, 2},      // 2.0 exact
    {S(3, 1), -4, S(3, 0), -2, -2, -2},  // -2.0 exact
    // Two bits dropped: quarters are not ties.
    {S(3, 2), 5, S(3, 0), 1, 1, 1},      // 1.25
    {S(3, 2), 7, S(3, 0), 1, 2, 2},      // 1.75
    {S(3, 2), -5, S(3, 0), -2, -1, -1},  // -1.25
    {S(3, 2), -7, S(3, 0), -2, -2, -2},  // -1.75
    {S(3, 2), -6, S(3, 0), -2, -1, -2},  // -1.5
    // Four bits dropped: ties and their neighbours one LSB away.
    {S(3, 4), 8, S(3, 0), 0, 1, 0},      // 0.5
    {S(3, 4), 9, S(3, 0), 0, 1, 1},      // 0.5625
    {S(3, 4), 7, S(3, 0), 0, 0, 0},      // 0.4375
    {S(3, 4), -8, S(3, 0), -1, 0, 0},    // -0.5
    {S(3, 4), -9, S(3, 0), -1, -1, -1},  // -0.5625
    {S(3, 4), -7, S(3, 0), -1, 0, 0},    // -0.4375
    {S(3, 4), 24, S(3, 2), 6, 6, 6},     // 1.5 is exact in S3.2
    {S(3, 4), 26, S(3, 2), 6, 7, 6},     // 1.625 -> 6.5 quarters, tie
    {S(3, 4), 30, S(3, 2), 7, 8, 8},     // 1.875 -> 7.5 quarters, tie
    {U(4, 4), 40, U(4, 0), 2, 3, 2},     // 2.5 unsigned
    {U(4, 4), 56, U(4, 0), 3, 4, 4},     // 3.5 unsigned
    // Adding fraction bits is exact in every mode.
    {S(3, 1), -5, S(3, 6), -160, -160, -160},
    // Widest formats: 2^63 - 1 in 0.63 is 1 - 2^-63, not a tie; 2^62 in 0.63 is exactly 0.5.
    {U(0, 63), kMax63, U(63, 0), 0, 1, 1},
    {U(0, 63), kP62, U(63, 0), 0, 1, 0},
    {U(0, 63), 3 * (kP62 / 2), U(63, 0), 0, 1, 1},       // 0.75
    {S(0, 62), -kP62, S(62, 0), -1, -1, -1},             // exactly -1
    {S(0, 62), -kP62 + 1, S(62, 0), -1, -1, -1},         // -1 + 2^-62 is nearest to -1
    {S(0, 62), -kP62 / 2, S(62, 0), -1, 0, 0},           // -0.5
    {S(0, 62), -kP62 / 2 + 1, S(62, 0), -1, 0, 0},       // -0.5 + 2^-62
    {S(0, 62), -kP62 / 2 - 1, S(62, 0), -1, -1, -1},     // -0.5 - 2^-62
    {S(0, 62), -kP62 / 2 - kP62, S(62, 0), -2, -1, -2},  // -1.5
    {S(0, 62), kP62 - 1, U(63, 0), 0, 1, 1},             // 1 - 2^-62
};

TEST(Directed, RoundingInRange) {
  for (const RoundCase& c : kRoundCases) {
    const std::int64_t want[] = {c.truncate, c.half_up, c.half_even};
    for (std::size_t i = 0; i < kRounds.size(); ++i) {
      for (const Overflow o : kOverflows) {
        const std::string where = Name(c.from) + " raw " + std::to_string(c.raw) + " -> " +
                                  Name(c.to) + " " + Mode(kRounds[i], o);
        EXPECT_EQ(fx::resize_raw(c.raw, c.from, c.to, kRounds[i], o), want[i]) << where;
        EXPECT_TRUE(fxref::requantize(fxref::value_of(c.raw, c.from), c.to, kRounds[i], o) ==
                    want[i])
            << "reference: " << where;
      }
    }
  }
}

// Requantizations that overflow: expected raw under wrap and under saturate.
struct OverflowCase {
  Format from;
  std::int64_t raw;
  Format to;
  Round round;
  std::int64_t wrap, saturate;
};

const OverflowCase kOverflowCases[] = {
    // S3.4 -> S1.4 keeps raws [-32, 31]: just inside, at and just outside both bounds.
    {S(3, 4), 30, S(1, 4), Round::truncate, 30, 30},
    {S(3, 4), 31, S(1, 4), Round::truncate, 31, 31},
    {S(3, 4), 32, S(1, 4), Round::truncate, -32, 31},
    {S(3, 4), -31, S(1, 4), Round::truncate, -31, -31},
    {S(3, 4), -32, S(1, 4), Round::truncate, -32, -32},
    {S(3, 4), -33, S(1, 4), Round::truncate, 31, -32},
    {S(3, 4), 127, S(1, 4), Round::truncate, -1, 31},  // 127 mod 64 = 63 -> -1
    {S(3, 4), -128, S(1, 4), Round::truncate, 0, -32},
    // Unsigned: 4.4 -> 2.4 keeps [0, 63].
    {U(4, 4), 63, U(2, 4), Round::truncate, 63, 63},
    {U(4, 4), 64, U(2, 4), Round::truncate, 0, 63},
    {U(4, 4), 255, U(2, 4), Round::truncate, 63, 63},
    {U(4, 4), 100, U(2, 4), Round::truncate, 36, 63},
    // Signed -> unsigned: negatives saturate to 0 and wrap modulo 2^7.
    {S(3, 4), -1, U(3, 4), Round::truncate, 127, 0},
    {S(3, 4), -128, U(3, 4), Round::truncate, 0, 0},
    {S(3, 4), -100, U(3, 4), Round::truncate, 28, 0},
    // Unsigned -> signed: the top half is out of range.
    {U(4, 4), 127, S(3, 4), Round::truncate, 127, 127},
    {U(4, 4), 128, S(3, 4), Round::truncate, -128, 127},
    {U(4, 4), 255, S(3, 4), Round::truncate, -1, 127},
    // Rounding up past the maximum: 7.9375 -> 8 does not fit S3.0.
    {S(3, 4), 127, S(3, 0), Round::half_up, -8, 7},
    {S(3, 4), 127, S(3, 0), Round::half_even, -8, 7},
    {S(3, 4), 127, S(3, 0), Round::truncate, 7, 7},
    {S(3, 4), 120, S(3, 0), Round::half_even, -8, 7},  // 7.5 ties to 8 (even)
    {S(3, 4), 120, S(3, 0), Round::truncate, 7, 7},
    {U(0, 1), 1, S(0, 0), Round::half_up, -1, 0},  // 0.5 -> 1 does not fit S0.0 = {-1, 0}
    {U(0, 1), 1, S(0, 0), Round::half_even, 0, 0},
    {U(0, 1), 1, S(0, 0), Round::truncate, 0, 0},
    // Zero fraction bits.
    {S(7, 0), 8, S(3, 0), Round::truncate, -8, 7},
    {S(7, 0), -9, S(3, 0), Round::truncate, 7, -8},
    {U(8, 0), 200, S(7, 0), Round::truncate, -56, 127},
    {U(8, 0), 200, U(4, 0), Round::truncate, 8, 15},
    {S(7, 0), -1, U(2, 0), Round::truncate, 3, 0},
    {S(0, 0), -1, U(1, 0), Round::truncate, 1, 0},
    {S(0, 0), -1, U(0, 1), Round::truncate, 0, 0},  // -1 -> raw -2, -2 mod 2 = 0
    // 63-bit formats: the intermediate exceeds 64 bits but the result must still be exact.
    {U(0, 63), kMax63, S(0, 62), Round::truncate, kP62 - 1, kP62 - 1},  // 2^62 - 0.5 -> floor
    {U(0, 63), kMax63, S(0, 62), Round::half_up, -kP62, kP62 - 1},      // -> 2^62, too big
    {U(0, 63), kMax63, S(0, 62), Round::half_even, -kP62, kP62 - 1},    // tie, 2^62 is even
    {U(63, 0), kMax63, U(0, 63), Round::truncate, 0, kMax63},  // (2^63-1)*2^63 mod 2^63 = 0
    {U(63, 0), kMax63, S(62, 0), Round::truncate, -1, kP62 - 1},
    {U(63, 0), kMax63, U(62, 1), Round::truncate, kMax63 - 1, kMax63},  // 2^64 - 2 mod 2^63
    {U(63, 0), kMax63, S(0, 62), Round::truncate, -kP62, kP62 - 1},     // 2^125 - 2^62
    {S(62, 0), -kP62, S(0, 62), Round::truncate, 0, -kP62},             // -2^124 mod 2^63 = 0
    {S(62, 0), -kP62, U(63, 0), Round::truncate, kP62, 0},              // 2^63 - 2^62
    {S(62, 0), -kP62, U(0, 63), Round::half_even, 0, 0},
    {S(62, 0), kP62 - 1, S(0, 62), Round::half_up, -kP62, kP62 - 1},  // (2^62-1)*2^62 mod 2^63
};

TEST(Directed, OverflowCorners) {
  for (const OverflowCase& c : kOverflowCases) {
    const std::int64_t want[] = {c.wrap, c.saturate};
    for (std::size_t i = 0; i < kOverflows.size(); ++i) {
      const std::string where = Name(c.from) + " raw " + std::to_string(c.raw) + " -> " +
                                Name(c.to) + " " + Mode(c.round, kOverflows[i]);
      EXPECT_EQ(fx::resize_raw(c.raw, c.from, c.to, c.round, kOverflows[i]), want[i]) << where;
      EXPECT_TRUE(fxref::requantize(fxref::value_of(c.raw, c.from), c.to, c.round, kOverflows[i]) ==
                  want[i])
          << "reference: " << where;
    }
  }
}

TEST(Directed, IdentityResizeOfWidestFormatsIsExact) {
  for (const Format f : {S(62, 0), U(63, 0), S(0, 62), U(0, 63), S(31, 31)}) {
    const fxref::Range rg = fxref::range(f);
    for (const auto raw :
         {static_cast<std::int64_t>(rg.lo), std::int64_t{0}, static_cast<std::int64_t>(rg.hi)}) {
      for (const Round r : kRounds) {
        for (const Overflow o : kOverflows) {
          EXPECT_EQ(fx::resize_raw(raw, f, f, r, o), raw) << Name(f) << " " << Mode(r, o);
        }
      }
    }
  }
}

}  // namespace
