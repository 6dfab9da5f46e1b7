// Tests for the bit-accurate fixed-point core (model/fixed.*).
//
// Three layers: exhaustive comparison against the independent exact reference in
// tests/fx_reference.h (small formats, every operand, every mode), sampled comparison for the
// widest (63-bit) formats, and directed corners whose expected values are literals derived by
// hand from the definitions in model/fixed.h. The directed tables are also run through the
// reference, so the reference itself is checked against hand arithmetic.
#include "model/fixed.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "base/error.h"
#include "tests/fx_reference.h"

// Lets gtest print formats readably in parameterized test names and assertion messages.
namespace phongsim::fx {
void PrintTo(const Format& f, std::ostream* os) {
  *os << (f.is_signed ? "S" : "") << f.int_bits << "." << f.frac_bits;
}
}  // namespace phongsim::fx

namespace {

namespace fx = phongsim::fx;
using fx::Fixed;
using fx::Format;
using fx::Overflow;
using fx::Round;
using phongsim::Error;

constexpr std::array kRounds{Round::truncate, Round::half_up, Round::half_even};
constexpr std::array kOverflows{Overflow::wrap, Overflow::saturate};

constexpr std::int64_t kP62 = std::int64_t{1} << 62;
constexpr std::int64_t kMax63 = std::numeric_limits<std::int64_t>::max();  // 2^63 - 1

constexpr Format S(int int_bits, int frac_bits) { return {true, int_bits, frac_bits}; }
constexpr Format U(int int_bits, int frac_bits) { return {false, int_bits, frac_bits}; }

// Own spelling of a format for messages, so a broken str() cannot garble failure reports.
std::string Name(Format f) {
  return fmt::format("{}{}.{}", f.is_signed ? "S" : "", f.int_bits, f.frac_bits);
}

// gtest parameter names allow only [A-Za-z0-9_].
std::string Ident(Format f) {
  return fmt::format("{}{}_{}", f.is_signed ? "S" : "U", f.int_bits, f.frac_bits);
}

std::string Mode(Round r, Overflow o) {
  const char* rn = r == Round::truncate  ? "truncate"
                   : r == Round::half_up ? "half_up"
                                         : "half_even";
  return std::string(rn) + "/" + (o == Overflow::wrap ? "wrap" : "saturate");
}

// Reals in messages: hexfloat so the printed value is the exact one.
std::string Real(double x) {
  std::ostringstream out;
  out << std::hexfloat << x;
  return out.str();
}

bool Valid(Format f) {
  const int w = fxref::width(f);
  return f.int_bits >= 0 && f.frac_bits >= 0 && w >= 1 && w <= fx::kMaxWidth;
}

// Every raw value of a format, in order (from the reference's range, not min_raw/max_raw).
std::vector<std::int64_t> AllRaws(Format f) {
  const fxref::Range r = fxref::range(f);
  std::vector<std::int64_t> out;
  for (auto v = static_cast<std::int64_t>(r.lo); v <= static_cast<std::int64_t>(r.hi); ++v) {
    out.push_back(v);
  }
  return out;
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

// Collects mismatches from an exhaustive loop (one per test) and says when to stop, so one bug
// reports a few reproducible cases instead of a million lines.
class Mismatches {
 public:
  // Returns true when the caller should stop looking.
  bool Report(const std::string& what) {
    ++count_;
    ADD_FAILURE() << what << (count_ == kLimit ? " [stopping after this mismatch]" : "");
    return count_ >= kLimit;
  }

 private:
  static constexpr int kLimit = 10;
  int count_ = 0;
};

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

// Expects fn() to throw phongsim::Error whose message contains `needle`.
::testing::AssertionResult ThrowsError(const std::function<void()>& fn,
                                       std::string_view needle = "") {
  try {
    fn();
  } catch (const Error& e) {
    if (std::string_view(e.what()).find(needle) != std::string_view::npos) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "message '" << e.what() << "' lacks '" << needle << "'";
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw a non-Error exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

// Formats of up to 8 bits: signed and unsigned, several fraction counts, zero fraction bits,
// and the 1-bit corners S0.0 (values -1, 0) and 1.0 (values 0, 1).
constexpr std::array kSmall{S(3, 4), U(4, 4), S(0, 7), U(2, 6), S(7, 0),
                            U(8, 0), S(1, 2), U(0, 3), S(0, 0), U(1, 0)};

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
// Widest formats: sampled raws (edges, exact ties, random) against the reference.

constexpr std::array kWide{S(62, 0),  U(63, 0),  S(0, 62), U(0, 63), S(31, 31),
                           U(31, 32), S(40, 22), U(1, 62), S(20, 0), U(0, 40)};

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

// ---------------------------------------------------------------------------------------------
// Format ranges, parsing and refusals.

TEST(FormatTest, MinMaxRawForEveryValidFormat) {
  for (const bool s : {false, true}) {
    for (int i = 0; i <= fx::kMaxWidth; ++i) {
      for (int f = 0; f <= fx::kMaxWidth; ++f) {
        const Format fmt{s, i, f};
        if (!Valid(fmt)) continue;
        const fxref::Range rg = fxref::range(fmt);
        ASSERT_TRUE(fmt.min_raw() == rg.lo) << Name(fmt);
        ASSERT_TRUE(fmt.max_raw() == rg.hi) << Name(fmt);
        ASSERT_EQ(fmt.width(), fxref::width(fmt)) << Name(fmt);
        ASSERT_EQ(fx::Format::parse(fmt.str()), fmt) << Name(fmt);
        ASSERT_EQ(fx::make_format(s, i, f), fmt) << Name(fmt);
      }
    }
  }
  EXPECT_EQ(S(3, 4).min_raw(), -128);
  EXPECT_EQ(S(3, 4).max_raw(), 127);
  EXPECT_EQ(U(4, 4).max_raw(), 255);
  EXPECT_EQ(S(0, 0).min_raw(), -1);
  EXPECT_EQ(S(0, 0).max_raw(), 0);
  EXPECT_EQ(U(63, 0).max_raw(), kMax63);
  EXPECT_EQ(S(62, 0).min_raw(), -kP62);
  EXPECT_EQ(S(62, 0).max_raw(), kP62 - 1);
}

TEST(FormatTest, ParseAcceptsBothSpellings) {
  EXPECT_EQ(Format::parse("S1.10"), S(1, 10));
  EXPECT_EQ(Format::parse("s1.10"), S(1, 10));
  EXPECT_EQ(Format::parse("1.10"), U(1, 10));
  EXPECT_EQ(Format::parse("U1.10"), U(1, 10));
  EXPECT_EQ(Format::parse("u1.10"), U(1, 10));
  EXPECT_EQ(Format::parse("S0.0"), S(0, 0));  // 1 bit
  EXPECT_EQ(Format::parse("0.1"), U(0, 1));
  EXPECT_EQ(Format::parse("S62.0"), S(62, 0));  // 63 bits
  EXPECT_EQ(Format::parse("0.63"), U(0, 63));
  EXPECT_EQ(Format::parse("s1.10").str(), "S1.10");
  EXPECT_EQ(Format::parse("u1.10").str(), "1.10");
  EXPECT_EQ(Format::parse("U1.10").str(), "1.10");
  EXPECT_EQ(S(0, 0).str(), "S0.0");
  EXPECT_EQ(U(63, 0).str(), "63.0");
}

TEST(FormatTest, ParseRefusesBadText) {
  for (const char* text :
       {"S63.0", "64.0", "0.64", "S31.32", "S62.1", "0.0", "S-1.3", "1.-3", "-1.3", "S1.1O", "1.",
        ".3", "", "S", "U", "S.", ".", "1", "S1", "1.2.3", " 1.2", "1.2 ", "+1.2", "S+1.2", "x1.2",
        "SS1.2", "SU1.2", "1,2", "1.2x", "99999999999.1", "1.99999999999", "S1.10\n",
        // Counts that fit int but whose sum does not: must still be refused.
        "2147483647.1", "S2147483647.2147483647"}) {
    EXPECT_TRUE(ThrowsError([&] { (void)Format::parse(text); }, text)) << "'" << text << "'";
  }
}

TEST(FormatTest, MakeFormatRefusesBadCounts) {
  const struct {
    bool s;
    int i, f;
  } bad[] = {
      {false, 0, 0},
      {true, -1, 3},
      {false, 3, -1},
      {true, -1, 0},
      {false, -5, 10},
      {false, 10, -5},
      {false, 64, 0},
      {true, 63, 0},
      {true, 62, 1},
      {false, 0, 64},
      {true, 31, 32},
      {false, std::numeric_limits<int>::max(), 1},
      {true, std::numeric_limits<int>::max(), std::numeric_limits<int>::max()},
  };
  for (const auto& b : bad) {
    EXPECT_TRUE(ThrowsError([&] { (void)fx::make_format(b.s, b.i, b.f); }))
        << (b.s ? "S" : "") << b.i << "." << b.f;
  }
  EXPECT_EQ(fx::make_format(true, 0, 0), S(0, 0));
  EXPECT_EQ(fx::make_format(false, 63, 0), U(63, 0));
  EXPECT_EQ(fx::make_format(true, 31, 31), S(31, 31));
  EXPECT_EQ(fx::make_format(false, 0, 1), U(0, 1));
}

TEST(FormatTest, OperationsRefuseResultsWiderThan63Bits) {
  // Each message names the operation and its operands.
  EXPECT_TRUE(ThrowsError([] { (void)fx::mul_format(S(15, 16), S(15, 16)); }, "S15.16 * S15.16"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::mul_format(U(16, 16), U(16, 16)); }, "16.16 * 16.16"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::mul_format(S(15, 16), U(0, 32)); }, "S15.16 * 0.32"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::add_format(S(31, 31), S(31, 31)); }, "S31.31 + S31.31"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::add_format(U(63, 0), U(0, 1)); }, "63.0 + 0.1"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::sub_format(S(31, 31), U(0, 1)); }, "S31.31 - 0.1"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::sub_format(U(62, 0), U(62, 0)); }, "62.0 - 62.0"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::neg_format(S(31, 31)); }, "-S31.31"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::neg_format(U(63, 0)); }, "-63.0"));
  // The value-level operations refuse the same way.
  EXPECT_TRUE(ThrowsError(
      [] { (void)fx::mul(fx::from_raw(1, S(15, 16)), fx::from_raw(1, S(15, 16))); }, "*"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::neg(fx::from_raw(0, U(63, 0))); }, "-63.0"));
  // Right at the limit is fine.
  EXPECT_EQ(fx::mul_format(S(15, 15), U(16, 16)), S(31, 31));
  EXPECT_EQ(fx::mul_format(S(30, 0), S(0, 31)), S(31, 31));
  EXPECT_EQ(fx::mul_format(S(15, 16), U(0, 31)), S(15, 47));
  EXPECT_EQ(fx::add_format(U(62, 0), U(62, 0)), U(63, 0));
  EXPECT_EQ(fx::sub_format(S(30, 31), U(30, 31)), S(31, 31));
  EXPECT_EQ(fx::neg_format(U(62, 0)), S(62, 0));
}

TEST(FormatTest, FromRawRefusesOutOfRange) {
  EXPECT_TRUE(ThrowsError([] { (void)fx::from_raw(128, S(3, 4)); }, "128"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::from_raw(-129, S(3, 4)); }, "-129"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::from_raw(-1, U(4, 4)); }, "4.4"));
  EXPECT_TRUE(ThrowsError([] { (void)fx::from_raw(256, U(4, 4)); }));
  EXPECT_TRUE(ThrowsError([] { (void)fx::from_raw(1, S(0, 0)); }));
  EXPECT_TRUE(ThrowsError([] { (void)fx::from_raw(kP62, S(62, 0)); }));
  EXPECT_EQ(fx::from_raw(-128, S(3, 4)), (Fixed{-128, S(3, 4)}));
  EXPECT_EQ(fx::from_raw(kMax63, U(63, 0)), (Fixed{kMax63, U(63, 0)}));
}

// ---------------------------------------------------------------------------------------------
// Reals: round_scaled() and quantize().

struct RealCase {
  double x;
  Format fmt;
  std::int64_t truncate, half_up, half_even;
};

const RealCase kRealCases[] = {
    {0.5, S(3, 0), 0, 1, 0},
    {-0.5, S(3, 0), -1, 0, 0},
    {1.5, S(3, 0), 1, 2, 2},
    {2.5, S(3, 0), 2, 3, 2},
    {-1.5, S(3, 0), -2, -1, -2},
    {-2.5, S(3, 0), -3, -2, -2},
    {3.0, S(3, 0), 3, 3, 3},
    {-3.0, S(3, 0), -3, -3, -3},
    {0.3, S(1, 4), 4, 5, 5},          // 4.8
    {-0.3, S(1, 4), -5, -5, -5},      // -4.8
    {0.15625, S(0, 4), 2, 3, 2},      // 2.5
    {-0.15625, S(0, 4), -3, -2, -2},  // -2.5
    {0.21875, S(0, 4), 3, 4, 4},      // 3.5
    {1e-300, S(3, 4), 0, 0, 0},
    {-1e-300, S(3, 4), -1, 0, 0},  // truncate is floor, even for a tiny negative
    {-0.0, S(3, 4), 0, 0, 0},
    {7.96875, S(3, 4), 127, 128, 128},  // 127.5: half_up/half_even overflow (checked below)
    {1.0 - 0x1p-53, U(0, 63), kMax63 - 1023, kMax63 - 1023, kMax63 - 1023},  // 2^63 - 2^10
    {-0x1p62, S(62, 0), -kP62, -kP62, -kP62},
};

TEST(RealTest, RoundScaledAndQuantizeInRange) {
  for (const RealCase& c : kRealCases) {
    const std::int64_t want[] = {c.truncate, c.half_up, c.half_even};
    for (std::size_t i = 0; i < kRounds.size(); ++i) {
      EXPECT_EQ(fx::round_scaled(c.x, c.fmt.frac_bits, kRounds[i]), static_cast<double>(want[i]))
          << Real(c.x) << " into " << Name(c.fmt) << " " << Mode(kRounds[i], Overflow::wrap);
      if (want[i] > fxref::range(c.fmt).hi) continue;  // overflowing rows: QuantizeOutOfRange
      for (const Overflow o : kOverflows) {
        EXPECT_EQ(fx::quantize(c.x, c.fmt, kRounds[i], o), want[i])
            << Real(c.x) << " into " << Name(c.fmt) << " " << Mode(kRounds[i], o);
      }
    }
  }
}

struct RealOverflowCase {
  double x;
  Format fmt;
  Round round;
  std::int64_t wrap, saturate;
};

const RealOverflowCase kRealOverflowCases[] = {
    {100.0, S(3, 4), Round::truncate, 64, 127},     // 1600 mod 256 = 64
    {-100.0, S(3, 4), Round::truncate, -64, -128},  // -1600 mod 256 = 192 -> -64
    {8.0, S(3, 4), Round::truncate, -128, 127},
    {-8.0625, S(3, 4), Round::truncate, 127, -128},
    {7.96875, S(3, 4), Round::half_up, -128, 127},
    {7.96875, S(3, 4), Round::half_even, -128, 127},
    {-0.0625, U(4, 4), Round::truncate, 255, 0},
    {-0.03125, U(4, 4), Round::truncate, 255, 0},  // floor(-0.5) = -1
    {16.0, U(4, 4), Round::truncate, 0, 255},
    {0.5, S(0, 0), Round::half_up, -1, 0},
    {0x1p62, S(62, 0), Round::truncate, -kP62, kP62 - 1},
    {0x1p63, U(63, 0), Round::truncate, 0, kMax63},
    {-1.0, U(63, 0), Round::truncate, kMax63, 0},  // wrap keeps the low 63 bits: all ones
    {1e300, S(3, 4), Round::truncate, 0, 127},     // 1e300 * 16 is a multiple of 2^8
    {-1e300, S(3, 4), Round::half_even, 0, -128},
    // x * 2^4 overflows double to infinity; the exact value is still a multiple of 2^8.
    {std::numeric_limits<double>::max(), S(3, 4), Round::truncate, 0, 127},
    {-std::numeric_limits<double>::max(), S(3, 4), Round::truncate, 0, -128},
};

TEST(RealTest, QuantizeOutOfRange) {
  for (const RealOverflowCase& c : kRealOverflowCases) {
    const std::int64_t want[] = {c.wrap, c.saturate};
    for (std::size_t i = 0; i < kOverflows.size(); ++i) {
      EXPECT_EQ(fx::quantize(c.x, c.fmt, c.round, kOverflows[i]), want[i])
          << Real(c.x) << " into " << Name(c.fmt) << " " << Mode(c.round, kOverflows[i]);
    }
  }
}

// Reals k / 2^(m+2) on a grid of quarter-LSBs, past both ends of the range, against the reference.
TEST(RealTest, QuantizeGridMatchesReference) {
  for (const Format f : kSmall) {
    const fxref::Range rg = fxref::range(f);
    const int e = f.frac_bits + 2;
    for (auto k = static_cast<std::int64_t>(rg.lo * 4 - 70);
         k <= static_cast<std::int64_t>(rg.hi * 4 + 70); ++k) {
      const double x = std::ldexp(static_cast<double>(k), -e);
      for (const Round r : kRounds) {
        ASSERT_EQ(fx::round_scaled(x, f.frac_bits, r),
                  static_cast<double>(fxref::round_div(k, 4, r)))
            << Real(x) << " " << Name(f) << " " << Mode(r, Overflow::wrap);
        for (const Overflow o : kOverflows) {
          ASSERT_TRUE(fx::quantize(x, f, r, o) == fxref::requantize({k, e}, f, r, o))
              << "quantize(" << Real(x) << ", " << Name(f) << ", " << Mode(r, o)
              << ") = " << fx::quantize(x, f, r, o) << ", want "
              << fxref::to_string(fxref::requantize({k, e}, f, r, o));
        }
      }
    }
  }
}

// Exactly representable reals k * 2^-e (|k| < 2^53) into the widest formats, against the reference:
// in range, ties, and far out of range for both overflow modes.
TEST(RealTest, QuantizeWideFormatsMatchesReference) {
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<std::int64_t> mantissa(-(std::int64_t{1} << 53) + 1,
                                                       (std::int64_t{1} << 53) - 1);
  std::vector<std::int64_t> ks{
      -3, -2, -1, 0, 1, 2, 3, (std::int64_t{1} << 53) - 1, -(std::int64_t{1} << 53) + 1};
  for (int n = 0; n < 300; ++n) ks.push_back(mantissa(rng));
  Mismatches bad;
  for (const Format f : kWide) {
    for (const int shift : {-40, -11, -1, 0, 1, 2, 30}) {
      const int e = f.frac_bits + shift;  // x = k / 2^e, so x * 2^frac = k / 2^shift
      for (const std::int64_t k : ks) {
        const double x = std::ldexp(static_cast<double>(k), -e);
        // The reference wants a non-negative exponent: fold 2^-e into the numerator if needed.
        const fxref::Value v =
            e >= 0 ? fxref::Value{k, e} : fxref::Value{fxref::checked_mul(k, fxref::pow2(-e)), 0};
        for (const Round r : kRounds) {
          for (const Overflow o : kOverflows) {
            const std::int64_t got = fx::quantize(x, f, r, o);
            const fxref::i128 want = fxref::requantize(v, f, r, o);
            if (got != want &&
                bad.Report("quantize(" + Real(x) + ", " + Name(f) + ", " + Mode(r, o) +
                           ") = " + std::to_string(got) + ", want " + fxref::to_string(want))) {
              return;
            }
          }
        }
      }
    }
  }
}

TEST(RealTest, NonFiniteThrows) {
  for (const double x :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()}) {
    for (const Round r : kRounds) {
      EXPECT_TRUE(ThrowsError([&] { (void)fx::round_scaled(x, 4, r); })) << x;
      for (const Overflow o : kOverflows) {
        EXPECT_TRUE(ThrowsError([&] { (void)fx::quantize(x, S(3, 4), r, o); })) << x;
      }
    }
  }
}

TEST(RealTest, RawInRangeBounds) {
  EXPECT_TRUE(fx::raw_in_range(127.0, S(3, 4)));
  EXPECT_FALSE(fx::raw_in_range(128.0, S(3, 4)));
  EXPECT_TRUE(fx::raw_in_range(-128.0, S(3, 4)));
  EXPECT_FALSE(fx::raw_in_range(-129.0, S(3, 4)));
  EXPECT_FALSE(fx::raw_in_range(-1.0, U(4, 4)));
  EXPECT_TRUE(fx::raw_in_range(0x1p63 - 1024, U(63, 0)));  // largest double below 2^63
  EXPECT_FALSE(fx::raw_in_range(0x1p63, U(63, 0)));
  EXPECT_TRUE(fx::raw_in_range(-0x1p62, S(62, 0)));
  EXPECT_FALSE(fx::raw_in_range(-0x1p62 - 1024, S(62, 0)));
  EXPECT_FALSE(fx::raw_in_range(0x1p62, S(62, 0)));
}

TEST(RealTest, ToRealIsExactForSmallFormats) {
  EXPECT_EQ(fx::to_real(-128, S(3, 4)), -8.0);
  EXPECT_EQ(fx::to_real(255, U(4, 4)), 15.9375);
  EXPECT_EQ(fx::to_real(-1, S(0, 0)), -1.0);
  EXPECT_EQ((Fixed{16384, S(7, 8)}).real(), 64.0);
  for (const Format f : kSmall) {
    for (const std::int64_t raw : AllRaws(f)) {
      for (const Round r : kRounds) {
        for (const Overflow o : kOverflows) {
          ASSERT_EQ(fx::quantize(fx::to_real(raw, f), f, r, o), raw) << Name(f) << " " << raw;
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Port bits.

TEST(BitsTest, RoundTripsForEveryRawAndPattern) {
  for (const Format f : {S(3, 4), U(4, 4), S(0, 0), U(0, 1), S(7, 8), U(8, 8), S(1, 2)}) {
    const int w = fxref::width(f);
    for (const std::int64_t raw : AllRaws(f)) {
      const std::uint64_t bits = fx::to_bits(raw, f);
      ASSERT_TRUE(bits < fxref::pow2(w)) << Name(f) << " raw " << raw;
      ASSERT_TRUE(fxref::from_bits(bits, f) == raw) << Name(f) << " raw " << raw;
      ASSERT_EQ(fx::from_bits(bits, f), raw) << Name(f) << " raw " << raw;
    }
    for (std::uint64_t b = 0; b < static_cast<std::uint64_t>(fxref::pow2(w)); ++b) {
      const std::int64_t raw = fx::from_bits(b, f);
      ASSERT_TRUE(fxref::from_bits(b, f) == raw) << Name(f) << " bits " << b;
      ASSERT_EQ(fx::to_bits(raw, f), b) << Name(f) << " bits " << b;
      // Bits above the port width are ignored.
      ASSERT_EQ(fx::from_bits(b | (0xA5A5ull << w), f), raw) << Name(f) << " bits " << b;
    }
  }
  EXPECT_EQ(fx::to_bits(-128, S(3, 4)), 0x80u);
  EXPECT_EQ(fx::to_bits(-1, S(3, 4)), 0xFFu);
  EXPECT_EQ(fx::from_bits(0x80, S(3, 4)), -128);
  EXPECT_EQ(fx::from_bits(0x80, U(4, 4)), 128);
  EXPECT_EQ(fx::to_bits(-1, S(62, 0)), 0x7FFF'FFFF'FFFF'FFFFull);
  EXPECT_EQ(fx::from_bits(0x4000'0000'0000'0000ull, S(62, 0)), -kP62);
  EXPECT_EQ(fx::from_bits(0x3FFF'FFFF'FFFF'FFFFull, S(62, 0)), kP62 - 1);
  EXPECT_EQ(fx::from_bits(~0ull, U(63, 0)), kMax63);
  EXPECT_EQ(fx::from_bits(~0ull, S(0, 0)), -1);
}

// ---------------------------------------------------------------------------------------------
// Mode names.

TEST(ModeNames, ParseAndPrint) {
  EXPECT_EQ(fx::parse_round("truncate"), Round::truncate);
  EXPECT_EQ(fx::parse_round("half_up"), Round::half_up);
  EXPECT_EQ(fx::parse_round("half_even"), Round::half_even);
  EXPECT_EQ(fx::parse_overflow("wrap"), Overflow::wrap);
  EXPECT_EQ(fx::parse_overflow("saturate"), Overflow::saturate);
  for (const Round r : kRounds) EXPECT_EQ(fx::parse_round(fx::to_string(r)), r);
  for (const Overflow o : kOverflows) EXPECT_EQ(fx::parse_overflow(fx::to_string(o)), o);
  EXPECT_EQ(fx::to_string(Round::half_even), "half_even");
  EXPECT_EQ(fx::to_string(Overflow::saturate), "saturate");
  // Encodings are shared with the RTL's fx_pkg.
  EXPECT_EQ(static_cast<int>(Round::truncate), 0);
  EXPECT_EQ(static_cast<int>(Round::half_up), 1);
  EXPECT_EQ(static_cast<int>(Round::half_even), 2);
  EXPECT_EQ(static_cast<int>(Overflow::wrap), 0);
  EXPECT_EQ(static_cast<int>(Overflow::saturate), 1);
}

TEST(ModeNames, RejectsUnknownNames) {
  for (const char* name :
       {"", "Truncate", "half-up", "halfeven", "round", "half_even ", "wrap", "nearest"}) {
    EXPECT_TRUE(ThrowsError([&] { (void)fx::parse_round(name); }, name)) << "'" << name << "'";
  }
  for (const char* name : {"", "Wrap", "sat", "clamp", "saturate\n", "truncate"}) {
    EXPECT_TRUE(ThrowsError([&] { (void)fx::parse_overflow(name); }, name)) << "'" << name << "'";
  }
}

}  // namespace
