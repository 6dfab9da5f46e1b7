// Bit-accurate fixed-point core: formats as runtime values, exact width growth, explicit
// requantization. rtl/common/fx_*.sv implements the same operations with the same names;
// docs/fixed-point.md is the specification both follow.
//
// Notation (Lyon, TR #43): "n.m" is unsigned with n integer and m fraction bits (n + m bits);
// "Sn.m" is signed two's complement with 1 + n + m bits. A value is an integer `raw` scaled by
// 2^-m. All raw values and every intermediate live in int64_t, so no format may be wider than
// kMaxWidth bits; formats and operations that would exceed it are refused when they are built
// (configuration time), never wrapped silently.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace phongsim::fx {

inline constexpr int kMaxWidth = 63;  // widest format whose raw value fits int64_t, signed or not

// Quantization when fraction bits are dropped. Encodings match fx_pkg::FxRound* in the RTL.
enum class Round : std::uint8_t {
  truncate = 0,   // floor (toward minus infinity): drop the bits
  half_up = 1,    // nearest, ties toward plus infinity: floor(x + 1/2)
  half_even = 2,  // nearest, ties to the even neighbour (convergent rounding)
};

// What happens when a value does not fit the destination. Encodings match fx_pkg::FxOverflow*.
enum class Overflow : std::uint8_t {
  wrap = 0,      // keep the low bits (two's complement modulo 2^width)
  saturate = 1,  // clamp to the most negative / most positive representable value
};

struct Format {
  bool is_signed = false;
  int int_bits = 0;
  int frac_bits = 0;

  [[nodiscard]] constexpr int width() const { return (is_signed ? 1 : 0) + int_bits + frac_bits; }
  [[nodiscard]] constexpr std::int64_t min_raw() const {
    return is_signed ? -(std::int64_t{1} << (width() - 1)) : 0;
  }
  [[nodiscard]] constexpr std::int64_t max_raw() const {
    return static_cast<std::int64_t>((std::uint64_t{1} << (is_signed ? width() - 1 : width())) - 1);
  }
  [[nodiscard]] std::string str() const;  // "S1.10" or "1.10"

  // Parses "S1.10" / "1.10" (also "s1.10", "U1.10", "u1.10") and validates; throws Error.
  [[nodiscard]] static Format parse(std::string_view text);

  friend bool operator==(const Format&, const Format&) = default;
};

// Raw value <-> the `width` bits a hardware port carries (zero-extended in a uint64_t).
// Inline: RTL plugins use them without linking the model.
[[nodiscard]] inline std::uint64_t to_bits(std::int64_t raw, Format fmt) {
  return static_cast<std::uint64_t>(raw) & ((std::uint64_t{1} << fmt.width()) - 1);
}
[[nodiscard]] inline std::int64_t from_bits(std::uint64_t bits, Format fmt) {
  const std::uint64_t mask = (std::uint64_t{1} << fmt.width()) - 1;
  bits &= mask;
  if (fmt.is_signed && ((bits >> (fmt.width() - 1)) & 1U) != 0) {
    return static_cast<std::int64_t>(bits | ~mask);
  }
  return static_cast<std::int64_t>(bits);
}

// Builds and validates a format: int_bits, frac_bits >= 0, 1 <= width <= kMaxWidth.
[[nodiscard]] Format make_format(bool is_signed, int int_bits, int frac_bits);

// Result formats of exact operations (no rounding, no overflow possible). Each throws Error
// when the result would be wider than kMaxWidth.
//   add: fraction max(fa, fb); integer max(ia, ib) + 1; signed if either operand is.
//   sub: fraction max(fa, fb); integer max(ia, ib) + 1; always signed.
//   mul: fraction fa + fb; integer ia + ib (+1 when both are signed); width wa + wb.
//   neg: signed; integer ia + 1 when a is signed (-(-2^ia) needs it), else ia.
//   abs: unsigned; integer ia + 1 when a is signed (|-2^ia| needs it), else ia.
//   scale by 2^k (k may be negative): the binary point moves, bits stay. k >= 0: integer ia + k,
//     fraction max(fa - k, 0) (raw shifted left by max(k - fa, 0)); k < 0: fraction fa - k,
//     integer max(ia + k, 0) (raw unchanged, the format may widen).
namespace detail {
[[nodiscard]] constexpr bool valid(Format f) {
  return f.int_bits >= 0 && f.frac_bits >= 0 && f.int_bits <= kMaxWidth &&
         f.frac_bits <= kMaxWidth && f.width() >= 1 && f.width() <= kMaxWidth;
}
// Throws Error for the result `r` of operation `op` on a (and b); out of line, off the hot path.
[[noreturn]] void refuse(Format r, const char* op, Format a, Format b);
}  // namespace detail

[[nodiscard]] inline Format add_format(Format a, Format b) {
  const Format r{a.is_signed || b.is_signed, std::max(a.int_bits, b.int_bits) + 1,
                 std::max(a.frac_bits, b.frac_bits)};
  if (!detail::valid(r)) [[unlikely]]
    detail::refuse(r, "+", a, b);
  return r;
}
[[nodiscard]] inline Format sub_format(Format a, Format b) {
  const Format r{true, std::max(a.int_bits, b.int_bits) + 1, std::max(a.frac_bits, b.frac_bits)};
  if (!detail::valid(r)) [[unlikely]]
    detail::refuse(r, "-", a, b);
  return r;
}
[[nodiscard]] inline Format mul_format(Format a, Format b) {
  const Format r{a.is_signed || b.is_signed,
                 a.int_bits + b.int_bits + (a.is_signed && b.is_signed ? 1 : 0),
                 a.frac_bits + b.frac_bits};
  if (!detail::valid(r)) [[unlikely]]
    detail::refuse(r, "*", a, b);
  return r;
}
[[nodiscard]] inline Format neg_format(Format a) {
  const Format r{true, a.int_bits + (a.is_signed ? 1 : 0), a.frac_bits};
  if (!detail::valid(r)) [[unlikely]]
    detail::refuse(r, "neg", a, a);
  return r;
}
[[nodiscard]] inline Format abs_format(Format a) {
  const Format r{false, a.int_bits + (a.is_signed ? 1 : 0), a.frac_bits};
  if (!detail::valid(r)) [[unlikely]]
    detail::refuse(r, "abs", a, a);
  return r;
}
[[nodiscard]] inline Format scale_format(Format a, int k) {
  const Format r = k >= 0 ? Format{a.is_signed, a.int_bits + k, std::max(a.frac_bits - k, 0)}
                          : Format{a.is_signed, std::max(a.int_bits + k, 0), a.frac_bits - k};
  if (!detail::valid(r)) [[unlikely]]
    detail::refuse(r, "scale", a, a);
  return r;
}

// A value: raw integer plus its format. Operations check their result format (cheap integer
// compares) so even unplanned use cannot overflow the host integer.
struct Fixed {
  std::int64_t raw = 0;
  Format fmt;

  [[nodiscard]] double real() const;
  friend bool operator==(const Fixed&, const Fixed&) = default;
};

// `raw` must lie in fmt's range; throws Error otherwise.
[[nodiscard]] Fixed from_raw(std::int64_t raw, Format fmt);

[[nodiscard]] inline Fixed add(Fixed a, Fixed b) {
  const Format r = add_format(a.fmt, b.fmt);
  return {(a.raw << (r.frac_bits - a.fmt.frac_bits)) + (b.raw << (r.frac_bits - b.fmt.frac_bits)),
          r};
}
[[nodiscard]] inline Fixed sub(Fixed a, Fixed b) {
  const Format r = sub_format(a.fmt, b.fmt);
  return {(a.raw << (r.frac_bits - a.fmt.frac_bits)) - (b.raw << (r.frac_bits - b.fmt.frac_bits)),
          r};
}
[[nodiscard]] inline Fixed mul(Fixed a, Fixed b) {
  return {a.raw * b.raw, mul_format(a.fmt, b.fmt)};
}
[[nodiscard]] inline Fixed neg(Fixed a) { return {-a.raw, neg_format(a.fmt)}; }
[[nodiscard]] inline Fixed abs(Fixed a) { return {a.raw < 0 ? -a.raw : a.raw, abs_format(a.fmt)}; }
// x · 2^k, exact: a shift of the binary point (see scale_format).
[[nodiscard]] inline Fixed scale(Fixed a, int k) {
  const Format r = scale_format(a.fmt, k);
  return {a.raw << std::max(k - a.fmt.frac_bits, 0), r};
}

// `raw` (in `from`) aligned to `to`'s binary point, rounding per `round` when fraction bits are
// dropped; not yet fitted to `to`'s range.
[[nodiscard]] inline __int128 align_raw(std::int64_t raw, Format from, Format to, Round round) {
  using i128 = __int128;  // |raw| < 2^63 shifted by at most 63 bits, plus a rounding bias
  i128 v = raw;
  const int d = from.frac_bits - to.frac_bits;
  if (d < 0) {
    v <<= -d;
  } else if (d > 0) {
    const i128 half = i128{1} << (d - 1);
    switch (round) {
      case Round::truncate:
        break;
      case Round::half_up:
        v += half;
        break;
      case Round::half_even:  // ties go up exactly when the kept LSB is odd
        v += half - 1 + ((v >> d) & 1);
        break;
    }
    v >>= d;  // arithmetic: floor
  }
  return v;
}

// Requantize `raw` (in `from`) to `to`: align the binary point (rounding per `round` when fraction
// bits are dropped), then handle overflow per `overflow`. Exact whenever `to` can hold the value.
[[nodiscard]] inline std::int64_t resize_raw(std::int64_t raw, Format from, Format to, Round round,
                                             Overflow overflow) {
  const __int128 v = align_raw(raw, from, to, round);
  if (v >= to.min_raw() && v <= to.max_raw()) [[likely]]
    return static_cast<std::int64_t>(v);
  if (overflow == Overflow::saturate) return v < to.min_raw() ? to.min_raw() : to.max_raw();
  return from_bits(static_cast<std::uint64_t>(v), to);  // wrap: keep the low width bits
}

// Where resize_raw's rounded value falls against `to`'s range, before the overflow mode acts:
// -1 below it (saturates low), +1 above it (saturates high), 0 inside (no overflow).
[[nodiscard]] inline int resize_side(std::int64_t raw, Format from, Format to, Round round) {
  const __int128 v = align_raw(raw, from, to, round);
  return v < to.min_raw() ? -1 : v > to.max_raw() ? 1 : 0;
}
[[nodiscard]] inline Fixed resize(Fixed x, Format to, Round round, Overflow overflow) {
  return {resize_raw(x.raw, x.fmt, to, round, overflow), to};
}

// Clamp to [0, 1] in the value's own format (fx_clamp01.sv): negative -> 0, above 1.0 -> 1.0
// (a format without integer bits cannot exceed 1).
[[nodiscard]] inline std::int64_t clamp01_raw(std::int64_t raw, Format fmt) {
  if (raw < 0) return 0;
  if (fmt.int_bits >= 1 && raw > (std::int64_t{1} << fmt.frac_bits)) {
    return std::int64_t{1} << fmt.frac_bits;
  }
  return raw;
}

// Real <-> fixed, inline with their rare paths out of line (every stimulus quantizes its random
// geometry through them).
namespace detail {
[[noreturn]] void not_finite(double x);                 // throws Error
[[nodiscard]] std::int64_t wrap(double q, Format fmt);  // quantize()'s wrap of an integer q

// 2^k as a double; a multiplication by it is exactly ldexp (both are the correctly rounded
// product), without ldexp's library call, which dominated the stimulus' quantization.
[[nodiscard]] inline double pow2(int k) {
  if (k >= 0 && k < 64) return static_cast<double>(std::uint64_t{1} << k);
  if (k < 0 && k > -64) return 1 / static_cast<double>(std::uint64_t{1} << -k);  // exact
  return std::ldexp(1.0, k);
}
}  // namespace detail

// Real <-> fixed. quantize() rounds x·2^frac per `round` and then handles overflow; throws Error
// for NaN or infinity. round_scaled() is the rounding step alone (result is an integer-valued
// double, or +-infinity when x·2^frac exceeds double's range), for callers that want to reject
// out-of-range reals instead of saturating them.
[[nodiscard]] inline double round_scaled(double x, int frac_bits, Round round) {
  if (!std::isfinite(x)) detail::not_finite(x);
  const double s = x * detail::pow2(frac_bits);  // exact (power-of-two scaling)
  if (!(std::abs(s) < 0x1p52)) return s;         // an integer already: every mode keeps it
  // Below 2^52 in integers and without branches on the value: std::floor is a library call in
  // baseline x86-64 code, and the comparisons' branches mispredict on random stimulus values.
  const auto t = static_cast<std::int64_t>(s);  // toward zero, exact
  const std::int64_t f = t - static_cast<std::int64_t>(static_cast<double>(t) > s);  // floor
  const double rest = s - static_cast<double>(f);  // exact: 0 <= rest < 1
  std::int64_t up = 0;
  switch (round) {
    case Round::truncate:
      break;
    case Round::half_up:
      up = static_cast<std::int64_t>(rest >= 0.5);
      break;
    case Round::half_even:  // above the half, or on it with f odd
      up = static_cast<std::int64_t>(rest > 0.5) | (static_cast<std::int64_t>(rest == 0.5) & f & 1);
      break;
  }
  return static_cast<double>(f + up);
}

// min_raw() <= scaled <= max_raw()
[[nodiscard]] inline bool raw_in_range(double scaled, Format fmt) {
  // Bounds as exact doubles: max_raw() + 1 is a power of two, max_raw() itself may not be.
  const double above_max = detail::pow2(fmt.is_signed ? fmt.width() - 1 : fmt.width());
  return scaled >= static_cast<double>(fmt.min_raw()) && scaled < above_max;
}

[[nodiscard]] inline std::int64_t quantize(double x, Format fmt, Round round, Overflow overflow) {
  const double q = round_scaled(x, fmt.frac_bits, round);
  if (raw_in_range(q, fmt)) return static_cast<std::int64_t>(q);
  if (overflow == Overflow::saturate) return q < 0 ? fmt.min_raw() : fmt.max_raw();
  return detail::wrap(q, fmt);
}

[[nodiscard]] inline double to_real(std::int64_t raw, Format fmt) {
  return static_cast<double>(raw) * detail::pow2(-fmt.frac_bits);
}

[[nodiscard]] Round parse_round(std::string_view name);        // "truncate", "half_up", ...
[[nodiscard]] Overflow parse_overflow(std::string_view name);  // "wrap", "saturate"
[[nodiscard]] std::string_view to_string(Round round);
[[nodiscard]] std::string_view to_string(Overflow overflow);

}  // namespace phongsim::fx
