// shade_lyon: Lyon's shading pipeline from triangle to pixels (Lyon, TR #43: "the interpolated,
// unnormalized normal" goes into the g2 path). A triangle program walks through the quadratic
// walker (quad_walker_core), which interpolates the normal's three components as its three
// channels and carries the triangle's V, L and shininess to every pixel; each pixel's normal N'
// goes into Lyon's unit (lyon_core, LIRP tied off: N0 = N1 = N', a = 0), which carries the
// pixel's position and triangle alongside. Out come (x, y, tri, spec, diff), one pixel per
// clock: the contract of every triangle-in, pixels-out top (docs/system.md).
//
// The walker's channels clamp to [0, 1], so a normal component n in [-1, 1] travels encoded as
// c = (n + 1)/2 in ChanFmt = U1.(F+1), where VecFmt = S1.F (I >= 1 integer bits): the setup
// writes the encoded samples, and decoding N'_c = 2c - 1 is exact, the raw subtraction
// C - 2^F (docs/shade_lyon.md, "Stages").
//
// Latency 17 + K cycles from a program to its first pixel (the walker's 4, Lyon's 13 + K);
// throughput: the walker's (one clock per row of the program's box plus one per covered pixel),
// Lyon's unit takes one pixel per clock. Any backpressure: both parts end in skid buffers.
// Parameters: Lyon's unit's (lyon_core: Arrangement .. DiffFmt, the configuration's [param],
// [mode] round and [format] keys) and the walker's:
//   AccFmt  [acc]      - signed accumulator format word of the walker's channels
//   SubBits [sub_bits] - subpixel bits of the setup (sets the edge DDA widths)
// Ports (fields packed from the LSB in the order listed):
//   clk_i, rst_ni            - clock; asynchronous reset, active low
//   in_valid_i, in_ready_o   - program handshake
//   in_bbox_i, in_edge0_i .. in_edge2_i - the triangle's box and edges, as quad_walker's
//   in_nx_i, in_ny_i, in_nz_i - per normal component: f, gy, gx, a, b, c (AccW bits each) of
//                               its encoded value c = (n + 1)/2
//   in_v_i, in_l_i           - V, L (x, y, z, VecW bits each), the triangle's
//   in_shin_i                - n or m, the triangle's
//   in_tri_i                 - the triangle's number (TriW bits), out with each of its pixels
//   out_valid_o, out_ready_i - pixel handshake
//   out_x_o, out_y_o         - the pixel
//   out_tri_o                - its triangle's number
//   out_spec_o, out_diff_o   - Lyon's spec and diff
//
// Assertions: the parts' (skid buffers, stream_check at Lyon's input, elaboration checks); the
// format check below.
module shade_lyon #(
  parameter bit [31:0] Arrangement = 7,
  parameter bit [31:0] Halfway     = 0,
  parameter bit [31:0] Norm        = 2,
  parameter bit [31:0] HNorm       = 0,
  parameter bit [31:0] K           = 2,
  parameter bit [31:0] Round       = fx_pkg::FxHalfEven,
  parameter bit [31:0] VecFmt      = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] AFmt        = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter bit [31:0] ShinFmt     = fx_pkg::fx_fmt(1'b0, 13, 0),
  parameter bit [31:0] NpFmt       = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] ZFmt        = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter bit [31:0] YFmt        = fx_pkg::fx_fmt(1'b1, 0, 12),
  parameter bit [31:0] GFmt        = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter bit [31:0] NFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] HFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] DotFmt      = fx_pkg::fx_fmt(1'b1, 1, 12),
  parameter bit [31:0] RFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] DFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] DdFmt       = fx_pkg::fx_fmt(1'b0, 3, 19),
  parameter bit [31:0] DabsFmt     = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter bit [31:0] WFmt        = fx_pkg::fx_fmt(1'b0, 0, 9),
  parameter bit [31:0] XfFmt       = fx_pkg::fx_fmt(1'b0, 0, 16),
  parameter bit [31:0] SqFmt       = fx_pkg::fx_fmt(1'b0, 1, 16),
  parameter bit [31:0] SpecFmt     = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter bit [31:0] DiffFmt     = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter bit [31:0] AccFmt      = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter bit [31:0] SubBits     = 4,
  // Derived, do not override.
  localparam bit [31:0] VecW       = fx_pkg::fx_width(VecFmt),
  localparam bit [31:0] AW         = fx_pkg::fx_width(AFmt),
  localparam bit [31:0] ShinW      = fx_pkg::fx_width(ShinFmt),
  localparam bit [31:0] SpecW      = fx_pkg::fx_width(SpecFmt),
  localparam bit [31:0] DiffW      = fx_pkg::fx_width(DiffFmt),
  localparam bit [31:0] AccW       = fx_pkg::fx_width(AccFmt),
  localparam bit [31:0] CoordW     = 11,
  localparam bit [31:0] TriW       = 16,
  localparam bit [31:0] QW         = 26 + 2 * SubBits,
  localparam bit [31:0] RW         = 12 + 2 * SubBits,
  localparam bit [31:0] EdgeW      = 2 + 2 * QW + 3 * RW,
  localparam bit [31:0] ProgChanW  = 6 * AccW
) (
  input  logic                clk_i,
  input  logic                rst_ni,
  input  logic                in_valid_i,
  output logic                in_ready_o,
  input  logic [4*CoordW-1:0] in_bbox_i,
  input  logic [   EdgeW-1:0] in_edge0_i,
  input  logic [   EdgeW-1:0] in_edge1_i,
  input  logic [   EdgeW-1:0] in_edge2_i,
  input  logic [ProgChanW-1:0] in_nx_i,
  input  logic [ProgChanW-1:0] in_ny_i,
  input  logic [ProgChanW-1:0] in_nz_i,
  input  logic [  3*VecW-1:0] in_v_i,
  input  logic [  3*VecW-1:0] in_l_i,
  input  logic [   ShinW-1:0] in_shin_i,
  input  logic [    TriW-1:0] in_tri_i,
  output logic                out_valid_o,
  input  logic                out_ready_i,
  output logic [  CoordW-1:0] out_x_o,
  output logic [  CoordW-1:0] out_y_o,
  output logic [    TriW-1:0] out_tri_o,
  output logic [   SpecW-1:0] out_spec_o,
  output logic [   DiffW-1:0] out_diff_o
);

  localparam bit [31:0] F       = fx_pkg::fx_frac(VecFmt);
  localparam bit [31:0] ChanFmt = fx_pkg::fx_fmt(1'b0, 1, F + 1);  // c = (n + 1)/2
  localparam bit [31:0] CW      = F + 2;  // an encoded component
  localparam bit [31:0] TagW    = TriW + ShinW + 6 * VecW;

  // ---- The walker: encoded normal components; the triangle, shininess, L and V as the tag ----
  logic                px_valid, px_ready;
  logic [  CoordW-1:0] px_x, px_y;
  logic [    3*CW-1:0] px_c;
  logic [    TagW-1:0] px_tag;
  quad_walker_core #(
    .AccFmt  (AccFmt),
    .OutFmt  (ChanFmt),
    .OutRound(Round),
    .SubBits (SubBits),
    .TagW    (TagW)
  ) u_walker (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .in_bbox_i,
    .in_edge0_i,
    .in_edge1_i,
    .in_edge2_i,
    .in_red_i   (in_nx_i),
    .in_green_i (in_ny_i),
    .in_blue_i  (in_nz_i),
    .in_tag_i   ({in_tri_i, in_shin_i, in_l_i, in_v_i}),
    .out_valid_o(px_valid),
    .out_ready_i(px_ready),
    .out_x_o    (px_x),
    .out_y_o    (px_y),
    .out_rgb_o  (px_c),
    .out_tag_o  (px_tag)
  );

  // ---- Decode: N'_c = 2c - 1 = C - 2^F, exact in VecFmt ----
  logic [3*VecW-1:0] np;
  for (genvar c = 0; c < 3; c++) begin : g_decode
    logic [CW-1:0] centred;  // |C - 2^F| <= 2^F: exact in CW signed bits
    assign centred = px_c[c*CW+:CW] - CW'(1 << F);
    assign np[c*VecW+:VecW] = VecW'($signed(centred));  // sign-extends to VecW >= CW
  end

  // ---- Lyon's unit, the pixel's position and triangle alongside ----
  lyon_core #(
    .Arrangement(Arrangement),
    .Halfway    (Halfway),
    .Norm       (Norm),
    .HNorm      (HNorm),
    .K          (K),
    .Round      (Round),
    .VecFmt     (VecFmt),
    .AFmt       (AFmt),
    .ShinFmt    (ShinFmt),
    .NpFmt      (NpFmt),
    .ZFmt       (ZFmt),
    .YFmt       (YFmt),
    .GFmt       (GFmt),
    .NFmt       (NFmt),
    .HFmt       (HFmt),
    .DotFmt     (DotFmt),
    .RFmt       (RFmt),
    .DFmt       (DFmt),
    .DdFmt      (DdFmt),
    .DabsFmt    (DabsFmt),
    .WFmt       (WFmt),
    .XfFmt      (XfFmt),
    .SqFmt      (SqFmt),
    .SpecFmt    (SpecFmt),
    .DiffFmt    (DiffFmt),
    .SideW      (TriW + 2 * CoordW)
  ) u_lyon (
    .clk_i,
    .rst_ni,
    .in_valid_i (px_valid),
    .in_ready_o (px_ready),
    .in_n0_i    (np),
    .in_n1_i    (np),
    .in_a_i     (AW'(0)),
    .in_v_i     (px_tag[0+:3*VecW]),
    .in_l_i     (px_tag[3*VecW+:3*VecW]),
    .in_shin_i  (px_tag[6*VecW+:ShinW]),
    .in_side_i  ({px_tag[TagW-1-:TriW], px_y, px_x}),
    .out_valid_o,
    .out_ready_i,
    .out_spec_o,
    .out_diff_o,
    .out_side_o ({out_tri_o, out_y_o, out_x_o})
  );

  // Assertions: elaboration-time parameter checks.
`ifndef __ICARUS__  // Icarus 11 has no elaboration-time $error
  if (!fx_pkg::fx_signed(VecFmt) || fx_pkg::fx_int(VecFmt) < 1) begin : g_bad_vec
    $error("shade_lyon: VecFmt must be signed with an integer bit (N' is in [-1, 1])");
  end
`endif

endmodule
