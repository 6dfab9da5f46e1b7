// lyon_core: Lyon's reformulated Phong specular unit with the diffuse term (Lyon, TR #43,
// Figs. 6-8), one pixel per clock, valid/ready with backpressure, with side data carried along
// each pixel unread (the composed pipeline's pixel position, docs/shade_lyon.md). lyon_top is
// this core without side data.
//
//   N' = LIRP(N0, N1, a); N = g(N'·N')·N'                           Fig. 7a (g: none, g1, g2)
//   reflect (Halfway = 0):  R = 2(N·V)N - V;  D = R - L             Fig. 7b, 7c
//   halfway (Halfway = 1):  H = (L + V)/2 (optionally g-normalized);
//                           D = H - (H·N)N, shininess n -> 4n       "The Half-way Vector Approach"
//   x/2^K from D and n (Arrangement 7) or m = sqrt(n) (Arrangement 8) Fig. 7c / Fig. 8
//   spec = f_K(x) = (1 - x/2^K)^(2^K), 0 when x/2^K >= 1             Fig. 7d
//   diff = max(N·L, 0)                                              (the diffuse term)
//
// Stages (one pipe_ctrl, Depth = 12 + K; the stage numbers of docs/lyon.md's table), then an
// output skid buffer: 0-1 LIRP (lirp_core) | 2 N' (and H) | 3-5 normalization (lyon_norm) |
// 6 dot, diff | 7 R or (H·N)N | 8 D | 9-10 x/2^K (lyon_x) | 11..11+K sq_0..sq_K (lyon_shape).
// Every requantization is rq = fx_rq: round with Round, saturate. Specification: docs/lyon.md.
//
// Latency 13 + K cycles; throughput 1 pixel per clock; any backpressure (in_ready_o has no
// combinational path from out_ready_i: the skid buffer cuts it).
// Parameters (formats are fx_pkg format words; the configuration key is in brackets):
//   Arrangement [arrangement] - 7 (x from n·D·D) or 8 (root shininess m)
//   Halfway [halfway]         - 0: D = R - L; 1: D = H - (H·N)N
//   Norm [norm], HNorm [h_norm] - normalization of N' and of H: 0 none, 1 g1, 2 g2
//   K [k]                     - shape function order, 0..3
//   Round [round]             - fx_pkg rounding mode of every rq
//   VecFmt [vec]              - components of N0, N1, V, L
//   AFmt [a]                  - LIRP factor a
//   ShinFmt [shin]            - shininess n (arrangement 7) or m (arrangement 8), unsigned
//   NpFmt [np]                - N'
//   ZFmt [z], YFmt [y], GFmt [g] - z = N'·N' (and H·H), y = 1 - z, g
//   NFmt [n], HFmt [h]        - N; H
//   DotFmt [dot]              - N·V (reflect) or H·N (halfway)
//   RFmt [r]                  - R (reflect) or (H·N)N (halfway)
//   DFmt [d]                  - D
//   DdFmt [dd]                - D·D (arrangement 7)
//   DabsFmt [dabs], WFmt [w]  - |D_c| and the squarer inputs (arrangement 8)
//   XfFmt [xf], SqFmt [sq]    - x/2^K requantized; sq_0 = 1 - x/2^K and its squares
//   SpecFmt [spec]            - output spec
//   DiffFmt [diff]            - output diff (the diffuse term; negative N·L saturates to 0)
//   SideW                     - bits of the side data
// Ports:
//   clk_i, rst_ni             - clock; asynchronous reset, active low
//   in_valid_i, in_ready_o    - input handshake
//   in_n0_i, in_n1_i          - N0, N1 (x, y, z packed from the LSB, VecW bits each)
//   in_a_i                    - a
//   in_v_i, in_l_i            - V, L (packed like N0)
//   in_shin_i                 - n or m
//   in_side_i                 - side data, out with the pixel's spec and diff
//   out_valid_o, out_ready_i  - output handshake
//   out_spec_o, out_diff_o    - spec, diff
//   out_side_o                - the pixel's side data
//
// Assertions: Arrangement and K are checked at elaboration (end of the module); the handshake
// (valid held until taken, data stable while stalled) is the skid buffer's and the pipe_ctrl's,
// checked by tests/stream_rtl_test.cpp and by the co-simulation harness.
module lyon_core #(
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
  parameter bit [31:0] SideW       = 1,
  // Derived, do not override.
  localparam bit [31:0] VecW       = fx_pkg::fx_width(VecFmt),
  localparam bit [31:0] AW         = fx_pkg::fx_width(AFmt),
  localparam bit [31:0] ShinW      = fx_pkg::fx_width(ShinFmt),
  localparam bit [31:0] SpecW      = fx_pkg::fx_width(SpecFmt),
  localparam bit [31:0] DiffW      = fx_pkg::fx_width(DiffFmt)
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              in_valid_i,
  output logic              in_ready_o,
  input  logic [3*VecW-1:0] in_n0_i,
  input  logic [3*VecW-1:0] in_n1_i,
  input  logic [    AW-1:0] in_a_i,
  input  logic [3*VecW-1:0] in_v_i,
  input  logic [3*VecW-1:0] in_l_i,
  input  logic [ ShinW-1:0] in_shin_i,
  input  logic [ SideW-1:0] in_side_i,
  output logic              out_valid_o,
  input  logic              out_ready_i,
  output logic [ SpecW-1:0] out_spec_o,
  output logic [ DiffW-1:0] out_diff_o,
  output logic [ SideW-1:0] out_side_o
);

  localparam bit [31:0] Depth = 12 + K;
  localparam bit [31:0] NpW   = fx_pkg::fx_width(NpFmt);
  localparam bit [31:0] NW    = fx_pkg::fx_width(NFmt);
  localparam bit [31:0] HW    = fx_pkg::fx_width(HFmt);
  localparam bit [31:0] DotW  = fx_pkg::fx_width(DotFmt);
  localparam bit [31:0] RW    = fx_pkg::fx_width(RFmt);
  localparam bit [31:0] DW    = fx_pkg::fx_width(DFmt);
  localparam bit [31:0] XfW   = fx_pkg::fx_width(XfFmt);

  // ---- Control: stage i loads its registers on en[i] ----
  logic [Depth-1:0] en;
  logic             pipe_valid, pipe_ready;
  pipe_ctrl #(.Depth(Depth)) u_ctrl (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .out_valid_o(pipe_valid),
    .out_ready_i(pipe_ready),
    .en_o       (en)
  );

  // ---- Side data: V and L (read by H at stage 2, the dots at 6, R at 7, D at 8), shininess
  // (read at 9). x_qi is x as held by stage i. ----
  logic [6*VecW-1:0] vl_q1, vl_q5, vl_q6;
  logic [3*VecW-1:0] l_q5, v_q6, l_q7;
  logic [ ShinW-1:0] shin_q8;
  pipe_delay #(.Width(6 * VecW), .Depth(2)) u_vl_to_2 (
    .clk_i,
    .en_i(en[1:0]),
    .d_i ({in_l_i, in_v_i}),
    .q_o (vl_q1)
  );
  pipe_delay #(.Width(6 * VecW), .Depth(4)) u_vl_to_6 (
    .clk_i,
    .en_i(en[5:2]),
    .d_i (vl_q1),
    .q_o (vl_q5)
  );
  pipe_delay #(.Width(6 * VecW), .Depth(1)) u_vl_6 (
    .clk_i,
    .en_i(en[6:6]),
    .d_i (vl_q5),
    .q_o (vl_q6)
  );
  pipe_delay #(.Width(3 * VecW), .Depth(1)) u_l_7 (
    .clk_i,
    .en_i(en[7:7]),
    .d_i (vl_q6[3*VecW+:3*VecW]),
    .q_o (l_q7)
  );
  pipe_delay #(.Width(ShinW), .Depth(9)) u_shin (
    .clk_i,
    .en_i(en[8:0]),
    .d_i (in_shin_i),
    .q_o (shin_q8)
  );
  assign l_q5 = vl_q5[3*VecW+:3*VecW];
  assign v_q6 = vl_q6[0+:3*VecW];

  // ---- Stages 0-2: N' = rq(N0 + a·(N1 - N0), np) (lirp_core: delta, prod, then N') ----
  logic [3*NpW-1:0] np_d, np_q;
  lirp_core #(
    .PFmt       (VecFmt),
    .AFmt       (AFmt),
    .OutFmt     (NpFmt),
    .OutRound   (Round),
    .OutOverflow(fx_pkg::FxSaturate)
  ) u_lirp (
    .clk_i,
    .en_i(en[1:0]),
    .p0_i(in_n0_i),
    .p1_i(in_n1_i),
    .a_i (in_a_i),
    .p_o (np_d)
  );
  always_ff @(posedge clk_i) begin
    if (en[2]) np_q <= np_d;
  end

  // ---- Stages 3-5: N = rq(g·N'_c, n), g from z = rq(N'·N', z) (lyon_norm) ----
  logic [3*NW-1:0] n_q5;
  lyon_norm #(
    .InFmt (NpFmt),
    .OutFmt(NFmt),
    .ZFmt  (ZFmt),
    .YFmt  (YFmt),
    .GFmt  (GFmt),
    .Order (Norm),
    .Round (Round)
  ) u_norm_n (
    .clk_i,
    .en_i (en[5:3]),
    .vec_i(np_q),
    .vec_o(n_q5)
  );

  // ---- Stage 6: diff = rq(N·L, diff); dot (below); N carried on ----
  logic [ DotW-1:0] dot_d, dot_q;
  logic [DiffW-1:0] diff_d, diff_q6;
  logic [ 3*NW-1:0] n_q6;
  fx_dot3 #(.AFmt(NFmt), .BFmt(VecFmt), .OutFmt(DiffFmt), .Round(Round))
      u_diff (.a_i(n_q5), .b_i(l_q5), .dot_o(diff_d));
  always_ff @(posedge clk_i) begin
    if (en[6]) begin
      dot_q   <= dot_d;
      diff_q6 <= diff_d;
      n_q6    <= n_q5;
    end
  end

  // ---- Stages 7-8: R, D ----
  logic [3*RW-1:0] r_d, r_q;
  logic [3*DW-1:0] d_d, d_q;
  always_ff @(posedge clk_i) begin
    if (en[7]) r_q <= r_d;
    if (en[8]) d_q <= d_d;
  end

  if (Halfway == 0) begin : g_reflect
    localparam bit [31:0] DotNFmt   = fx_pkg::fx_mul_fmt(DotFmt, NFmt);
    localparam bit [31:0] TwiceFmt  = fx_pkg::fx_scale_fmt(DotNFmt, 1);
    localparam bit [31:0] RExactFmt = fx_pkg::fx_sub_fmt(TwiceFmt, VecFmt);
    localparam bit [31:0] DExactFmt = fx_pkg::fx_sub_fmt(RFmt, VecFmt);
    logic [3*VecW-1:0] v_q5;
    assign v_q5 = vl_q5[0+:3*VecW];
    // Stage 6: dot = rq(N·V, dot).
    fx_dot3 #(.AFmt(NFmt), .BFmt(VecFmt), .OutFmt(DotFmt), .Round(Round))
        u_dot (.a_i(n_q5), .b_i(v_q5), .dot_o(dot_d));
    for (genvar c = 0; c < 3; c++) begin : g_comp
      logic [fx_pkg::fx_width(DotNFmt)-1:0]   dot_n;
      logic [fx_pkg::fx_width(TwiceFmt)-1:0]  twice;
      logic [fx_pkg::fx_width(RExactFmt)-1:0] r_exact;
      logic [fx_pkg::fx_width(DExactFmt)-1:0] d_exact;
      // Stage 7: R_c = rq(2·(dot·N_c) - V_c, r).
      fx_mul #(.AFmt(DotFmt), .BFmt(NFmt))
          u_dot_n (.a_i(dot_q), .b_i(n_q6[c*NW+:NW]), .prod_o(dot_n));
      fx_scale #(.AFmt(DotNFmt), .Shift(1)) u_twice (.a_i(dot_n), .scaled_o(twice));
      fx_sub #(.AFmt(TwiceFmt), .BFmt(VecFmt))
          u_r_exact (.a_i(twice), .b_i(v_q6[c*VecW+:VecW]), .delta_o(r_exact));
      fx_rq #(.InFmt(RExactFmt), .OutFmt(RFmt), .Round(Round))
          u_r (.in_i(r_exact), .out_o(r_d[c*RW+:RW]));
      // Stage 8: D_c = rq(R_c - L_c, d).
      fx_sub #(.AFmt(RFmt), .BFmt(VecFmt))
          u_d_exact (.a_i(r_q[c*RW+:RW]), .b_i(l_q7[c*VecW+:VecW]), .delta_o(d_exact));
      fx_rq #(.InFmt(DExactFmt), .OutFmt(DFmt), .Round(Round))
          u_d (.in_i(d_exact), .out_o(d_d[c*DW+:DW]));
    end
  end else begin : g_halfway
    localparam bit [31:0] LPlusVFmt = fx_pkg::fx_add_fmt(VecFmt, VecFmt);
    localparam bit [31:0] HExactFmt = fx_pkg::fx_scale_fmt(LPlusVFmt, -1);
    localparam bit [31:0] ProjFmt   = fx_pkg::fx_mul_fmt(DotFmt, NFmt);
    localparam bit [31:0] DExactFmt = fx_pkg::fx_sub_fmt(HFmt, RFmt);
    logic [3*HW-1:0]   h_d, h_q, hn_q5, hn_q6, hn_q7;
    logic [3*VecW-1:0] v_q1, l_q1;
    assign {l_q1, v_q1} = vl_q1;
    // Stage 2: H_c = rq((L_c + V_c)·2^-1, h).
    for (genvar c = 0; c < 3; c++) begin : g_h
      logic [fx_pkg::fx_width(LPlusVFmt)-1:0] l_plus_v;
      logic [fx_pkg::fx_width(HExactFmt)-1:0] h_exact;
      fx_add #(.AFmt(VecFmt), .BFmt(VecFmt))
          u_l_plus_v (.a_i(l_q1[c*VecW+:VecW]), .b_i(v_q1[c*VecW+:VecW]), .sum_o(l_plus_v));
      fx_scale #(.AFmt(LPlusVFmt), .Shift(-1)) u_h_exact (.a_i(l_plus_v), .scaled_o(h_exact));
      fx_rq #(.InFmt(HExactFmt), .OutFmt(HFmt), .Round(Round))
          u_h (.in_i(h_exact), .out_o(h_d[c*HW+:HW]));
    end
    always_ff @(posedge clk_i) begin
      if (en[2]) h_q <= h_d;
      if (en[6]) hn_q6 <= hn_q5;
      if (en[7]) hn_q7 <= hn_q6;
    end
    // Stages 3-5: H normalized like N, into h (HNorm 0: only requantized).
    lyon_norm #(
      .InFmt (HFmt),
      .OutFmt(HFmt),
      .ZFmt  (ZFmt),
      .YFmt  (YFmt),
      .GFmt  (GFmt),
      .Order (HNorm),
      .Round (Round)
    ) u_norm_h (
      .clk_i,
      .en_i (en[5:3]),
      .vec_i(h_q),
      .vec_o(hn_q5)
    );
    // Stage 6: dot = rq(H·N, dot).
    fx_dot3 #(.AFmt(HFmt), .BFmt(NFmt), .OutFmt(DotFmt), .Round(Round))
        u_dot (.a_i(hn_q5), .b_i(n_q5), .dot_o(dot_d));
    for (genvar c = 0; c < 3; c++) begin : g_comp
      logic [fx_pkg::fx_width(ProjFmt)-1:0]   proj;
      logic [fx_pkg::fx_width(DExactFmt)-1:0] d_exact;
      // Stage 7: the projection (H·N)N_c = rq(dot·N_c, r).
      fx_mul #(.AFmt(DotFmt), .BFmt(NFmt))
          u_proj (.a_i(dot_q), .b_i(n_q6[c*NW+:NW]), .prod_o(proj));
      fx_rq #(.InFmt(ProjFmt), .OutFmt(RFmt), .Round(Round))
          u_r (.in_i(proj), .out_o(r_d[c*RW+:RW]));
      // Stage 8: D_c = rq(H_c - (H·N)N_c, d).
      fx_sub #(.AFmt(HFmt), .BFmt(RFmt))
          u_d_exact (.a_i(hn_q7[c*HW+:HW]), .b_i(r_q[c*RW+:RW]), .delta_o(d_exact));
      fx_rq #(.InFmt(DExactFmt), .OutFmt(DFmt), .Round(Round))
          u_d (.in_i(d_exact), .out_o(d_d[c*DW+:DW]));
    end
    // V after stage 2 and L after stage 6 only serve the reflect variant.
    logic unused_v_l;
    assign unused_v_l = ^{l_q7, v_q6, vl_q5[0+:3*VecW]};
  end

  // ---- Stages 9-10: x/2^K as xf = rq(x/2^K, xf) and zero = (x/2^K >= 1) (lyon_x) ----
  logic [XfW-1:0] xf;
  logic           zero;
  lyon_x #(
    .Arrangement(Arrangement),
    .Halfway    (Halfway),
    .K          (K),
    .DFmt       (DFmt),
    .ShinFmt    (ShinFmt),
    .DdFmt      (DdFmt),
    .DabsFmt    (DabsFmt),
    .WFmt       (WFmt),
    .XfFmt      (XfFmt),
    .Round      (Round)
  ) u_x (
    .clk_i,
    .en_i  (en[10:9]),
    .d_i   (d_q),
    .shin_i(shin_q8),
    .xf_o  (xf),
    .zero_o(zero)
  );

  // ---- Stages 11..11+K: sq_0 = rq(1 - xf, sq), sq_j = rq(sq_(j-1)², sq);
  // spec = zero ? 0 : rq(sq_K, spec) (lyon_shape) ----
  logic [SpecW-1:0] spec;
  lyon_shape #(
    .K      (K),
    .XfFmt  (XfFmt),
    .SqFmt  (SqFmt),
    .SpecFmt(SpecFmt),
    .Round  (Round)
  ) u_shape (
    .clk_i,
    .en_i  (en[11+K:11]),
    .xf_i  (xf),
    .zero_i(zero),
    .spec_o(spec)
  );

  // diff, computed at stage 6, travels to the last stage.
  logic [DiffW-1:0] diff_last;
  pipe_delay #(.Width(DiffW), .Depth(Depth - 7)) u_diff_delay (
    .clk_i,
    .en_i(en[Depth-1:7]),
    .d_i (diff_q6),
    .q_o (diff_last)
  );

  // Side data travels through every stage.
  logic [SideW-1:0] side_last;
  pipe_delay #(.Width(SideW), .Depth(Depth)) u_side_delay (
    .clk_i,
    .en_i(en),
    .d_i (in_side_i),
    .q_o (side_last)
  );

  // ---- Output skid buffer: registers spec and diff and cuts the ready path ----
  stream_skid #(.Width(SideW + SpecW + DiffW)) u_out (
    .clk_i,
    .rst_ni,
    .in_valid_i (pipe_valid),
    .in_ready_o (pipe_ready),
    .in_data_i  ({side_last, spec, diff_last}),
    .out_valid_o,
    .out_ready_i,
    .out_data_o ({out_side_o, out_spec_o, out_diff_o})
  );

  // Assertions (simulation only): the valid/ready rules of the input (stream_check); the output
  // skid buffer checks the pipeline's stream and the output.
  stream_check #(.Width(SideW + 12 * VecW + AW + ShinW)) u_check_in (
    .clk_i,
    .rst_ni,
    .valid_i(in_valid_i),
    .ready_i(in_ready_o),
    .data_i ({in_side_i, in_shin_i, in_l_i, in_v_i, in_a_i, in_n1_i, in_n0_i})
  );

  // Assertions: elaboration-time parameter checks.
`ifndef __ICARUS__  // Icarus 11 has no elaboration-time $error
  if (Arrangement != 7 && Arrangement != 8) begin : g_bad_arrangement
    $error("lyon_core: Arrangement must be 7 or 8");
  end
  if (K > 3) begin : g_bad_k
    $error("lyon_core: K must be 0..3");
  end
`endif

endmodule
