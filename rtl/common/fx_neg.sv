// fx_neg: exact negation -a in fx_pkg::fx_neg_fmt(AFmt) (model: fx::neg), always signed (one
// integer bit more for a signed operand: -(-2^n) needs it).
//
// Latency 0 (combinational).
// Parameters:
//   AFmt  - operand format word (fx_pkg::fx_fmt)
// Ports:
//   a_i   - operand (raw bits)
//   neg_o - -a in fx_neg_fmt(AFmt)
//
// Assertions: none (no parameter value is invalid).
module fx_neg #(
  parameter int unsigned AFmt   = fx_pkg::fx_fmt(1'b1, 1, 10),
  // Derived, do not override.
  localparam int unsigned NegFmt = fx_pkg::fx_neg_fmt(AFmt),
  localparam int unsigned AW     = fx_pkg::fx_width(AFmt),
  localparam int unsigned NegW   = fx_pkg::fx_width(NegFmt)
) (
  input  logic [  AW-1:0] a_i,
  output logic [NegW-1:0] neg_o
);

  logic [NegW-1:0] a_ext;

  fx_resize #(
    .InFmt   (AFmt),
    .OutFmt  (NegFmt),
    .Round   (fx_pkg::FxTruncate),
    .Overflow(fx_pkg::FxWrap)
  ) u_extend (
    .in_i (a_i),
    .out_o(a_ext)
  );

  assign neg_o = -a_ext;

endmodule
