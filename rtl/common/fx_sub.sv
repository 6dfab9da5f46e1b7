// fx_sub: exact difference delta = a - b in fx_pkg::fx_sub_fmt(AFmt, BFmt) (model: fx::sub),
// always signed. Both operands are aligned to the result's binary point; the result format holds
// every difference, so nothing is rounded or clipped.
//
// Latency 0 (combinational).
// Parameters:
//   AFmt, BFmt - operand format words (fx_pkg::fx_fmt)
// Ports:
//   a_i, b_i   - operands (raw bits)
//   delta_o    - a - b in fx_sub_fmt(AFmt, BFmt)
//
// Assertions: none (no parameter value is invalid).
module fx_sub #(
  parameter int unsigned AFmt     = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned BFmt     = fx_pkg::fx_fmt(1'b1, 1, 10),
  // Derived, do not override.
  localparam int unsigned DeltaFmt = fx_pkg::fx_sub_fmt(AFmt, BFmt),
  localparam int unsigned AW       = fx_pkg::fx_width(AFmt),
  localparam int unsigned BW       = fx_pkg::fx_width(BFmt),
  localparam int unsigned DeltaW   = fx_pkg::fx_width(DeltaFmt)
) (
  input  logic [    AW-1:0] a_i,
  input  logic [    BW-1:0] b_i,
  output logic [DeltaW-1:0] delta_o
);

  logic [DeltaW-1:0] a_aligned, b_aligned;

  // Alignment is exact (DeltaFmt has at least each operand's bits), so the modes do not matter.
  fx_resize #(
    .InFmt   (AFmt),
    .OutFmt  (DeltaFmt),
    .Round   (fx_pkg::FxTruncate),
    .Overflow(fx_pkg::FxWrap)
  ) u_align_a (
    .in_i (a_i),
    .out_o(a_aligned)
  );
  fx_resize #(
    .InFmt   (BFmt),
    .OutFmt  (DeltaFmt),
    .Round   (fx_pkg::FxTruncate),
    .Overflow(fx_pkg::FxWrap)
  ) u_align_b (
    .in_i (b_i),
    .out_o(b_aligned)
  );

  // Modulo-2^DeltaW subtraction is exact because DeltaFmt holds the true difference.
  assign delta_o = a_aligned - b_aligned;

endmodule
