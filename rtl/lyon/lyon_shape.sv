// lyon_shape: Lyon's shape function f_K(x) = (1 - x/2^K)^(2^K), forced to 0 when x/2^K >= 1
// (TR #43, "Phong Specularity Reformulation" and Fig. 7d): one subtraction and K cascaded
// squarers. The input is already x/2^K, split into its fraction xf and the flag zero
// (x/2^K >= 1). Register stages under the caller's pipe_ctrl (rq = fx_rq: round with Round,
// saturate):
//   stage sq_0 (en_i[0]):  sq_0 = rq(1 - xf, SqFmt)            (exact when SqFmt has xf's bits)
//   stage sq_j (en_i[j]):  sq_j = rq(sq_(j-1)², SqFmt)         j = 1..K
//   output (comb):         spec = zero ? 0 : rq(sq_K, SpecFmt)
// Specification: docs/lyon.md, stages 11..11+K.
//
// Latency K + 1 register stages (in step with en_i); throughput 1 per clock.
// Parameters:
//   K       - squarings (0..3)
//   XfFmt   - format word of xf (unsigned)
//   SqFmt   - format word of sq_0 .. sq_K (unsigned)
//   SpecFmt - format word of spec (unsigned)
//   Round   - fx_pkg rounding mode of every rq
// Ports:
//   clk_i   - clock (data registers only, no reset)
//   en_i    - load enables of stages sq_0 .. sq_K
//   xf_i    - x/2^K requantized (its fraction)
//   zero_i  - x/2^K >= 1: the output is 0
//   spec_o  - f_K of the transaction in stage sq_K
//
// Assertions: none (K is checked by lyon_top).
module lyon_shape #(
  parameter int unsigned K       = 2,
  parameter int unsigned XfFmt   = fx_pkg::fx_fmt(1'b0, 0, 16),
  parameter int unsigned SqFmt   = fx_pkg::fx_fmt(1'b0, 1, 16),
  parameter int unsigned SpecFmt = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter int unsigned Round   = fx_pkg::FxHalfEven,
  // Derived, do not override.
  localparam int unsigned XfW    = fx_pkg::fx_width(XfFmt),
  localparam int unsigned SpecW  = fx_pkg::fx_width(SpecFmt)
) (
  input  logic             clk_i,
  input  logic [      K:0] en_i,
  input  logic [  XfW-1:0] xf_i,
  input  logic             zero_i,
  output logic [SpecW-1:0] spec_o
);

  localparam int unsigned OneFmt        = fx_pkg::fx_fmt(1'b0, 1, 0);
  localparam int unsigned OneMinusXfFmt = fx_pkg::fx_sub_fmt(OneFmt, XfFmt);
  localparam int unsigned SqW           = fx_pkg::fx_width(SqFmt);
  localparam int unsigned SqSqFmt       = fx_pkg::fx_mul_fmt(SqFmt, SqFmt);

  // sq_q[j*SqW +: SqW] is stage sq_j's value; zero_q[j] its flag.
  logic [(K+1)*SqW-1:0] sq_d, sq_q;
  logic [          K:0] zero_q;

  // Stage sq_0 = rq(1 - xf, SqFmt).
  logic [fx_pkg::fx_width(OneMinusXfFmt)-1:0] one_minus_xf;
  fx_sub #(.AFmt(OneFmt), .BFmt(XfFmt))
      u_one_minus_xf (.a_i(1'b1), .b_i(xf_i), .delta_o(one_minus_xf));
  fx_rq #(.InFmt(OneMinusXfFmt), .OutFmt(SqFmt), .Round(Round))
      u_sq_0 (.in_i(one_minus_xf), .out_o(sq_d[0+:SqW]));

  // Stages sq_j = rq(sq_(j-1)², SqFmt), j = 1..K.
  for (genvar j = 1; j <= K; j++) begin : g_square
    logic [fx_pkg::fx_width(SqSqFmt)-1:0] square;
    fx_mul #(.AFmt(SqFmt), .BFmt(SqFmt))
        u_square (.a_i(sq_q[(j-1)*SqW+:SqW]), .b_i(sq_q[(j-1)*SqW+:SqW]), .prod_o(square));
    fx_rq #(.InFmt(SqSqFmt), .OutFmt(SqFmt), .Round(Round))
        u_sq_j (.in_i(square), .out_o(sq_d[j*SqW+:SqW]));
  end

  for (genvar j = 0; j <= K; j++) begin : g_stage
    always_ff @(posedge clk_i) begin
      if (en_i[j]) begin
        sq_q[j*SqW+:SqW] <= sq_d[j*SqW+:SqW];
        zero_q[j]        <= j == 0 ? zero_i : zero_q[j == 0 ? 0 : j-1];
      end
    end
  end

  // Output: spec = zero ? 0 : rq(sq_K, SpecFmt), the comparator's multiplexer.
  logic [SpecW-1:0] spec;
  fx_rq #(.InFmt(SqFmt), .OutFmt(SpecFmt), .Round(Round))
      u_spec (.in_i(sq_q[K*SqW+:SqW]), .out_o(spec));
  assign spec_o = zero_q[K] ? '0 : spec;

endmodule
