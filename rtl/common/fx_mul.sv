// fx_mul: exact product a · b in fx_pkg::fx_mul_fmt(AFmt, BFmt) (model: fx::mul); the product
// is AW + BW bits wide, so nothing is rounded or clipped.
//
// Latency 0 (combinational).
// Parameters:
//   AFmt, BFmt - operand format words (fx_pkg::fx_fmt)
// Ports:
//   a_i, b_i   - operands (raw bits)
//   prod_o     - a · b in fx_mul_fmt(AFmt, BFmt)
//
// Assertions: none (no parameter value is invalid).
module fx_mul #(
  parameter int unsigned AFmt    = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned BFmt    = fx_pkg::fx_fmt(1'b0, 1, 10),
  // Derived, do not override.
  localparam int unsigned ProdFmt = fx_pkg::fx_mul_fmt(AFmt, BFmt),
  localparam int unsigned AW      = fx_pkg::fx_width(AFmt),
  localparam int unsigned BW      = fx_pkg::fx_width(BFmt),
  localparam int unsigned ProdW   = fx_pkg::fx_width(ProdFmt)
) (
  input  logic [   AW-1:0] a_i,
  input  logic [   BW-1:0] b_i,
  output logic [ProdW-1:0] prod_o
);

  // Each operand as a signed number one bit wider (an unsigned operand gets a 0 sign bit), so one
  // signed multiplier serves every signedness combination.
  logic signed [AW:0] a_s;
  logic signed [BW:0] b_s;
  logic signed [AW+BW+1:0] full;

  if (fx_pkg::fx_signed(AFmt)) begin : g_a_signed
    assign a_s = (AW + 1)'($signed(a_i));
  end else begin : g_a_unsigned
    assign a_s = $signed({1'b0, a_i});
  end
  if (fx_pkg::fx_signed(BFmt)) begin : g_b_signed
    assign b_s = (BW + 1)'($signed(b_i));
  end else begin : g_b_unsigned
    assign b_s = $signed({1'b0, b_i});
  end

  assign full = a_s * b_s;
  // The top two bits of `full` only repeat the sign: ProdFmt holds every product.
  assign prod_o = full[ProdW-1:0];
  logic unused_sign_copies;
  assign unused_sign_copies = ^full[AW+BW+1:ProdW];

endmodule
