// Tests for the bit-accurate fixed-point core (model/fixed.*): formats (ranges, parsing,
// refusals), reals (round_scaled, quantize, to_real), port bits and rounding / overflow mode
// names. Expected values are literals derived by hand from the definitions in model/fixed.h or
// come from the independent exact reference in tests/fx_reference.h. The arithmetic and
// requantization: fixed_arith_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "model/fixed.h"
#include "tests/fixed_helpers.h"
#include "tests/fx_reference.h"

namespace {

using namespace phongsim::testing;  // tests/fixed_helpers.h

// Reals in messages: hexfloat so the printed value is the exact one.
std::string Real(double x) {
  std::ostringstream out;
  out << std::hexfloat << x;
  return out.str();
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

// round_scaled against its definition on the library's floor and fmod, over doubles of every
// magnitude from 2^-60 to 2^70 (across 2^52 and 2^53, where doubles stop having fraction bits
// and stop being odd), both signs, and exact ties (k + 1/2).
TEST(RealTest, RoundScaledMatchesFloorDefinition) {
  const auto reference = [](double x, int frac_bits, Round round) {
    const double s = std::ldexp(x, frac_bits);
    const double f = std::floor(s);
    const double rest = s - f;
    if (round == Round::truncate) return f;
    if (round == Round::half_up) return rest >= 0.5 ? f + 1 : f;
    if (rest != 0.5) return rest > 0.5 ? f + 1 : f;
    return std::fmod(f, 2.0) == 0.0 ? f : f + 1;
  };
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> exponent(-60, 70);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> frac(0, 12);
  for (int i = 0; i < 200000; ++i) {
    double x = std::ldexp(mantissa(rng), exponent(rng));
    if (i % 4 == 1) x = std::ldexp(std::floor(x) + 0.5, 0);  // a tie at frac_bits 0 (or integer)
    if (i % 2 == 1) x = -x;
    const int fb = i % 4 == 1 ? 0 : frac(rng);
    for (const Round r : kRounds) {
      ASSERT_EQ(fx::round_scaled(x, fb, r), reference(x, fb, r))
          << Real(x) << " frac_bits " << fb << " " << Mode(r, Overflow::wrap);
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

// The power-of-two scaling in round_scaled and to_real is a multiplication, not ldexp: the same
// double for every exponent, subnormal and overflowing results included.
TEST(RealTest, ScalingIsLdexp) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-1074, 1023);
  for (int n = 0; n < 20000; ++n) {
    const double x = std::ldexp(mantissa(rng), exponent(rng));
    for (const int k : {-70, -64, -63, -40, -1, 0, 1, 12, 52, 63, 64, 70}) {
      ASSERT_EQ(fx::round_scaled(x, k, Round::truncate), std::floor(std::ldexp(x, k)))
          << Real(x) << " * 2^" << k;
    }
  }
  for (const Format f : {S(1, 10), U(0, 63), S(62, 0), S(31, 31)}) {
    for (const std::int64_t raw : {f.min_raw(), std::int64_t{-1}, std::int64_t{1}, f.max_raw()}) {
      if (raw < f.min_raw()) continue;
      EXPECT_EQ(fx::to_real(raw, f), std::ldexp(static_cast<double>(raw), -f.frac_bits))
          << raw << " in " << Name(f);
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
