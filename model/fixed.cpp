#include "model/fixed.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "base/error.h"

namespace phongsim::fx {
namespace detail {

void refuse(Format r, const char* op, Format a, Format b) {
  const std::string o = op;
  const std::string what = o == "neg"     ? fmt::format("-{}", a.str())
                           : o == "abs"   ? fmt::format("|{}|", a.str())
                           : o == "scale" ? fmt::format("scale({})", a.str())
                                          : fmt::format("{} {} {}", a.str(), op, b.str());
  if (r.width() > kMaxWidth) {
    throw Error(
        fmt::format("{}: the exact result needs {} bits, over the model's {}-bit limit "
                    "(int64_t raw values)",
                    what, r.width(), kMaxWidth));
  }
  throw Error(fmt::format("{}: invalid result format", what));
}

}  // namespace detail

namespace {

void check_format(Format f, std::string_view text) {
  if (f.int_bits < 0 || f.frac_bits < 0) {
    throw Error(fmt::format("format {}: integer and fraction bit counts must be >= 0", text));
  }
  // In 64 bits: Format::width() would overflow int for counts near INT_MAX.
  const long long width = (f.is_signed ? 1LL : 0LL) + f.int_bits + f.frac_bits;
  if (width < 1) throw Error(fmt::format("format {}: a format needs at least one bit", text));
  if (width > kMaxWidth) {
    throw Error(
        fmt::format("format {}: {} bits exceeds the model's {}-bit limit (int64_t raw "
                    "values)",
                    text, width, kMaxWidth));
  }
}

}  // namespace

std::string Format::str() const {
  return fmt::format("{}{}.{}", is_signed ? "S" : "", int_bits, frac_bits);
}

Format Format::parse(std::string_view text) {
  const auto bad = [&]() {
    return Error(
        fmt::format("'{}' is not a fixed-point format (expected n.m or Sn.m, e.g. 1.10 "
                    "or S1.10)",
                    text));
  };
  std::string_view s = text;
  bool is_signed = false;
  if (!s.empty() && (s.front() == 'S' || s.front() == 's')) {
    is_signed = true;
    s.remove_prefix(1);
  } else if (!s.empty() && (s.front() == 'U' || s.front() == 'u')) {
    s.remove_prefix(1);
  }
  const auto dot = s.find('.');
  if (dot == std::string_view::npos) throw bad();
  const auto parse_count = [&](std::string_view part) {
    int value = 0;
    const auto* end = part.data() + part.size();
    const auto [ptr, ec] = std::from_chars(part.data(), end, value);
    if (part.empty() || ec != std::errc{} || ptr != end) throw bad();
    return value;
  };
  const int int_bits = parse_count(s.substr(0, dot));
  const int frac_bits = parse_count(s.substr(dot + 1));
  const Format f{is_signed, int_bits, frac_bits};
  check_format(f, text);
  return f;
}

Format make_format(bool is_signed, int int_bits, int frac_bits) {
  const Format f{is_signed, int_bits, frac_bits};
  check_format(f, fmt::format("{}{}.{}", is_signed ? "S" : "", int_bits, frac_bits));
  return f;
}

double Fixed::real() const { return to_real(raw, fmt); }

Fixed from_raw(std::int64_t raw, Format fmt) {
  if (raw < fmt.min_raw() || raw > fmt.max_raw()) {
    throw Error(fmt::format("raw value {} does not fit format {} [{}, {}]", raw, fmt.str(),
                            fmt.min_raw(), fmt.max_raw()));
  }
  return {raw, fmt};
}

namespace detail {

void not_finite(double x) { throw Error(fmt::format("cannot quantize {}", x)); }

std::int64_t wrap(double q, Format fmt) {
  // Keep the low width bits of q. x·2^m beyond double's range (q infinite) means |x| >= 2^961,
  // a multiple of 2^909, so its low 63 bits are all zero.
  if (!std::isfinite(q)) return 0;
  // fmod by a power of two is exact and |remainder| < 2^63: exact in __int128, and two's
  // complement masking then gives the low bits of negative values too.
  const double rem = std::fmod(q, std::ldexp(1.0, fmt.width()));
  return from_bits(static_cast<std::uint64_t>(static_cast<__int128>(rem)), fmt);
}

}  // namespace detail

Round parse_round(std::string_view name) {
  if (name == "truncate") return Round::truncate;
  if (name == "half_up") return Round::half_up;
  if (name == "half_even") return Round::half_even;
  throw Error(
      fmt::format("unknown rounding mode '{}' (expected truncate, half_up or half_even)", name));
}

Overflow parse_overflow(std::string_view name) {
  if (name == "wrap") return Overflow::wrap;
  if (name == "saturate") return Overflow::saturate;
  throw Error(fmt::format("unknown overflow mode '{}' (expected wrap or saturate)", name));
}

std::string_view to_string(Round round) {
  switch (round) {
    case Round::truncate:
      return "truncate";
    case Round::half_up:
      return "half_up";
    case Round::half_even:
      return "half_even";
  }
  return "?";
}

std::string_view to_string(Overflow overflow) {
  return overflow == Overflow::wrap ? "wrap" : "saturate";
}

}  // namespace phongsim::fx
