// fx_sub: exact difference a - b in fx_pkg::fx_sub_fmt(AFmt, BFmt) (model: fx::sub), always signed.
// Combinational; latency 0.
//
// Parameters: AFmt, BFmt - operand format words. Ports: a_i, b_i - operands; diff_o - result.
module fx_sub
#(
  parameter int unsigned AFmt    = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned BFmt    = fx_pkg::fx_fmt(1'b1, 1, 10),
  // Derived, do not override.
  localparam int unsigned DiffFmt = fx_pkg::fx_sub_fmt(AFmt, BFmt),
  localparam int unsigned AW      = fx_pkg::fx_width(AFmt),
  localparam int unsigned BW      = fx_pkg::fx_width(BFmt),
  localparam int unsigned DiffW   = fx_pkg::fx_width(DiffFmt)
) (
  input  logic [   AW-1:0] a_i,
  input  logic [   BW-1:0] b_i,
  output logic [DiffW-1:0] diff_o
);

  logic [DiffW-1:0] a_aligned, b_aligned;

  fx_resize #(.InFmt(AFmt), .OutFmt(DiffFmt), .Round(fx_pkg::FxTruncate), .Overflow(fx_pkg::FxWrap)) u_align_a (
    .in_i (a_i),
    .out_o(a_aligned)
  );
  fx_resize #(.InFmt(BFmt), .OutFmt(DiffFmt), .Round(fx_pkg::FxTruncate), .Overflow(fx_pkg::FxWrap)) u_align_b (
    .in_i (b_i),
    .out_o(b_aligned)
  );

  // Modulo-2^DiffW subtraction is exact because DiffFmt holds the true difference.
  assign diff_o = a_aligned - b_aligned;

endmodule
