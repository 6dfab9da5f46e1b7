// lyon_norm: approximate normalization of a 3-vector (Lyon, TR #43, "Approximate
// Normalization", Fig. 7a): out = g(z)·in with z = in·in, y = 1 - z and
//   Order 0: g = 1 (the vector is only requantized),
//   Order 1: g1 = 1 + y/2,
//   Order 2: g2 = 1 + (y + y²)/2 (Lyon's over-corrected second order).
// Three register stages under the caller's pipe_ctrl (rq = fx_rq: round with Round, saturate):
//   stage z   (en_i[0]):  z = rq(in·in, ZFmt)
//   stage g   (en_i[1]):  y = rq(1 - z, YFmt);  g = rq(g_Order(y), GFmt)
//   stage out (en_i[2]):  out_c = rq(g·in_c, OutFmt)      (Order 0: rq(in_c, OutFmt))
// Specification: docs/lyon.md, stages 3-5.
//
// Latency 3 register stages (in step with en_i); throughput 1 per clock.
// Parameters:
//   InFmt, OutFmt - component format words of vec_i and vec_o
//   ZFmt, YFmt, GFmt - format words of z, y and g
//   Order         - 0, 1 or 2
//   Round         - fx_pkg rounding mode of every rq
// Ports:
//   clk_i         - clock (data registers only, no reset)
//   en_i          - load enables of stages z, g, out
//   vec_i         - input vector, x, y, z packed from the LSB
//   vec_o         - the normalized vector held by stage out
//
// Assertions: Order is checked at elaboration.
module lyon_norm #(
  parameter int unsigned InFmt  = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned OutFmt = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned ZFmt   = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter int unsigned YFmt   = fx_pkg::fx_fmt(1'b1, 0, 12),
  parameter int unsigned GFmt   = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter int unsigned Order  = 2,
  parameter int unsigned Round  = fx_pkg::FxHalfEven,
  // Derived, do not override.
  localparam int unsigned InW   = fx_pkg::fx_width(InFmt),
  localparam int unsigned OutW  = fx_pkg::fx_width(OutFmt)
) (
  input  logic              clk_i,
  input  logic [       2:0] en_i,
  input  logic [ 3*InW-1:0] vec_i,
  output logic [3*OutW-1:0] vec_o
);

  localparam int unsigned GW = fx_pkg::fx_width(GFmt);

  logic [3*InW-1:0]  vec_q, vec_q2;
  logic [3*OutW-1:0] out_d, out_q;
  logic [GW-1:0]     g_q;

  always_ff @(posedge clk_i) begin
    if (en_i[0]) vec_q <= vec_i;
    if (en_i[1]) vec_q2 <= vec_q;
    if (en_i[2]) out_q <= out_d;
  end
  assign vec_o = out_q;

  if (Order == 0) begin : g_requantize_only
    // Stage out: out_c = rq(in_c, OutFmt).
    for (genvar c = 0; c < 3; c++) begin : g_comp
      fx_rq #(.InFmt(InFmt), .OutFmt(OutFmt), .Round(Round))
          u_out (.in_i(vec_q2[c*InW+:InW]), .out_o(out_d[c*OutW+:OutW]));
    end
    assign g_q = '0;
    logic unused_g;
    assign unused_g = ^g_q;
  end else begin : g_approximate
    localparam int unsigned OneFmt  = fx_pkg::fx_fmt(1'b0, 1, 0);  // the constant 1
    localparam int unsigned ZW      = fx_pkg::fx_width(ZFmt);
    localparam int unsigned YW      = fx_pkg::fx_width(YFmt);
    // Exact intermediates.
    localparam int unsigned OneMinusZFmt = fx_pkg::fx_sub_fmt(OneFmt, ZFmt);
    localparam int unsigned YSqFmt  = fx_pkg::fx_mul_fmt(YFmt, YFmt);
    localparam int unsigned PolyFmt = Order == 1 ? YFmt : fx_pkg::fx_add_fmt(YFmt, YSqFmt);
    localparam int unsigned HalfFmt = fx_pkg::fx_scale_fmt(PolyFmt, -1);
    localparam int unsigned GExactFmt = fx_pkg::fx_add_fmt(OneFmt, HalfFmt);
    localparam int unsigned ProdFmt = fx_pkg::fx_mul_fmt(GFmt, InFmt);

    // Stage z: z = rq(in·in, ZFmt).
    logic [ZW-1:0] z_d, z_q;
    fx_dot3 #(.AFmt(InFmt), .BFmt(InFmt), .OutFmt(ZFmt), .Round(Round))
        u_z (.a_i(vec_i), .b_i(vec_i), .dot_o(z_d));
    always_ff @(posedge clk_i) begin
      if (en_i[0]) z_q <= z_d;
    end

    // Stage g: y = rq(1 - z, YFmt); g = rq(1 + poly/2, GFmt), poly = y (g1) or y + y² (g2).
    logic [fx_pkg::fx_width(OneMinusZFmt)-1:0] one_minus_z;
    logic [YW-1:0]                             y;
    logic [fx_pkg::fx_width(PolyFmt)-1:0]      poly;
    logic [fx_pkg::fx_width(HalfFmt)-1:0]      half;
    logic [fx_pkg::fx_width(GExactFmt)-1:0]    g_exact;
    logic [GW-1:0]                             g_d;
    fx_sub #(.AFmt(OneFmt), .BFmt(ZFmt))
        u_one_minus_z (.a_i(1'b1), .b_i(z_q), .delta_o(one_minus_z));
    fx_rq #(.InFmt(OneMinusZFmt), .OutFmt(YFmt), .Round(Round)) u_y (.in_i(one_minus_z), .out_o(y));
    if (Order == 1) begin : g_first_order
      assign poly = y;
    end else begin : g_second_order
      logic [fx_pkg::fx_width(YSqFmt)-1:0] y_sq;
      fx_mul #(.AFmt(YFmt), .BFmt(YFmt)) u_y_sq (.a_i(y), .b_i(y), .prod_o(y_sq));
      fx_add #(.AFmt(YFmt), .BFmt(YSqFmt)) u_poly (.a_i(y), .b_i(y_sq), .sum_o(poly));
    end
    fx_scale #(.AFmt(PolyFmt), .Shift(-1)) u_half (.a_i(poly), .scaled_o(half));
    fx_add #(.AFmt(OneFmt), .BFmt(HalfFmt)) u_g_exact (.a_i(1'b1), .b_i(half), .sum_o(g_exact));
    fx_rq #(.InFmt(GExactFmt), .OutFmt(GFmt), .Round(Round)) u_g (.in_i(g_exact), .out_o(g_d));
    always_ff @(posedge clk_i) begin
      if (en_i[1]) g_q <= g_d;
    end

    // Stage out: out_c = rq(g·in_c, OutFmt).
    for (genvar c = 0; c < 3; c++) begin : g_comp
      logic [fx_pkg::fx_width(ProdFmt)-1:0] prod;
      fx_mul #(.AFmt(GFmt), .BFmt(InFmt))
          u_scale (.a_i(g_q), .b_i(vec_q2[c*InW+:InW]), .prod_o(prod));
      fx_rq #(.InFmt(ProdFmt), .OutFmt(OutFmt), .Round(Round))
          u_out (.in_i(prod), .out_o(out_d[c*OutW+:OutW]));
    end
  end

  if (Order > 2) begin : g_bad_order
    $error("lyon_norm: Order must be 0, 1 or 2");
  end

endmodule
