// The steps a model's compiled plan is made of. Formats stay runtime values read from the
// configuration, but each operation's formats are derived (and checked) once, when the plan is
// compiled; what remains per vector is integer work on int64_t: alignment shifts, adds,
// multiplies, and each requantization as one precomputed shift / round / clamp / wrap step.
// The stage-by-stage path (fx::Fixed, model/fixed.h) stays the reference: every plan is tested
// bit-identical to it (tests/plan_test.cpp). Specification: docs/fixed-point.md.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "model/fixed.h"

namespace phongsim::fx {

// ---- Instruction sets. A batch kernel (a plan's loops over many vectors, or a native kernel)
// is compiled once per instruction set and runs the one kernel_isa() names: int64 multiplies,
// arithmetic shifts and min/max vectorize only with AVX-512 (x86-64-v4), so the baseline code
// runs the block loops one value at a time. docs/performance.md has the measured effect.
enum class Isa { baseline, avx2, avx512 };  // x86-64, x86-64-v3, x86-64-v4

[[nodiscard]] const char* isa_name(Isa isa);
// The instruction sets this CPU runs, baseline first (baseline only where the kernels are not
// compiled for more: other than GCC on x86-64).
[[nodiscard]] std::vector<Isa> supported_isas();
// What the kernels run: $PHONGSIM_ISA if set (baseline, avx2 or avx512; an unknown or
// unsupported name is an Error), else the widest supported.
[[nodiscard]] Isa kernel_isa();
// The kernels run `isa` from now on (tests run every supported one); unsupported: an Error.
void set_kernel_isa(Isa isa);

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PHONGSIM_ISA_CLONES 1
#include <immintrin.h>
#endif

namespace detail {
// flatten inlines what body() calls, compiled for the function's instruction set; but GCC
// inlines across instruction sets only functions declared inline (templates, lambdas, members
// defined in their class). A kernel's other helpers are [[gnu::always_inline]] inline (as
// LyonPlan::block is), or they would run baseline code.
#ifdef PHONGSIM_ISA_CLONES
template <class Body>
[[gnu::target("arch=x86-64-v4"), gnu::flatten]] void on_avx512(Body& body) {
  body();
}
template <class Body>
[[gnu::target("arch=x86-64-v3"), gnu::flatten]] void on_avx2(Body& body) {
  body();
}
#endif
template <class Body>
[[gnu::flatten]] void on_baseline(Body& body) {
  body();
}
}  // namespace detail

// Runs body() compiled for kernel_isa(). Call it from the file that defines the kernel's loops,
// so that they can be inlined.
template <class Body>
void on_kernel_isa(Body&& body) {
#ifdef PHONGSIM_ISA_CLONES
  switch (kernel_isa()) {
    case Isa::avx512:
      return detail::on_avx512(body);
    case Isa::avx2:
      return detail::on_avx2(body);
    case Isa::baseline:
      break;
  }
#endif
  detail::on_baseline(body);
}

// resize_raw(x, from, to, round, overflow) compiled: branch-free, the same result for every x
// in `from`'s range (tests/plan_test.cpp checks every value of many formats and modes). Valid
// only when fits_int64(): the aligned value plus the rounding bias must fit int64_t, which
// resize_raw's __int128 does not need; a plan with a step that does not fit is not used
// (its model keeps the stage path).
class Requant {
 public:
  Requant() = default;
  Requant(Format from, Format to, Round round, Overflow overflow) {
    const int d = from.frac_bits - to.frac_bits;
    lshift_ = std::max(-d, 0);
    rshift_ = std::max(d, 0);
    if (d > 0) {
      const std::int64_t half = std::int64_t{1} << (d - 1);
      bias_ = round == Round::truncate ? 0 : round == Round::half_up ? half : half - 1;
      odd_ = round == Round::half_even ? 1 : 0;
    }
    saturates_ = overflow == Overflow::saturate;
    if (saturates_) {
      lo_ = to.min_raw();
      hi_ = to.max_raw();
    } else {  // wrap: the low width bits, read in `to`'s signedness (fx::from_bits)
      mask_ = static_cast<std::int64_t>((std::uint64_t{1} << to.width()) - 1);
      sign_ = to.is_signed ? std::int64_t{1} << (to.width() - 1) : 0;
    }
    // |raw| < 2^(width - 1) (signed) or 2^width (unsigned), shifted left, plus a bias below
    // 2^(d - 1) and the odd bit: one bit to spare covers every case.
    fits_ = from.width() + lshift_ + (rshift_ > 0 ? 1 : 0) <= 62;
  }

  [[nodiscard]] bool fits_int64() const { return fits_; }
  // The step saturates: saturated() gives what operator() does, without the wrap.
  [[nodiscard]] bool saturates() const { return saturates_; }

  // Both the clamp and the wrap, each the identity in the other mode: no branch, so a loop of
  // requantizations vectorizes.
  [[nodiscard]] std::int64_t operator()(std::int64_t v) const {
    v = saturated(v);
    return ((v & mask_) ^ sign_) - sign_;
  }
  // Only where saturates(): a plan whose steps all saturate leaves out the wrap's identity
  // operations (three of ten).
  [[nodiscard]] std::int64_t saturated(std::int64_t v) const {
    v = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) << lshift_);
    v = (v + bias_ + ((v >> rshift_) & odd_)) >> rshift_;  // >>: arithmetic, floor
    return std::min(std::max(v, lo_), hi_);
  }

 private:
  int lshift_ = 0;
  int rshift_ = 0;
  std::int64_t bias_ = 0;
  std::int64_t odd_ = 0;  // half_even: add the kept LSB
  std::int64_t lo_ = std::numeric_limits<std::int64_t>::min();
  std::int64_t hi_ = std::numeric_limits<std::int64_t>::max();
  std::int64_t mask_ = -1;
  std::int64_t sign_ = 0;
  bool saturates_ = true;
  bool fits_ = true;
};

// A requantization that saturates (Requant::saturated): the steps of a plan that never wraps.
class Saturate {
 public:
  Saturate() = default;
  Saturate(Format from, Format to, Round round) : r_(from, to, round, Overflow::saturate) {}
  [[nodiscard]] bool fits_int64() const { return r_.fits_int64(); }
  [[nodiscard]] std::int64_t operator()(std::int64_t v) const { return r_.saturated(v); }

 private:
  Requant r_;
};

// Exact add and sub (fx::add, fx::sub): both operands shifted left to the result's binary point.
struct AddStep {
  Format r;
  int a = 0;  // left shift of the first operand
  int b = 0;  // ... of the second

  [[nodiscard]] static AddStep add(Format fa, Format fb) {
    return aligned(add_format(fa, fb), fa, fb);
  }
  [[nodiscard]] static AddStep sub(Format fa, Format fb) {
    return aligned(sub_format(fa, fb), fa, fb);
  }
  [[nodiscard]] std::int64_t sum(std::int64_t x, std::int64_t y) const {
    return (x << a) + (y << b);
  }
  [[nodiscard]] std::int64_t diff(std::int64_t x, std::int64_t y) const {
    return (x << a) - (y << b);
  }

 private:
  static AddStep aligned(Format r, Format fa, Format fb) {
    return {r, r.frac_bits - fa.frac_bits, r.frac_bits - fb.frac_bits};
  }
};

// fx::scale by 2^k: the raw value moves left only when the binary point passes the last
// fraction bit.
struct ScaleStep {
  Format r;
  int shift = 0;

  [[nodiscard]] static ScaleStep of(Format a, int k) {
    return {scale_format(a, k), std::max(k - a.frac_bits, 0)};
  }
  [[nodiscard]] std::int64_t operator()(std::int64_t x) const { return x << shift; }
};

// A value of format f is >= 1 (an unsigned value with a bit above the binary point): Lyon's
// zero comparator. `shift` = frac_bits, or 63 when f has no integer bits (never >= 1).
struct AtLeastOne {
  int shift = 63;
  [[nodiscard]] static AtLeastOne of(Format f) { return {f.int_bits > 0 ? f.frac_bits : 63}; }
  [[nodiscard]] bool operator()(std::int64_t raw) const { return (raw >> shift) != 0; }
};

// Transactions per block of a batch kernel.
inline constexpr std::size_t kBlock = 64;

// ---- Transposes between m <= kBlock transactions stored back to back (n raw fields each) and
// a block's structure of arrays soa[f][k]. On AVX-512 eight transactions at a time, by 8x8
// transposes in registers with masked loads and stores (the compiler's own code moves one
// value at a time; LIRP's plan runs about a third faster with these); the rest, and other
// instruction sets, one value at a time. Call them inside fx::on_kernel_isa.
#ifdef PHONGSIM_ISA_CLONES
namespace detail {
using Lanes8 = long long __attribute__((vector_size(64)));  // __m512i

// Rows r[0..7] to columns, in place.
[[gnu::target("arch=x86-64-v4"), gnu::always_inline]] inline void transpose8x8(Lanes8 (&r)[8]) {
  using Index = Lanes8;
  Lanes8 t[8], u[8];
  for (int p = 0; p < 8; p += 2) {  // t[p]: rows p, p+1 at even columns; t[p+1]: odd columns
    t[p] = __builtin_shuffle(r[p], r[p + 1], Index{0, 8, 2, 10, 4, 12, 6, 14});
    t[p + 1] = __builtin_shuffle(r[p], r[p + 1], Index{1, 9, 3, 11, 5, 13, 7, 15});
  }
  for (int q : {0, 1, 4, 5}) {  // u[q]: four rows' columns c and c + 4, c = q % 4 (and q + 2)
    u[q] = __builtin_shuffle(t[q], t[q + 2], Index{0, 1, 8, 9, 4, 5, 12, 13});
    u[q + 2] = __builtin_shuffle(t[q], t[q + 2], Index{2, 3, 10, 11, 6, 7, 14, 15});
  }
  for (int c = 0; c < 4; ++c) {
    r[c] = __builtin_shuffle(u[c], u[c + 4], Index{0, 1, 2, 3, 8, 9, 10, 11});
    r[c + 4] = __builtin_shuffle(u[c], u[c + 4], Index{4, 5, 6, 7, 12, 13, 14, 15});
  }
}

// The first `groups` eight transactions. Each group of up to eight fields moves through one 8x8
// transpose; the masks touch only a row's own fields, never past the transactions.
[[gnu::target("arch=x86-64-v4")]] inline void to_fields8(const std::int64_t* src, std::size_t n,
                                                         std::size_t groups,
                                                         std::int64_t (*soa)[kBlock]) {
  for (std::size_t i = 0; i < 8 * groups; i += 8) {
    for (std::size_t g = 0; g < n; g += 8) {
      const std::size_t k = std::min<std::size_t>(8, n - g);
      const auto mask = static_cast<__mmask8>((1U << k) - 1);
      Lanes8 r[8];
      for (std::size_t j = 0; j < 8; ++j) {
        r[j] = _mm512_maskz_loadu_epi64(mask, src + (i + j) * n + g);
      }
      transpose8x8(r);
      for (std::size_t c = 0; c < k; ++c) _mm512_storeu_si512(soa[g + c] + i, r[c]);
    }
  }
}

[[gnu::target("arch=x86-64-v4")]] inline void from_fields8(const std::int64_t (*soa)[kBlock],
                                                           std::size_t n, std::size_t groups,
                                                           std::int64_t* dst) {
  for (std::size_t i = 0; i < 8 * groups; i += 8) {
    for (std::size_t g = 0; g < n; g += 8) {
      const std::size_t k = std::min<std::size_t>(8, n - g);
      const auto mask = static_cast<__mmask8>((1U << k) - 1);
      Lanes8 r[8] = {};
      for (std::size_t c = 0; c < k; ++c) r[c] = _mm512_loadu_si512(soa[g + c] + i);
      transpose8x8(r);
      for (std::size_t j = 0; j < 8; ++j) {
        _mm512_mask_storeu_epi64(dst + (i + j) * n + g, mask, r[j]);
      }
    }
  }
}
}  // namespace detail
#endif

// soa[f][k] = src[k * n + f] for k < m, f < n.
inline void to_fields(const std::int64_t* src, std::size_t n, std::size_t m,
                      std::int64_t (*soa)[kBlock]) {
  std::size_t k = 0;
#ifdef PHONGSIM_ISA_CLONES
  if (kernel_isa() == Isa::avx512) {
    detail::to_fields8(src, n, m / 8, soa);
    k = m / 8 * 8;
  }
#endif
  for (; k < m; ++k) {
    for (std::size_t f = 0; f < n; ++f) soa[f][k] = src[k * n + f];
  }
}

// dst[k * n + f] = soa[f][k] for k < m, f < n.
inline void from_fields(const std::int64_t (*soa)[kBlock], std::size_t n, std::size_t m,
                        std::int64_t* dst) {
  std::size_t k = 0;
#ifdef PHONGSIM_ISA_CLONES
  if (kernel_isa() == Isa::avx512) {
    detail::from_fields8(soa, n, m / 8, dst);
    k = m / 8 * 8;
  }
#endif
  for (; k < m; ++k) {
    for (std::size_t f = 0; f < n; ++f) dst[k * n + f] = soa[f][k];
  }
}

// Runs a structure-of-arrays kernel over n transactions stored back to back (NIn raw inputs
// each), writing NOut outputs each to `out`: blocks of kBlock transactions are transposed in,
// computed by kernel(in_fields, out_fields, count) and transposed out.
template <std::size_t NIn, std::size_t NOut, class Kernel>
void for_each_block(const std::int64_t* in, std::int64_t* out, std::size_t n, Kernel&& kernel) {
  alignas(64) std::int64_t soa_in[NIn][kBlock];
  alignas(64) std::int64_t soa_out[NOut][kBlock];
  const std::int64_t* in_fields[NIn];
  std::int64_t* out_fields[NOut];
  for (std::size_t f = 0; f < NIn; ++f) in_fields[f] = soa_in[f];
  for (std::size_t f = 0; f < NOut; ++f) out_fields[f] = soa_out[f];
  for (std::size_t base = 0; base < n; base += kBlock) {
    const std::size_t m = std::min(kBlock, n - base);
    to_fields(in + base * NIn, NIn, m, soa_in);
    kernel(in_fields, out_fields, m);
    from_fields(soa_out, NOut, m, out + base * NOut);
  }
}

}  // namespace phongsim::fx
