// lyon_x: from the difference vector D and the shininess to the shape function's input x/2^K
// (Lyon, TR #43: x = (n/2)·D·D; Fig. 7c and the root-shininess arrangement of Fig. 8), as its
// fraction xf and the flag zero (x/2^K >= 1). Two register stages under the caller's pipe_ctrl
// (rq = fx_rq: round with Round, saturate; everything else exact):
//
// Arrangement 7 (shininess n):
//   stage 9  (en_i[0]):  dd = rq(D·D, DdFmt)
//   stage 10 (en_i[1]):  x2 = n·dd (×4 for the halfway variant: n -> 4n);  xk = x2·2^-(K+1)
//                        zero = xk >= 1;  xf = rq(xk, XfFmt)
// Arrangement 8 (shininess m = sqrt(n)), with s = ceil((K+1)/2), e = 2s - (K+1) in {0, 1}:
//   stage 9  (en_i[0]):  dabs_c = rq(|D_c|, DabsFmt);  u_c = m·dabs_c·2^-s (×2 halfway: m -> 2m)
//                        big = any u_c >= 1;  w_c = rq(u_c, WFmt)  (fraction bits only)
//   stage 10 (en_i[1]):  xk = 2^e·Σ w_c²  (= x/2^K, since (m|D|)² = 2x)
//                        zero = big or xk >= 1;  xf = rq(xk, XfFmt)
// For odd K the shift s is Lyon's; for even K the √2 he notes is absorbed by shifting one bit
// further before squaring (e = 1) and doubling after, so the squarers still see only fraction
// bits. Specification: docs/lyon.md, stages 9-10.
//
// Latency 2 register stages (in step with en_i); throughput 1 per clock.
// Parameters:
//   Arrangement - 7 or 8
//   Halfway     - 1 for the halfway-vector variant (n -> 4n, m -> 2m)
//   K           - shape function order, 0..3
//   DFmt        - format word of D's components
//   ShinFmt     - format word of the shininess (n or m, unsigned)
//   DdFmt       - format word of dd = D·D (arrangement 7)
//   DabsFmt     - format word of dabs = |D_c| (arrangement 8)
//   WFmt        - format word of the squarer inputs w (arrangement 8)
//   XfFmt       - format word of xf
//   Round       - fx_pkg rounding mode of every rq
// Ports:
//   clk_i       - clock (data registers only, no reset)
//   en_i        - load enables of stages 9 and 10
//   d_i         - D, x, y, z packed from the LSB
//   shin_i      - n or m, of the transaction entering stage 9
//   xf_o        - xf of the transaction in stage 10
//   zero_o      - its flag x/2^K >= 1
//
// Assertions: none (Arrangement and K are checked by lyon_top).
module lyon_x #(
  parameter int unsigned Arrangement = 7,
  parameter int unsigned Halfway     = 0,
  parameter int unsigned K           = 2,
  parameter int unsigned DFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned ShinFmt     = fx_pkg::fx_fmt(1'b0, 13, 0),
  parameter int unsigned DdFmt       = fx_pkg::fx_fmt(1'b0, 3, 19),
  parameter int unsigned DabsFmt     = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter int unsigned WFmt        = fx_pkg::fx_fmt(1'b0, 0, 9),
  parameter int unsigned XfFmt       = fx_pkg::fx_fmt(1'b0, 0, 16),
  parameter int unsigned Round       = fx_pkg::FxHalfEven,
  // Derived, do not override.
  localparam int unsigned DW         = fx_pkg::fx_width(DFmt),
  localparam int unsigned ShinW      = fx_pkg::fx_width(ShinFmt),
  localparam int unsigned XfW        = fx_pkg::fx_width(XfFmt)
) (
  input  logic             clk_i,
  input  logic [      1:0] en_i,
  input  logic [ 3*DW-1:0] d_i,
  input  logic [ShinW-1:0] shin_i,
  output logic [  XfW-1:0] xf_o,
  output logic             zero_o
);

  logic [XfW-1:0] xf_d, xf_q;
  logic           zero_d, zero_q;
  assign xf_o   = xf_q;
  assign zero_o = zero_q;
  always_ff @(posedge clk_i) begin
    if (en_i[1]) begin
      xf_q   <= xf_d;
      zero_q <= zero_d;
    end
  end

  if (Arrangement == 7) begin : g_fig7
    localparam int          KSigned  = K;
    localparam int          XkShift  = -(KSigned + 1);
    localparam int unsigned DdW      = fx_pkg::fx_width(DdFmt);
    // Exact intermediates.
    localparam int unsigned X2Fmt    = fx_pkg::fx_mul_fmt(ShinFmt, DdFmt);
    localparam int unsigned X2hFmt   = fx_pkg::fx_scale_fmt(X2Fmt, Halfway != 0 ? 2 : 0);
    localparam int unsigned XkFmt    = fx_pkg::fx_scale_fmt(X2hFmt, XkShift);
    localparam int unsigned XkW      = fx_pkg::fx_width(XkFmt);
    localparam int unsigned XkFrac   = fx_pkg::fx_frac(XkFmt);

    // Stage 9: dd = rq(D·D, dd).
    logic [DdW-1:0]   dd_d, dd_q;
    logic [ShinW-1:0] shin_q;
    fx_dot3 #(.AFmt(DFmt), .BFmt(DFmt), .OutFmt(DdFmt), .Round(Round))
        u_dd (.a_i(d_i), .b_i(d_i), .dot_o(dd_d));
    always_ff @(posedge clk_i) begin
      if (en_i[0]) begin
        dd_q   <= dd_d;
        shin_q <= shin_i;
      end
    end

    // Stage 10: xk = n·dd·2^-(K+1) (·4 halfway), exact; zero = xk >= 1; xf = rq(xk, xf).
    logic [fx_pkg::fx_width(X2Fmt)-1:0]  x2;
    logic [fx_pkg::fx_width(X2hFmt)-1:0] x2h;
    logic [XkW-1:0]                      xk;
    fx_mul #(.AFmt(ShinFmt), .BFmt(DdFmt)) u_x2 (.a_i(shin_q), .b_i(dd_q), .prod_o(x2));
    fx_scale #(.AFmt(X2Fmt), .Shift(Halfway != 0 ? 2 : 0)) u_x2h (.a_i(x2), .scaled_o(x2h));
    fx_scale #(.AFmt(X2hFmt), .Shift(XkShift)) u_xk (.a_i(x2h), .scaled_o(xk));
    if (XkW > XkFrac) begin : g_can_reach_one
      assign zero_d = |xk[XkW-1:XkFrac];
    end else begin : g_below_one
      assign zero_d = 1'b0;
    end
    fx_rq #(.InFmt(XkFmt), .OutFmt(XfFmt), .Round(Round)) u_xf (.in_i(xk), .out_o(xf_d));
  end else begin : g_fig8
    localparam int unsigned S         = (K + 2) / 2;  // ceil((K+1)/2)
    localparam int unsigned E         = 2 * S - (K + 1);
    localparam int          SSigned   = S;
    localparam int          ESigned   = E;
    localparam int          UShift    = (Halfway != 0 ? 1 : 0) - SSigned;
    localparam int unsigned DabsW     = fx_pkg::fx_width(DabsFmt);
    localparam int unsigned WW        = fx_pkg::fx_width(WFmt);
    // Exact intermediates.
    localparam int unsigned AbsDFmt   = fx_pkg::fx_abs_fmt(DFmt);
    localparam int unsigned MdFmt     = fx_pkg::fx_mul_fmt(ShinFmt, DabsFmt);
    localparam int unsigned UFmt      = fx_pkg::fx_scale_fmt(MdFmt, UShift);
    localparam int unsigned UW        = fx_pkg::fx_width(UFmt);
    localparam int unsigned UFrac     = fx_pkg::fx_frac(UFmt);
    localparam int unsigned WSqFmt    = fx_pkg::fx_mul_fmt(WFmt, WFmt);
    localparam int unsigned WSqW      = fx_pkg::fx_width(WSqFmt);
    localparam int unsigned Sum2Fmt   = fx_pkg::fx_add_fmt(WSqFmt, WSqFmt);
    localparam int unsigned Sum3Fmt   = fx_pkg::fx_add_fmt(Sum2Fmt, WSqFmt);
    localparam int unsigned XkFmt     = fx_pkg::fx_scale_fmt(Sum3Fmt, ESigned);
    localparam int unsigned XkW       = fx_pkg::fx_width(XkFmt);
    localparam int unsigned XkFrac    = fx_pkg::fx_frac(XkFmt);

    // Stage 9: dabs_c = rq(|D_c|, dabs); u_c = m·dabs_c·2^-s (·2 halfway), exact;
    // big = any u_c >= 1; w_c = rq(u_c, w).
    logic [3*WW-1:0] w_d, w_q;
    logic [     2:0] big_d;
    logic            big_q;
    for (genvar c = 0; c < 3; c++) begin : g_comp
      logic [fx_pkg::fx_width(AbsDFmt)-1:0] abs_d;
      logic [DabsW-1:0]                     dabs;
      logic [fx_pkg::fx_width(MdFmt)-1:0]   md;
      logic [UW-1:0]                        u;
      fx_abs #(.AFmt(DFmt)) u_abs_d (.a_i(d_i[c*DW+:DW]), .abs_o(abs_d));
      fx_rq #(.InFmt(AbsDFmt), .OutFmt(DabsFmt), .Round(Round)) u_dabs (.in_i(abs_d), .out_o(dabs));
      fx_mul #(.AFmt(ShinFmt), .BFmt(DabsFmt)) u_md (.a_i(shin_i), .b_i(dabs), .prod_o(md));
      fx_scale #(.AFmt(MdFmt), .Shift(UShift)) u_u (.a_i(md), .scaled_o(u));
      if (UW > UFrac) begin : g_can_reach_one
        assign big_d[c] = |u[UW-1:UFrac];
      end else begin : g_below_one
        assign big_d[c] = 1'b0;
      end
      fx_rq #(.InFmt(UFmt), .OutFmt(WFmt), .Round(Round)) u_w (.in_i(u), .out_o(w_d[c*WW+:WW]));
    end
    always_ff @(posedge clk_i) begin
      if (en_i[0]) begin
        w_q   <= w_d;
        big_q <= |big_d;
      end
    end

    // Stage 10: xk = 2^e·Σ w_c², exact; zero = big or xk >= 1; xf = rq(xk, xf).
    logic [3*WSqW-1:0]                    w_sq;
    logic [fx_pkg::fx_width(Sum2Fmt)-1:0] sum2;
    logic [fx_pkg::fx_width(Sum3Fmt)-1:0] sum3;
    logic [XkW-1:0]                       xk;
    for (genvar c = 0; c < 3; c++) begin : g_square
      fx_mul #(.AFmt(WFmt), .BFmt(WFmt))
          u_w_sq (.a_i(w_q[c*WW+:WW]), .b_i(w_q[c*WW+:WW]), .prod_o(w_sq[c*WSqW+:WSqW]));
    end
    fx_add #(.AFmt(WSqFmt), .BFmt(WSqFmt))
        u_sum2 (.a_i(w_sq[0+:WSqW]), .b_i(w_sq[WSqW+:WSqW]), .sum_o(sum2));
    fx_add #(.AFmt(Sum2Fmt), .BFmt(WSqFmt))
        u_sum3 (.a_i(sum2), .b_i(w_sq[2*WSqW+:WSqW]), .sum_o(sum3));
    fx_scale #(.AFmt(Sum3Fmt), .Shift(ESigned)) u_xk (.a_i(sum3), .scaled_o(xk));
    logic ge_one;
    if (XkW > XkFrac) begin : g_can_reach_one
      assign ge_one = |xk[XkW-1:XkFrac];
    end else begin : g_below_one
      assign ge_one = 1'b0;
    end
    assign zero_d = big_q | ge_one;
    fx_rq #(.InFmt(XkFmt), .OutFmt(XfFmt), .Round(Round)) u_xf (.in_i(xk), .out_o(xf_d));
  end

endmodule
