// lyon_top: Lyon's reformulated Phong specular unit with the diffuse term (Lyon, TR #43,
// Figs. 6-8), one pixel per clock, valid/ready with backpressure.
//
//   N' = LIRP(N0, N1, a); N = g(N'·N')·N'                           Fig. 7a (g: none, g1, g2)
//   reflect (Halfway = 0):  R = 2(N·V)N - V;  D = R - L             Fig. 7b, 7c
//   halfway (Halfway = 1):  H = (L + V)/2 (optionally g-normalized);
//                           D = H - (H·N)N, shininess n -> 4n       "The Half-way Vector Approach"
//   x/2^K from D and n (Arrangement 7) or m = sqrt(n) (Arrangement 8) Fig. 7c / Fig. 8
//   spec = f_K(x) = (1 - x/2^K)^(2^K), 0 when x/2^K >= 1             Fig. 7d
//   diff = max(N·L, 0)
//
// Stages (pipe_ctrl, Depth = 12 + K), then an output skid buffer; latency 13 + K cycles:
//   0-1 LIRP (lirp_core) | 2 N' (and H) | 3-5 normalization (lyon_norm) | 6 dot products |
//   7 R or projection | 8 D | 9-10 x (lyon_x) | 11.. shape (lyon_shape: t, K squarings)
// Every requantization rounds with Round and saturates. Specification: docs/lyon.md.
//
// Parameters (formats are fx_pkg format words; the configuration key is in brackets):
//   Arrangement [arrangement] 7 or 8; Halfway [halfway] 0/1; Norm [norm] 0/1/2 for N;
//   HNorm [h_norm] 0/1/2 for H; K [k] 0..3; Round [round];
//   VecFmt [vec] N0, N1, V, L components; AFmt [a]; ShinFmt [shin] n or m;
//   NpFmt [np] N'; ZFmt [z], YFmt [y], GFmt [g] normalization; NFmt [n] N; HFmt [h] H;
//   DotFmt [dot] N·V or H·N; RFmt [r] R or (H·N)N; DFmt [d] D; DdFmt [dd] D·D (7);
//   DabsFmt [dabs] |D| and WFmt [w] squarer inputs (8); XfFmt [xf] x/2^K; SqFmt [sq] squarers;
//   SpecFmt [spec], DiffFmt [diff] outputs.
// Ports: clk_i, rst_ni (asynchronous, active low); in_valid_i, in_ready_o, in_n0_i, in_n1_i,
//        in_a_i, in_v_i, in_l_i, in_shin_i (vectors packed x, y, z from the LSB);
//        out_valid_o, out_ready_i, out_spec_o, out_diff_o.
module lyon_top #(
  parameter int unsigned Arrangement = 7,
  parameter int unsigned Halfway     = 0,
  parameter int unsigned Norm        = 2,
  parameter int unsigned HNorm       = 0,
  parameter int unsigned K           = 2,
  parameter int unsigned Round       = fx_pkg::FxHalfEven,
  parameter int unsigned VecFmt      = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned AFmt        = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter int unsigned ShinFmt     = fx_pkg::fx_fmt(1'b0, 13, 0),
  parameter int unsigned NpFmt       = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned ZFmt        = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter int unsigned YFmt        = fx_pkg::fx_fmt(1'b1, 0, 12),
  parameter int unsigned GFmt        = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter int unsigned NFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned HFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned DotFmt      = fx_pkg::fx_fmt(1'b1, 1, 12),
  parameter int unsigned RFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned DFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned DdFmt       = fx_pkg::fx_fmt(1'b0, 3, 19),
  parameter int unsigned DabsFmt     = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter int unsigned WFmt        = fx_pkg::fx_fmt(1'b0, 0, 9),
  parameter int unsigned XfFmt       = fx_pkg::fx_fmt(1'b0, 0, 16),
  parameter int unsigned SqFmt       = fx_pkg::fx_fmt(1'b0, 1, 16),
  parameter int unsigned SpecFmt     = fx_pkg::fx_fmt(1'b0, 1, 12),
  parameter int unsigned DiffFmt     = fx_pkg::fx_fmt(1'b0, 1, 12),
  // Derived, do not override.
  localparam int unsigned VecW       = fx_pkg::fx_width(VecFmt),
  localparam int unsigned AW         = fx_pkg::fx_width(AFmt),
  localparam int unsigned ShinW      = fx_pkg::fx_width(ShinFmt),
  localparam int unsigned SpecW      = fx_pkg::fx_width(SpecFmt),
  localparam int unsigned DiffW      = fx_pkg::fx_width(DiffFmt)
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
  output logic              out_valid_o,
  input  logic              out_ready_i,
  output logic [ SpecW-1:0] out_spec_o,
  output logic [ DiffW-1:0] out_diff_o
);

  localparam int unsigned Depth = 12 + K;
  localparam int unsigned NpW   = fx_pkg::fx_width(NpFmt);
  localparam int unsigned NW    = fx_pkg::fx_width(NFmt);
  localparam int unsigned HW    = fx_pkg::fx_width(HFmt);
  localparam int unsigned DotW  = fx_pkg::fx_width(DotFmt);
  localparam int unsigned RW    = fx_pkg::fx_width(RFmt);
  localparam int unsigned DW    = fx_pkg::fx_width(DFmt);
  localparam int unsigned XfW   = fx_pkg::fx_width(XfFmt);

  // ---- Control ----
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

  // ---- Side data: V and L (for H at stage 2, the dots at 6, R at 7, D at 8), shininess ----
  logic [6*VecW-1:0] vl_q1, vl_q5, vl_q6;
  logic [3*VecW-1:0] l_q7;
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

  // ---- Stages 0-2: N' = LIRP(N0, N1, a) ----
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

  // ---- Stages 3-5: N = g(N'·N')·N' ----
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

  // ---- Stage 6: dot products (and N carried on) ----
  logic [ DotW-1:0] dot_d, dot_q;
  logic [DiffW-1:0] diff_d, diff_q6;
  logic [ 3*NW-1:0] n_q6;
  lyon_dot3 #(.AFmt(NFmt), .BFmt(VecFmt), .OutFmt(DiffFmt), .Round(Round)) u_diffuse (
    .a_i  (n_q5),
    .b_i  (vl_q5[3*VecW+:3*VecW]),
    .dot_o(diff_d)
  );
  always_ff @(posedge clk_i) begin
    if (en[6]) begin
      dot_q   <= dot_d;
      diff_q6 <= diff_d;
      n_q6    <= n_q5;
    end
  end

  // ---- Stages 7-8: D ----
  logic [3*RW-1:0] r_d, r_q;
  logic [3*DW-1:0] d_d, d_q;
  always_ff @(posedge clk_i) begin
    if (en[7]) r_q <= r_d;
    if (en[8]) d_q <= d_d;
  end

  if (Halfway == 0) begin : g_reflect
    localparam int unsigned DotNFmt = fx_pkg::fx_mul_fmt(DotFmt, NFmt);
    localparam int unsigned TwiceFmt = fx_pkg::fx_scale_fmt(DotNFmt, 1);
    localparam int unsigned RExactFmt = fx_pkg::fx_sub_fmt(TwiceFmt, VecFmt);
    localparam int unsigned DExactFmt = fx_pkg::fx_sub_fmt(RFmt, VecFmt);
    // Stage 6: N·V.
    lyon_dot3 #(.AFmt(NFmt), .BFmt(VecFmt), .OutFmt(DotFmt), .Round(Round)) u_dot (
      .a_i  (n_q5),
      .b_i  (vl_q5[0+:3*VecW]),
      .dot_o(dot_d)
    );
    for (genvar c = 0; c < 3; c++) begin : g_comp
      // Stage 7: R = 2(N·V)N - V.
      logic [fx_pkg::fx_width(DotNFmt)-1:0] dot_n;
      logic [fx_pkg::fx_width(TwiceFmt)-1:0] twice;
      logic [fx_pkg::fx_width(RExactFmt)-1:0] r_exact;
      fx_mul #(.AFmt(DotFmt), .BFmt(NFmt)) u_dot_n (
        .a_i   (dot_q),
        .b_i   (n_q6[c*NW+:NW]),
        .prod_o(dot_n)
      );
      fx_scale #(.AFmt(DotNFmt), .Shift(1)) u_twice (
        .a_i     (dot_n),
        .scaled_o(twice)
      );
      fx_sub #(.AFmt(TwiceFmt), .BFmt(VecFmt)) u_r (
        .a_i   (twice),
        .b_i   (vl_q6[c*VecW+:VecW]),
        .diff_o(r_exact)
      );
      fx_resize #(
        .InFmt   (RExactFmt),
        .OutFmt  (RFmt),
        .Round   (Round),
        .Overflow(fx_pkg::FxSaturate)
      ) u_r_round (
        .in_i (r_exact),
        .out_o(r_d[c*RW+:RW])
      );
      // Stage 8: D = R - L.
      logic [fx_pkg::fx_width(DExactFmt)-1:0] d_exact;
      fx_sub #(.AFmt(RFmt), .BFmt(VecFmt)) u_d (
        .a_i   (r_q[c*RW+:RW]),
        .b_i   (l_q7[c*VecW+:VecW]),
        .diff_o(d_exact)
      );
      fx_resize #(
        .InFmt   (DExactFmt),
        .OutFmt  (DFmt),
        .Round   (Round),
        .Overflow(fx_pkg::FxSaturate)
      ) u_d_round (
        .in_i (d_exact),
        .out_o(d_d[c*DW+:DW])
      );
    end
  end else begin : g_halfway
    localparam int unsigned SumFmt = fx_pkg::fx_add_fmt(VecFmt, VecFmt);
    localparam int unsigned HalfFmt = fx_pkg::fx_scale_fmt(SumFmt, -1);
    localparam int unsigned ProjFmt = fx_pkg::fx_mul_fmt(DotFmt, NFmt);
    localparam int unsigned DExactFmt = fx_pkg::fx_sub_fmt(HFmt, RFmt);
    logic [3*HW-1:0] h_d, h_q, hn_q5, hn_q6, hn_q7;
    // Stage 2: H = (L + V)/2.
    for (genvar c = 0; c < 3; c++) begin : g_h
      logic [fx_pkg::fx_width(SumFmt)-1:0] sum;
      logic [fx_pkg::fx_width(HalfFmt)-1:0] half;
      fx_add #(.AFmt(VecFmt), .BFmt(VecFmt)) u_sum (
        .a_i  (vl_q1[3*VecW+c*VecW+:VecW]),
        .b_i  (vl_q1[c*VecW+:VecW]),
        .sum_o(sum)
      );
      fx_scale #(.AFmt(SumFmt), .Shift(-1)) u_half (
        .a_i     (sum),
        .scaled_o(half)
      );
      fx_resize #(
        .InFmt   (HalfFmt),
        .OutFmt  (HFmt),
        .Round   (Round),
        .Overflow(fx_pkg::FxSaturate)
      ) u_h_round (
        .in_i (half),
        .out_o(h_d[c*HW+:HW])
      );
    end
    always_ff @(posedge clk_i) begin
      if (en[2]) h_q <= h_d;
      if (en[6]) hn_q6 <= hn_q5;
      if (en[7]) hn_q7 <= hn_q6;
    end
    // Stages 3-5: H normalized like N (HNorm 0: only requantized).
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
    // Stage 6: H·N.
    lyon_dot3 #(.AFmt(HFmt), .BFmt(NFmt), .OutFmt(DotFmt), .Round(Round)) u_dot (
      .a_i  (hn_q5),
      .b_i  (n_q5),
      .dot_o(dot_d)
    );
    for (genvar c = 0; c < 3; c++) begin : g_comp
      // Stage 7: the projection (H·N)N.
      logic [fx_pkg::fx_width(ProjFmt)-1:0] proj;
      fx_mul #(.AFmt(DotFmt), .BFmt(NFmt)) u_proj (
        .a_i   (dot_q),
        .b_i   (n_q6[c*NW+:NW]),
        .prod_o(proj)
      );
      fx_resize #(
        .InFmt   (ProjFmt),
        .OutFmt  (RFmt),
        .Round   (Round),
        .Overflow(fx_pkg::FxSaturate)
      ) u_proj_round (
        .in_i (proj),
        .out_o(r_d[c*RW+:RW])
      );
      // Stage 8: D = H - (H·N)N.
      logic [fx_pkg::fx_width(DExactFmt)-1:0] d_exact;
      fx_sub #(.AFmt(HFmt), .BFmt(RFmt)) u_d (
        .a_i   (hn_q7[c*HW+:HW]),
        .b_i   (r_q[c*RW+:RW]),
        .diff_o(d_exact)
      );
      fx_resize #(
        .InFmt   (DExactFmt),
        .OutFmt  (DFmt),
        .Round   (Round),
        .Overflow(fx_pkg::FxSaturate)
      ) u_d_round (
        .in_i (d_exact),
        .out_o(d_d[c*DW+:DW])
      );
    end
    // V and L after stage 6 only serve the reflect variant.
    logic unused_v_l;
    assign unused_v_l = ^{l_q7, vl_q6[0+:3*VecW]};
  end

  // ---- Stages 9-10: x/2^K ----
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

  // ---- Stages 11..11+K: f_K ----
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

  // Diffuse, computed at stage 6, travels to the last stage.
  logic [DiffW-1:0] diff_last;
  pipe_delay #(.Width(DiffW), .Depth(Depth - 7)) u_diff (
    .clk_i,
    .en_i(en[Depth-1:7]),
    .d_i (diff_q6),
    .q_o (diff_last)
  );

  // ---- Output skid buffer: registers the outputs and cuts the ready path ----
  stream_skid #(.Width(SpecW + DiffW)) u_out (
    .clk_i,
    .rst_ni,
    .in_valid_i (pipe_valid),
    .in_ready_o (pipe_ready),
    .in_data_i  ({spec, diff_last}),
    .out_valid_o,
    .out_ready_i,
    .out_data_o ({out_spec_o, out_diff_o})
  );

  // Assertions: elaboration-time parameter checks.
  if (Arrangement != 7 && Arrangement != 8) begin : g_bad_arrangement
    $error("lyon_top: Arrangement must be 7 or 8");
  end
  if (K > 3) begin : g_bad_k
    $error("lyon_top: K must be 0..3");
  end

endmodule
