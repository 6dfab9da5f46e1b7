// Test helpers shared by the fixed-point core's tests (fixed_arith_test.cpp,
// fixed_format_test.cpp): the test formats, rounding and overflow modes, own spellings of formats
// and modes for messages, every raw value of a format, a mismatch collector and an Error matcher.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "model/fixed.h"
#include "tests/fx_reference.h"

// Lets gtest print formats readably in parameterized test names and assertion messages.
namespace phongsim::fx {
inline void PrintTo(const Format& f, std::ostream* os) {
  *os << (f.is_signed ? "S" : "") << f.int_bits << "." << f.frac_bits;
}
}  // namespace phongsim::fx

namespace phongsim::testing {

namespace fx = phongsim::fx;
using fx::Fixed;
using fx::Format;
using fx::Overflow;
using fx::Round;
using phongsim::Error;

inline constexpr std::array kRounds{Round::truncate, Round::half_up, Round::half_even};
inline constexpr std::array kOverflows{Overflow::wrap, Overflow::saturate};

inline constexpr std::int64_t kP62 = std::int64_t{1} << 62;
inline constexpr std::int64_t kMax63 = std::numeric_limits<std::int64_t>::max();  // 2^63 - 1

constexpr Format S(int int_bits, int frac_bits) { return {true, int_bits, frac_bits}; }
constexpr Format U(int int_bits, int frac_bits) { return {false, int_bits, frac_bits}; }

// Own spelling of a format for messages, so a broken str() cannot garble failure reports.
inline std::string Name(Format f) {
  return fmt::format("{}{}.{}", f.is_signed ? "S" : "", f.int_bits, f.frac_bits);
}

inline std::string Mode(Round r, Overflow o) {
  const char* rn = r == Round::truncate  ? "truncate"
                   : r == Round::half_up ? "half_up"
                                         : "half_even";
  return std::string(rn) + "/" + (o == Overflow::wrap ? "wrap" : "saturate");
}

inline bool Valid(Format f) {
  const int w = fxref::width(f);
  return f.int_bits >= 0 && f.frac_bits >= 0 && w >= 1 && w <= fx::kMaxWidth;
}

// Every raw value of a format, in order (from the reference's range, not min_raw/max_raw).
inline std::vector<std::int64_t> AllRaws(Format f) {
  const fxref::Range r = fxref::range(f);
  std::vector<std::int64_t> out;
  for (auto v = static_cast<std::int64_t>(r.lo); v <= static_cast<std::int64_t>(r.hi); ++v) {
    out.push_back(v);
  }
  return out;
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

// Expects fn() to throw phongsim::Error whose message contains `needle`.
inline ::testing::AssertionResult ThrowsError(const std::function<void()>& fn,
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
inline constexpr std::array kSmall{S(3, 4), U(4, 4), S(0, 7), U(2, 6), S(7, 0),
                                   U(8, 0), S(1, 2), U(0, 3), S(0, 0), U(1, 0)};

// The widest formats (up to 63 bits), sampled rather than enumerated.
inline constexpr std::array kWide{S(62, 0),  U(63, 0),  S(0, 62), U(0, 63), S(31, 31),
                                  U(31, 32), S(40, 22), U(1, 62), S(20, 0), U(0, 40)};

}  // namespace phongsim::testing
