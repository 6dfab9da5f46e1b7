// shade_quad: the quadratic (or linear) colour interpolator as a triangle-in, pixels-out
// pipeline (docs/system.md): a triangle program with its number in, (x, y, tri, R, G, B) for every
// covered pixel out, one per clock. It is the walker (quad_walker_core: every stage, the latency
// of 4 cycles and the throughput of one row set-up clock plus one clock per pixel are described
// there) with the triangle's number as its tag. Specification: docs/quad.md; the number:
// docs/system.md, "Composed pipelines".
// Parameters:
//   AccFmt   [acc]       - signed accumulator format word of the channels
//   OutFmt   [out]       - colour output format word
//   OutRound [out_round] - fx_pkg rounding mode of the colour output
//   SubBits  [sub_bits]  - subpixel bits of the setup (sets the DDA widths QW and RW)
// Ports (fields packed from the LSB in the order listed):
//   clk_i, rst_ni            - clock; asynchronous reset, active low
//   in_valid_i, in_ready_o   - program handshake
//   in_bbox_i                - x0, y0, x1, y1 (CoordW bits each): rows y0..y1, columns x0..x1
//   in_edge0_i .. in_edge2_i - per edge: kind (2 bits), q, r, d, dq, dr
//   in_red_i, in_green_i, in_blue_i - per channel: f, gy, gx, a, b, c (AccW bits each)
//   in_tri_i                 - the triangle's number (TriW bits)
//   out_valid_o, out_ready_i - pixel handshake
//   out_x_o, out_y_o         - the pixel
//   out_tri_o                - its triangle's number
//   out_rgb_o                - R, G, B (OutW bits each)
//
// Assertions: the walker's.
module shade_quad #(
  parameter bit [31:0] AccFmt   = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter bit [31:0] OutFmt   = fx_pkg::fx_fmt(1'b0, 0, 8),
  parameter bit [31:0] OutRound = fx_pkg::FxHalfEven,
  parameter bit [31:0] SubBits  = 4,
  // Derived, do not override.
  localparam bit [31:0] AccW    = fx_pkg::fx_width(AccFmt),
  localparam bit [31:0] OutW    = fx_pkg::fx_width(OutFmt),
  localparam bit [31:0] CoordW  = 11,
  localparam bit [31:0] TriW    = 16,
  localparam bit [31:0] QW      = 26 + 2 * SubBits,
  localparam bit [31:0] RW      = 12 + 2 * SubBits,
  localparam bit [31:0] EdgeW   = 2 + 2 * QW + 3 * RW,
  localparam bit [31:0] ChanW   = 6 * AccW
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic [4*CoordW-1:0] in_bbox_i,
  input  logic [   EdgeW-1:0] in_edge0_i,
  input  logic [   EdgeW-1:0] in_edge1_i,
  input  logic [   EdgeW-1:0] in_edge2_i,
  input  logic [   ChanW-1:0] in_red_i,
  input  logic [   ChanW-1:0] in_green_i,
  input  logic [   ChanW-1:0] in_blue_i,
  input  logic [    TriW-1:0] in_tri_i,
  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [  CoordW-1:0] out_x_o,
  output logic [  CoordW-1:0] out_y_o,
  output logic [    TriW-1:0] out_tri_o,
  output logic [  3*OutW-1:0] out_rgb_o
);

  quad_walker_core #(
    .AccFmt  (AccFmt),
    .OutFmt  (OutFmt),
    .OutRound(OutRound),
    .SubBits (SubBits),
    .TagW    (TriW)
  ) u_walker (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .in_bbox_i,
    .in_edge0_i,
    .in_edge1_i,
    .in_edge2_i,
    .in_red_i,
    .in_green_i,
    .in_blue_i,
    .in_tag_i   (in_tri_i),
    .out_valid_o,
    .out_ready_i,
    .out_x_o,
    .out_y_o,
    .out_rgb_o,
    .out_tag_o  (out_tri_o)
  );

endmodule
