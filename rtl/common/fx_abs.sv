// fx_abs: exact magnitude |a| in fx_pkg::fx_abs_fmt(AFmt) (model: fx::abs), unsigned and as
// wide as a (the most negative value's magnitude needs the bit that held the sign).
//
// Latency 0 (combinational).
// Parameters:
//   AFmt  - operand format word (fx_pkg::fx_fmt)
// Ports:
//   a_i   - operand (raw bits)
//   abs_o - |a| in fx_abs_fmt(AFmt)
//
// Assertions: none (no parameter value is invalid).
module fx_abs #(
  parameter int unsigned AFmt   = fx_pkg::fx_fmt(1'b1, 1, 10),
  // Derived, do not override.
  localparam int unsigned AbsFmt = fx_pkg::fx_abs_fmt(AFmt),
  localparam int unsigned AW     = fx_pkg::fx_width(AFmt),
  localparam int unsigned AbsW   = fx_pkg::fx_width(AbsFmt)
) (
  input  logic [  AW-1:0] a_i,
  output logic [AbsW-1:0] abs_o
);

  if (fx_pkg::fx_signed(AFmt)) begin : g_signed
    assign abs_o = a_i[AW-1] ? AbsW'(-a_i) : AbsW'(a_i);
  end else begin : g_unsigned
    assign abs_o = AbsW'(a_i);
  end

endmodule
