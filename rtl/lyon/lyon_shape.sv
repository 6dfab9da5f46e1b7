// lyon_shape: Lyon's shape function f_K(x) = (1 - x/2^K)^(2^K), forced to 0 when x/2^K >= 1
// (TR #43, "Phong Specularity Reformulation" and Fig. 7d): one subtraction and K cascaded
// squarers. The input is already x/2^K, split into its fraction xf and the flag zero
// (x/2^K >= 1). Register stages under the caller's pipe_ctrl:
//   stage t    (en_i[0]):  t = resize(1 - xf, SqFmt)            (exact when SqFmt has xf's bits)
//   stage sq_j (en_i[j]):  sq_j = resize(sq_(j-1)², SqFmt)      j = 1..K, sq_0 = t
//   output (comb):         spec = zero ? 0 : resize(sq_K, SpecFmt)
// Every resize rounds with Round and saturates. Specification: docs/lyon.md.
//
// Parameters: K - squarings (0..3); XfFmt, SqFmt, SpecFmt - format words (unsigned);
//             Round - fx_pkg rounding mode.
// Ports: clk_i; en_i - load enables of stages t, sq_1..sq_K; xf_i, zero_i - input;
//        spec_o - result of the transaction in the last stage.
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

  localparam int unsigned OneFmt   = fx_pkg::fx_fmt(1'b0, 1, 0);
  localparam int unsigned TFmt     = fx_pkg::fx_sub_fmt(OneFmt, XfFmt);
  localparam int unsigned SqW      = fx_pkg::fx_width(SqFmt);
  localparam int unsigned SqSqFmt  = fx_pkg::fx_mul_fmt(SqFmt, SqFmt);

  // sq_q[j*SqW +: SqW] is stage j's value (j = 0: t); zero_q[j] its flag.
  logic [(K+1)*SqW-1:0] sq_d, sq_q;
  logic [          K:0] zero_q;

  // Stage t.
  logic [fx_pkg::fx_width(TFmt)-1:0] t_exact;
  fx_sub #(.AFmt(OneFmt), .BFmt(XfFmt)) u_t (
    .a_i   (1'b1),
    .b_i   (xf_i),
    .diff_o(t_exact)
  );
  fx_resize #(
    .InFmt   (TFmt),
    .OutFmt  (SqFmt),
    .Round   (Round),
    .Overflow(fx_pkg::FxSaturate)
  ) u_t_round (
    .in_i (t_exact),
    .out_o(sq_d[0+:SqW])
  );

  // Stages sq_1 .. sq_K.
  for (genvar j = 1; j <= K; j++) begin : g_square
    logic [fx_pkg::fx_width(SqSqFmt)-1:0] square;
    fx_mul #(.AFmt(SqFmt), .BFmt(SqFmt)) u_square (
      .a_i   (sq_q[(j-1)*SqW+:SqW]),
      .b_i   (sq_q[(j-1)*SqW+:SqW]),
      .prod_o(square)
    );
    fx_resize #(
      .InFmt   (SqSqFmt),
      .OutFmt  (SqFmt),
      .Round   (Round),
      .Overflow(fx_pkg::FxSaturate)
    ) u_square_round (
      .in_i (square),
      .out_o(sq_d[j*SqW+:SqW])
    );
  end

  for (genvar j = 0; j <= K; j++) begin : g_stage
    always_ff @(posedge clk_i) begin
      if (en_i[j]) begin
        sq_q[j*SqW+:SqW] <= sq_d[j*SqW+:SqW];
        zero_q[j]        <= j == 0 ? zero_i : zero_q[j == 0 ? 0 : j-1];
      end
    end
  end

  // Output: the comparator's multiplexer.
  logic [SpecW-1:0] spec;
  fx_resize #(
    .InFmt   (SqFmt),
    .OutFmt  (SpecFmt),
    .Round   (Round),
    .Overflow(fx_pkg::FxSaturate)
  ) u_spec (
    .in_i (sq_q[K*SqW+:SqW]),
    .out_o(spec)
  );
  assign spec_o = zero_q[K] ? '0 : spec;

endmodule
