// fx_dot3: dot product of two 3-vectors, requantized once: dot = rq(a_x·b_x + a_y·b_y + a_z·b_z,
// OutFmt) with Round, saturating (model: the pipelines' dot3 followed by fx::resize). The
// products and their sum are exact and summed in the model's order, (x + y) + z. Used for every
// N·V, H·N, N·L, N'·N' and D·D of the Lyon unit (docs/lyon.md).
//
// Latency 0 (combinational).
// Parameters:
//   AFmt, BFmt - format words of a's and b's components
//   OutFmt     - format word of the result
//   Round      - fx_pkg rounding mode of the one requantization
// Ports:
//   a_i, b_i   - the vectors, components x, y, z packed from the LSB (AW resp. BW bits each)
//   dot_o      - rq(a·b, OutFmt)
//
// Assertions: Round is checked at elaboration (fx_rq).
module fx_dot3 #(
  parameter int unsigned AFmt    = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned BFmt    = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned OutFmt  = fx_pkg::fx_fmt(1'b1, 1, 12),
  parameter int unsigned Round   = fx_pkg::FxHalfEven,
  // Derived, do not override.
  localparam int unsigned AW     = fx_pkg::fx_width(AFmt),
  localparam int unsigned BW     = fx_pkg::fx_width(BFmt),
  localparam int unsigned OutW   = fx_pkg::fx_width(OutFmt)
) (
  input  logic [3*AW-1:0] a_i,
  input  logic [3*BW-1:0] b_i,
  output logic [OutW-1:0] dot_o
);

  localparam int unsigned ProdFmt = fx_pkg::fx_mul_fmt(AFmt, BFmt);
  localparam int unsigned Sum2Fmt = fx_pkg::fx_add_fmt(ProdFmt, ProdFmt);
  localparam int unsigned Sum3Fmt = fx_pkg::fx_add_fmt(Sum2Fmt, ProdFmt);
  localparam int unsigned ProdW   = fx_pkg::fx_width(ProdFmt);

  logic [3*ProdW-1:0]                   prod;
  logic [fx_pkg::fx_width(Sum2Fmt)-1:0] sum2;
  logic [fx_pkg::fx_width(Sum3Fmt)-1:0] sum3;

  for (genvar c = 0; c < 3; c++) begin : g_comp
    fx_mul #(.AFmt(AFmt), .BFmt(BFmt)) u_mul (
      .a_i   (a_i[c*AW+:AW]),
      .b_i   (b_i[c*BW+:BW]),
      .prod_o(prod[c*ProdW+:ProdW])
    );
  end
  fx_add #(.AFmt(ProdFmt), .BFmt(ProdFmt)) u_add_xy (
    .a_i  (prod[0+:ProdW]),
    .b_i  (prod[ProdW+:ProdW]),
    .sum_o(sum2)
  );
  fx_add #(.AFmt(Sum2Fmt), .BFmt(ProdFmt)) u_add_z (
    .a_i  (sum2),
    .b_i  (prod[2*ProdW+:ProdW]),
    .sum_o(sum3)
  );
  fx_rq #(.InFmt(Sum3Fmt), .OutFmt(OutFmt), .Round(Round)) u_rq (.in_i(sum3), .out_o(dot_o));

endmodule
