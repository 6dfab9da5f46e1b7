// Independent exact reference for the fixed-point core (tests only).
//
// Values are exact rationals num / 2^exp. Requantization follows the definitions in model/fixed.h
// literally: scale to an exact fraction n/d, true floor division with explicit sign correction,
// rounding by comparing the remainder with d/2, then clamping or modular reduction. It uses no
// shifts and calls nothing from fixed.cpp (only the plain Format/Round/Overflow types), so it
// cannot share a bug with the shift-based implementation. Every i128 operation is overflow
// checked: a reference that silently wrapped would be worthless.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "model/fixed.h"

namespace fxref {

using i128 = __int128;
using phongsim::fx::Format;
using phongsim::fx::Overflow;
using phongsim::fx::Round;

inline i128 checked_add(i128 a, i128 b) {
  i128 r;
  if (__builtin_add_overflow(a, b, &r)) throw std::logic_error("fxref: i128 add overflow");
  return r;
}

inline i128 checked_mul(i128 a, i128 b) {
  i128 r;
  if (__builtin_mul_overflow(a, b, &r)) throw std::logic_error("fxref: i128 mul overflow");
  return r;
}

// 2^k for 0 <= k <= 126, by repeated doubling.
inline i128 pow2(int k) {
  static const std::array<i128, 127> table = [] {
    std::array<i128, 127> t{};
    t[0] = 1;
    for (int i = 1; i < 127; ++i) t[i] = t[i - 1] * 2;
    return t;
  }();
  if (k < 0 || k > 126) throw std::logic_error("fxref: pow2 exponent out of range");
  return table[static_cast<std::size_t>(k)];
}

// Counted from the Lyon definition, not via Format::width().
inline int width(Format f) { return (f.is_signed ? 1 : 0) + f.int_bits + f.frac_bits; }

// Raw range of a format: [-2^(w-1), 2^(w-1) - 1] signed, [0, 2^w - 1] unsigned.
struct Range {
  i128 lo;
  i128 hi;
};
inline Range range(Format f) {
  const int w = width(f);
  if (f.is_signed) return {-pow2(w - 1), pow2(w - 1) - 1};
  return {0, pow2(w) - 1};
}

// The exact rational num / 2^exp (exp >= 0).
struct Value {
  i128 num = 0;
  int exp = 0;
};

inline Value value_of(std::int64_t raw, Format f) { return {raw, f.frac_bits}; }

// Same value expressed with a larger exponent.
inline i128 num_at(Value v, int exp) { return checked_mul(v.num, pow2(exp - v.exp)); }

inline Value add(Value a, Value b) {
  const int e = a.exp > b.exp ? a.exp : b.exp;
  return {checked_add(num_at(a, e), num_at(b, e)), e};
}
inline Value neg(Value a) { return {checked_mul(a.num, -1), a.exp}; }
inline Value sub(Value a, Value b) { return add(a, neg(b)); }
inline Value mul(Value a, Value b) { return {checked_mul(a.num, b.num), a.exp + b.exp}; }

inline bool equal(Value a, Value b) {
  const int e = a.exp > b.exp ? a.exp : b.exp;
  return num_at(a, e) == num_at(b, e);
}

// q = floor(n / d) and 0 <= r < d for d > 0. C++ division truncates toward zero, so a negative
// remainder means the quotient must step down by one.
struct DivMod {
  i128 q;
  i128 r;
};
inline DivMod floor_divmod(i128 n, i128 d) {
  i128 q = n / d;
  i128 r = n % d;
  if (r < 0) {
    q -= 1;
    r += d;
  }
  return {q, r};
}

// n / d rounded to an integer per `round` (d a power of two >= 1).
inline i128 round_div(i128 n, i128 d, Round round) {
  const auto [q, r] = floor_divmod(n, d);
  const i128 twice_r = checked_mul(r, 2);  // compare r with d/2 without halving d
  switch (round) {
    case Round::truncate:
      return q;
    case Round::half_up:
      return twice_r >= d ? q + 1 : q;
    case Round::half_even:
      if (twice_r > d) return q + 1;
      if (twice_r < d) return q;
      return q % 2 == 0 ? q : q + 1;  // tie: the even neighbour (q % 2 is -1 for odd negatives)
  }
  throw std::logic_error("fxref: bad Round");
}

// Brings an integer raw q into `to`: clamp, or reduce modulo 2^w into [lo, lo + 2^w).
inline i128 apply_overflow(i128 q, Format to, Overflow overflow) {
  const Range rg = range(to);
  if (overflow == Overflow::saturate) return q < rg.lo ? rg.lo : (q > rg.hi ? rg.hi : q);
  const i128 m = pow2(width(to));
  i128 r = checked_add(q, -rg.lo) % m;
  if (r < 0) r += m;
  return rg.lo + r;
}

// The raw value in `to` for exact value v, by definition.
inline i128 requantize(Value v, Format to, Round round, Overflow overflow) {
  i128 n = v.num;
  i128 d = 1;
  if (to.frac_bits >= v.exp) {
    n = checked_mul(v.num, pow2(to.frac_bits - v.exp));
  } else {
    d = pow2(v.exp - to.frac_bits);
  }
  return apply_overflow(round_div(n, d, round), to, overflow);
}

// True when format f represents v exactly: v * 2^frac is an integer within f's raw range.
inline bool fits(Value v, Format f) {
  i128 n = v.num;
  i128 d = 1;
  if (f.frac_bits >= v.exp) {
    n = checked_mul(v.num, pow2(f.frac_bits - v.exp));
  } else {
    d = pow2(v.exp - f.frac_bits);
  }
  const auto [q, r] = floor_divmod(n, d);
  const Range rg = range(f);
  return r == 0 && rg.lo <= q && q <= rg.hi;
}

// Raw value carried by the low `width` bits of a port.
inline i128 from_bits(std::uint64_t bits, Format f) {
  const i128 b = static_cast<i128>(bits) % pow2(width(f));
  return f.is_signed && b >= pow2(width(f) - 1) ? b - pow2(width(f)) : b;
}

inline std::string to_string(i128 v) {
  if (v == 0) return "0";
  const bool negative = v < 0;
  std::string digits;
  while (v != 0) {
    const int digit = static_cast<int>(v % 10);
    digits.insert(digits.begin(), static_cast<char>('0' + (digit < 0 ? -digit : digit)));
    v /= 10;
  }
  return negative ? "-" + digits : digits;
}

inline std::string to_string(Value v) { return to_string(v.num) + "/2^" + std::to_string(v.exp); }

}  // namespace fxref
