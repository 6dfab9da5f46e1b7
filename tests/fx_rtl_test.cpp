// Exhaustive co-simulation of the SystemVerilog fixed-point helpers (rtl/common/fx_*.sv) against
// the model's core (model/fixed.h): every case of tests/gen_fx_cosim.py, every input value
// (every operand pair for add/sub/mul, every pair of vectors for dot3), every rounding and
// overflow mode listed there.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "Vfx_cosim_top.h"
#include "fx_cosim_cases.h"
#include "model/fixed.h"
#include "verilated.h"

namespace phongsim::fx {
namespace {

// The model's answer for `c` with the 16 bits of a_i as the RTL sees them.
Fixed expected(const FxCosimCase& c, std::uint64_t a_bits) {
  const std::string_view op = c.op;
  const Format fa = Format::parse(c.a);
  const Fixed a{from_bits(a_bits, fa), fa};
  if (op == "resize" || op == "rq") {  // rq: the generator always passes "saturate"
    return resize(a, Format::parse(c.b), parse_round(c.round), parse_overflow(c.overflow));
  }
  if (op == "dot3") {  // b is "<b format>:<output format>"; a's components, then b's, from the LSB
    const std::string_view spec = c.b;
    const std::size_t colon = spec.find(':');
    const Format fb = Format::parse(spec.substr(0, colon));
    const Format fo = Format::parse(spec.substr(colon + 1));
    const int wa = fa.width();
    const int wb = fb.width();
    const auto comp = [&](int shift, Format f) { return Fixed{from_bits(a_bits >> shift, f), f}; };
    Fixed sum = mul(comp(0, fa), comp(3 * wa, fb));
    sum = add(sum, mul(comp(wa, fa), comp(3 * wa + wb, fb)));
    sum = add(sum, mul(comp(2 * wa, fa), comp(3 * wa + 2 * wb, fb)));
    return resize(sum, fo, parse_round(c.round), parse_overflow(c.overflow));
  }
  if (op == "neg") return neg(a);
  if (op == "abs") return abs(a);
  if (op == "scale") return scale(a, std::stoi(c.b));
  if (op == "clamp01") return Fixed{clamp01_raw(a.raw, fa), fa};
  const Format fb = Format::parse(c.b);
  const Fixed b{from_bits(a_bits >> 8, fb), fb};
  if (op == "add") return add(a, b);
  if (op == "sub") return sub(a, b);
  return mul(a, b);
}

TEST(FxRtl, EveryCaseEveryInputMatchesTheModel) {
  VerilatedContext context;
  Vfx_cosim_top top(&context);
  constexpr std::size_t kCases = std::size(kFxCosimCases);
  std::size_t checked = 0;
  for (std::uint64_t a = 0; a < (1U << 16); ++a) {
    top.a_i = static_cast<std::uint16_t>(a);
    top.eval();
    for (std::size_t i = 0; i < kCases; ++i) {
      const FxCosimCase& c = kFxCosimCases[i];
      const Fixed want = expected(c, a);
      const std::uint32_t slot = top.out_o[i];
      // The slot holds the RTL result zero-extended: nothing may be set above the model's
      // result width (that would mean the RTL grew the width differently).
      const std::uint64_t got_bits = slot;
      ASSERT_EQ(got_bits >> want.fmt.width(), 0U)
          << "slot " << i << " " << c.op << " " << c.a << " " << c.b << ": RTL result is wider "
          << "than the model's " << want.fmt.str() << ", a_i=" << a;
      ASSERT_EQ(from_bits(got_bits, want.fmt), want.raw)
          << "slot " << i << ": " << c.op << " " << c.a << " " << c.b << " " << c.round << " "
          << c.overflow << ", a_i=0x" << std::hex << a << " (result format " << want.fmt.str()
          << ")";
      ++checked;
    }
  }
  EXPECT_EQ(checked, kCases << 16);
}

}  // namespace
}  // namespace phongsim::fx
