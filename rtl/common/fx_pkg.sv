// Fixed-point formats and modes shared by every phongsim datapath.
//
// Same semantics and encodings as model/fixed.h (specification: docs/fixed-point.md).
// A format is packed into one int unsigned "format word" so a module takes one parameter per
// signal: signed * 2^16 + integer bits * 2^8 + fraction bits (each count below 256). The fields
// are read arithmetically rather than by bit slices so lint sees every bit used. Lyon's notation:
// "n.m" is unsigned with n integer and m fraction bits, "Sn.m" is signed with 1 + n + m bits.
// Written in the SystemVerilog subset Yosys 0.23 reads (Debian 12): no `return`, no package
// imports; modules refer to fx_pkg:: names explicitly.
package fx_pkg;

  // Not every user of the package needs every constant.
  /* verilator lint_off UNUSEDPARAM */

  // Rounding when fraction bits are dropped (phongsim::fx::Round).
  localparam bit [31:0] FxTruncate = 0;  // floor
  localparam bit [31:0] FxHalfUp   = 1;  // nearest, ties toward +infinity
  localparam bit [31:0] FxHalfEven = 2;  // nearest, ties to even (convergent)

  // Overflow handling (phongsim::fx::Overflow).
  localparam bit [31:0] FxWrap     = 0;  // keep the low bits
  localparam bit [31:0] FxSaturate = 1;  // clamp to the format's range
  /* verilator lint_on UNUSEDPARAM */

  function automatic int unsigned fx_fmt(bit is_signed, int unsigned int_bits,
                                         int unsigned frac_bits);
    fx_fmt = (is_signed ? 32'd65536 : 32'd0) + int_bits * 256 + frac_bits;
  endfunction

  function automatic bit fx_signed(int unsigned fmt);
    fx_signed = (fmt / 65536) % 2 == 1;
  endfunction

  function automatic int unsigned fx_int(int unsigned fmt);
    fx_int = (fmt / 256) % 256;
  endfunction

  function automatic int unsigned fx_frac(int unsigned fmt);
    fx_frac = fmt % 256;
  endfunction

  function automatic int unsigned fx_width(int unsigned fmt);
    fx_width = (fx_signed(fmt) ? 1 : 0) + fx_int(fmt) + fx_frac(fmt);
  endfunction

  function automatic int unsigned fx_max(int unsigned a, int unsigned b);
    fx_max = a > b ? a : b;
  endfunction

  // Exact width growth, identical to add_format / sub_format / mul_format / neg_format /
  // abs_format.
  function automatic int unsigned fx_add_fmt(int unsigned a, int unsigned b);
    fx_add_fmt = fx_fmt(fx_signed(a) | fx_signed(b), fx_max(fx_int(a), fx_int(b)) + 1,
                  fx_max(fx_frac(a), fx_frac(b)));
  endfunction

  function automatic int unsigned fx_sub_fmt(int unsigned a, int unsigned b);
    fx_sub_fmt = fx_fmt(1'b1, fx_max(fx_int(a), fx_int(b)) + 1, fx_max(fx_frac(a), fx_frac(b)));
  endfunction

  function automatic int unsigned fx_mul_fmt(int unsigned a, int unsigned b);
    fx_mul_fmt = fx_fmt(fx_signed(a) | fx_signed(b),
                  fx_int(a) + fx_int(b) + (fx_signed(a) && fx_signed(b) ? 1 : 0),
                  fx_frac(a) + fx_frac(b));
  endfunction

  function automatic int unsigned fx_abs_fmt(int unsigned a);
    fx_abs_fmt = fx_fmt(1'b0, fx_int(a) + (fx_signed(a) ? 1 : 0), fx_frac(a));
  endfunction

  // Scale by 2^k: the binary point moves by k, the bits stay (model: fx::scale_format).
  function automatic int unsigned fx_scale_fmt(int unsigned a, int k);
    if (k >= 0) begin
      fx_scale_fmt = fx_fmt(fx_signed(a), fx_int(a) + k,
                            fx_frac(a) > k ? fx_frac(a) - k : 0);
    end else begin
      fx_scale_fmt = fx_fmt(fx_signed(a), fx_int(a) > -k ? fx_int(a) + k : 0, fx_frac(a) - k);
    end
  endfunction

  function automatic int unsigned fx_neg_fmt(int unsigned a);
    fx_neg_fmt = fx_fmt(1'b1, fx_int(a) + (fx_signed(a) ? 1 : 0), fx_frac(a));
  endfunction

endpackage
