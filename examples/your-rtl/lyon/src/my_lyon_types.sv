// my_lyon_types - constants and the requantizer of the my_lyon specular unit.
// A package in a file of its own name (not *_pkg.sv); lists/files.f lists it after its users.
//
// rq() is the only place my_lyon drops information (docs/fixed-point.md, "Requantization"):
// align the binary point (dropping bits with the rounding mode), then saturate to the target
// format. It works on one fixed-width exact word (`MY_LYON_EXACT_W bits); the callers sign-extend
// their exact values into it and keep the low bits of the result.
`include "my_lyon_defs.svh"
package my_lyon_types;

  /* verilator lint_off UNUSEDPARAM */
  // Round parameter encodings (phongsim's [mode] round).
  localparam bit [31:0] RoundTruncate = 0;  // floor
  localparam bit [31:0] RoundHalfUp   = 1;  // nearest, ties toward +inf
  localparam bit [31:0] RoundHalfEven = 2;  // nearest, ties to even

  // The structure this unit implements (phongsim's [param] keys).
  localparam bit [31:0] ArrangementNDD = 7;  // Fig. 7: x = (n/2) D.D
  localparam bit [31:0] NormNone       = 0;
  localparam bit [31:0] NormG1         = 1;  // g = 1 + y/2
  localparam bit [31:0] NormG2         = 2;  // g = 1 + (y + y^2)/2
  /* verilator lint_on UNUSEDPARAM */

  localparam int ExactW = `MY_LYON_EXACT_W;

  // Round exact value x (x_frac fraction bits) to format word fmt, then saturate.
  //   guard  = first dropped bit (worth half an output LSB)
  //   sticky = any dropped bit below the guard bit
  //   half up:   +1 when guard
  //   half even: +1 when guard and (sticky or the kept LSB is odd)
  function automatic logic signed [ExactW-1:0] rq(input logic signed [ExactW-1:0] x,
                                                  input int x_frac, input bit [31:0] fmt,
                                                  input bit [31:0] mode);
    logic signed [ExactW-1:0] q, mask, lo, hi;
    logic guard, sticky;
    int drop, width;
    drop  = x_frac - `MY_LYON_FMT_F(fmt);
    width = `MY_LYON_FMT_W(fmt);
    if (drop <= 0) begin
      q = x <<< (-drop);
    end else begin
      q      = x >>> drop;
      guard  = ((x >>> (drop - 1)) & ExactW'(1)) != '0;
      mask   = (ExactW'(1) <<< (drop - 1)) - ExactW'(1);
      sticky = (x & mask) != '0;
      if (mode == RoundHalfUp) begin
        if (guard) q = q + ExactW'(1);
      end else if (mode == RoundHalfEven) begin
        if (guard && (sticky || q[0])) q = q + ExactW'(1);
      end
    end
    if (`MY_LYON_FMT_S(fmt) != 0) begin
      hi = (ExactW'(1) <<< (width - 1)) - ExactW'(1);
      lo = -(ExactW'(1) <<< (width - 1));
    end else begin
      hi = (ExactW'(1) <<< width) - ExactW'(1);
      lo = '0;
    end
    if (q > hi) q = hi;
    if (q < lo) q = lo;
    rq = q;
  endfunction

endpackage
