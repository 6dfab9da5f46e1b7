// fx_add: exact sum a + b in fx_pkg::fx_add_fmt(AFmt, BFmt) (model: fx::add). Operands are
// aligned to the sum's binary point; the sum format holds every result, so nothing is rounded or
// clipped.
//
// Latency 0 (combinational).
// Parameters:
//   AFmt, BFmt - operand format words (fx_pkg::fx_fmt)
// Ports:
//   a_i, b_i   - operands (raw bits)
//   sum_o      - a + b in fx_add_fmt(AFmt, BFmt)
//
// Assertions: none (no parameter value is invalid).
module fx_add #(
  parameter int unsigned AFmt   = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned BFmt   = fx_pkg::fx_fmt(1'b1, 1, 10),
  // Derived, do not override.
  localparam int unsigned SumFmt = fx_pkg::fx_add_fmt(AFmt, BFmt),
  localparam int unsigned AW     = fx_pkg::fx_width(AFmt),
  localparam int unsigned BW     = fx_pkg::fx_width(BFmt),
  localparam int unsigned SumW   = fx_pkg::fx_width(SumFmt)
) (
  input  logic [  AW-1:0] a_i,
  input  logic [  BW-1:0] b_i,
  output logic [SumW-1:0] sum_o
);

  logic [SumW-1:0] a_aligned, b_aligned;

  // Alignment is exact (SumFmt has at least each operand's bits), so the modes do not matter.
  fx_resize #(
    .InFmt   (AFmt),
    .OutFmt  (SumFmt),
    .Round   (fx_pkg::FxTruncate),
    .Overflow(fx_pkg::FxWrap)
  ) u_align_a (
    .in_i (a_i),
    .out_o(a_aligned)
  );
  fx_resize #(
    .InFmt   (BFmt),
    .OutFmt  (SumFmt),
    .Round   (fx_pkg::FxTruncate),
    .Overflow(fx_pkg::FxWrap)
  ) u_align_b (
    .in_i (b_i),
    .out_o(b_aligned)
  );

  // Modulo-2^SumW addition is exact because SumFmt holds the true sum.
  assign sum_o = a_aligned + b_aligned;

endmodule
