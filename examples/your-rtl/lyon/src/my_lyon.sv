// my_lyon - Lyon's reformulated Phong specular unit (R. F. Lyon, Apple TR #43, Fig. 7) with the
// diffuse term, written from docs/lyon.md apart from phongsim's rtl/lyon, as a customer RTL team
// would bring its own unit to `phongsim cosim lyon` (docs/your-rtl.md). Port contract:
// `phongsim contract lyon`.
//
//   N' = N0 + a (N1 - N0)                 LIRP of the normals
//   z  = N'.N'   y = 1 - z   g = 1 + (y + y^2)/2 (g2) or 1 + y/2 (g1)   N = g N'
//   R  = 2 (N.V) N - V       D = R - L    x/2^k = n (D.D) / 2^(k+1)
//   spec = x/2^k >= 1 ? 0 : (1 - x/2^k)^(2^k)        diff = max(N.L, 0)
//
// Structure supported: Arrangement 7 (x from n D.D), Halfway 0 (reflect), Norm 0/1/2, K 0..3,
// every Round, any widths of the formats phongsim passes (signedness as in configs/lyon: vectors,
// N', y, N, dot, R, D signed; a, n, z, g, dd, xf, sq, spec, diff unsigned): configs/lyon's
// default, fig7_k0/k1/k3, fig7_g1, fig7_nonorm and narrow. Anything else is refused (an $error at
// elaboration, a $fatal at time 0 in simulation: see the end of the module).
//
// Pipeline: one register stage per row of docs/lyon.md's stage table (stage s holds the values
// named there; vld_q[s] says it holds a pixel), 13 + K stages, latency 13 + K cycles, one pixel
// per clock. Stage s loads when a pixel is offered to it and it is empty or some stage after it
// is empty or the output is taken (bubbles collapse under backpressure); the last stage is the
// output register, so out_valid_o and the outputs hold while out_ready_i is low. in_ready_o
// depends combinationally on out_ready_i.
//
// Registers are named after the spec's signals: delta_q, prod_q, np_q, z_q, y_q, g_q, n_q,
// dot_q, diff_q, r_q, d_q, dd_q, xf_q, zero_q, sq_0_q .. sq_3_q, spec_q; side data (n0_q, a_q,
// v_q, l_q, shin_q) is indexed by stage: v_q[s] is V of the pixel in stage s. *_d is what a
// stage register loads, *_full an exact (unrounded) intermediate (never *_x: phongsim's failure
// report reads a signal np_x as the model's x component of N'); xk is x/2^k exact, the model's
// stage of that name.
//
// Defines: MY_LYON_BUG_G2 - a deliberate bug for the failing example: g2 drops its y^2 term
// (g = 1 + y/2, i.e. g1), so g, N and everything after them differ from the model.
// MY_LYON_EXACT_W (inc/my_lyon_defs.svh) - width of the requantizer's exact word.
`include "my_lyon_defs.svh"

// sq_j = rq(sq_(j-1)^2, sq): the square is exact in SqXW bits (unsigned, frac 2 SqF).
`define MY_LYON_SQUARE(V) \
  `MY_LYON_RQ(SqW, $signed({1'b0, SqXW'(V) * SqXW'(V)}), 2 * SqF, SqFmt)

module my_lyon #(
  // Structure ([param]) and rounding ([mode] round).
  parameter bit [31:0] Arrangement = my_lyon_types::ArrangementNDD,
  parameter bit [31:0] Halfway     = 0,
  parameter bit [31:0] Norm        = my_lyon_types::NormG2,
  parameter bit [31:0] K           = 2,
  parameter bit [31:0] Round       = my_lyon_types::RoundHalfEven,
  // Formats ([format]); defaults: configs/lyon/default.toml.
  parameter bit [31:0] VecFmt      = 65802,  // S1.10  N0, N1, V, L components
  parameter bit [31:0] AFmt        = 266,    //  1.10  a
  parameter bit [31:0] ShinFmt     = 3328,   // 13.0   n
  parameter bit [31:0] NpFmt       = 65802,  // S1.10  N'
  parameter bit [31:0] ZFmt        = 268,    //  1.12  z
  parameter bit [31:0] YFmt        = 65548,  // S0.12  y
  parameter bit [31:0] GFmt        = 268,    //  1.12  g
  parameter bit [31:0] NFmt        = 65802,  // S1.10  N
  parameter bit [31:0] DotFmt      = 65804,  // S1.12  N.V
  parameter bit [31:0] RFmt        = 65802,  // S1.10  R
  parameter bit [31:0] DFmt        = 65802,  // S1.10  D
  parameter bit [31:0] DdFmt       = 787,    //  3.19  D.D
  parameter bit [31:0] XfFmt       = 16,     //  0.16  x/2^k
  parameter bit [31:0] SqFmt       = 272,    //  1.16  sq_0 .. sq_K
  parameter bit [31:0] SpecFmt     = 268,    //  1.12  spec
  parameter bit [31:0] DiffFmt     = 268,    //  1.12  diff
  // Halfway and Fig. 8 only: this unit does not implement them (checked below).
  parameter bit [31:0] HNorm       = 0,
  /* verilator lint_off UNUSEDPARAM */
  parameter bit [31:0] HFmt        = 65802,
  parameter bit [31:0] DabsFmt     = 266,
  parameter bit [31:0] WFmt        = 9,
  /* verilator lint_on UNUSEDPARAM */
  localparam int VW    = `MY_LYON_FMT_W(VecFmt),
  localparam int AW    = `MY_LYON_FMT_W(AFmt),
  localparam int ShinW = `MY_LYON_FMT_W(ShinFmt),
  localparam int SpecW = `MY_LYON_FMT_W(SpecFmt),
  localparam int DiffW = `MY_LYON_FMT_W(DiffFmt)
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              in_valid_i,
  output logic              in_ready_o,
  input  logic [3*VW-1:0]   in_n0_i,
  input  logic [3*VW-1:0]   in_n1_i,
  input  logic [  AW-1:0]   in_a_i,
  input  logic [3*VW-1:0]   in_v_i,
  input  logic [3*VW-1:0]   in_l_i,
  input  logic [ShinW-1:0]  in_shin_i,
  output logic              out_valid_o,
  input  logic              out_ready_i,
  output logic [SpecW-1:0]  out_spec_o,
  output logic [DiffW-1:0]  out_diff_o
);

  // ---------------------------------------------------------------------------------------------
  // Formats: width W and fraction bits F of every stage.
  localparam int VF    = `MY_LYON_FMT_F(VecFmt);
  localparam int AF    = `MY_LYON_FMT_F(AFmt);
  localparam int ShinF = `MY_LYON_FMT_F(ShinFmt);
  localparam int NpW   = `MY_LYON_FMT_W(NpFmt),   NpF   = `MY_LYON_FMT_F(NpFmt);
  localparam int ZW    = `MY_LYON_FMT_W(ZFmt),    ZF    = `MY_LYON_FMT_F(ZFmt);
  localparam int YW    = `MY_LYON_FMT_W(YFmt),    YF    = `MY_LYON_FMT_F(YFmt);
  localparam int GW    = `MY_LYON_FMT_W(GFmt),    GF    = `MY_LYON_FMT_F(GFmt);
  localparam int NW    = `MY_LYON_FMT_W(NFmt),    NF    = `MY_LYON_FMT_F(NFmt);
  localparam int DotW  = `MY_LYON_FMT_W(DotFmt),  DotF  = `MY_LYON_FMT_F(DotFmt);
  localparam int RW    = `MY_LYON_FMT_W(RFmt),    RF    = `MY_LYON_FMT_F(RFmt);
  localparam int DW    = `MY_LYON_FMT_W(DFmt),    DF    = `MY_LYON_FMT_F(DFmt);
  localparam int DdW   = `MY_LYON_FMT_W(DdFmt),   DdF   = `MY_LYON_FMT_F(DdFmt);
  localparam int XfW   = `MY_LYON_FMT_W(XfFmt),   XfF   = `MY_LYON_FMT_F(XfFmt);
  localparam int SqW   = `MY_LYON_FMT_W(SqFmt),   SqF   = `MY_LYON_FMT_F(SqFmt);
  localparam int SpecF = `MY_LYON_FMT_F(SpecFmt);

  // Exact intermediates: widths (the value always fits) and fraction bits.
  localparam int DeltaW = VW + 1;                  // N1 - N0                     frac VF
  localparam int ProdW  = (AW + 1) + DeltaW;       // a (N1 - N0), a as signed    frac AF + VF
  localparam int NpXW   = ProdW + 1;               // N0 + a (N1 - N0)            frac AF + VF
  localparam int ZXW    = 2 * NpW + 2;             // N'.N'                       frac 2 NpF
  localparam int YXW    = ZW + 2;                  // 1 - z                       frac ZF
  localparam int GXW    = 2 * YW + 4;              // 1 + (y + y^2)/2             frac 2 YF + 1
  localparam int NXW    = (GW + 1) + NpW;          // g N'                        frac GF + NpF
  localparam int DotXW  = NW + VW + 2;             // N.V, N.L                    frac NF + VF
  localparam int RShift = DotF + NF - VF;          // V aligned to dot N
  localparam int RXW    = DotW + NW + VW + RShift + 2;  // 2 (N.V) N - V          frac DotF + NF
  localparam int DFr    = RF > VF ? RF : VF;       // R - L                       frac DFr
  localparam int DXW    = RW + VW + DFr + 2;
  localparam int DdXW   = 2 * DW + 2;              // D.D                         frac 2 DF
  localparam int XXW    = ShinW + DdW;             // n dd 2^-(k+1) (unsigned)    frac XFr
  localparam int XFr    = ShinF + DdF + K + 1;
  localparam int Sq0XW  = XfW + 2;                 // 1 - xf                      frac XfF
  localparam int SqXW   = 2 * SqW;                 // sq_(j-1)^2 (unsigned)       frac 2 SqF

  // ---------------------------------------------------------------------------------------------
  // Pipeline control. Stages in docs/lyon.md's table order, numbered from 1 here: the table's
  // stages 0-1 are SDelta and SProd, and from N' on each number here is the table's plus one.
  localparam int SDelta = 1;   // delta = N1 - N0
  localparam int SProd  = 2;   // prod = a delta
  localparam int SNp    = 3;   // N'
  localparam int SZ     = 4;   // z
  localparam int SG     = 5;   // y, g
  localparam int SN     = 6;   // N
  localparam int SDot   = 7;   // dot, diff
  localparam int SR     = 8;   // R
  localparam int SD     = 9;   // D
  localparam int SDd    = 10;  // dd
  localparam int SXf    = 11;  // xf, zero
  localparam int SSq0   = 12;  // sq_0; sq_j in stage SSq0 + j
  localparam int SSpec  = SSq0 + K + 1;  // spec (the output register)
  localparam int NSt    = SSpec;

  logic [NSt:1] vld_q;    // stage s holds a pixel
  logic [NSt:0] offered;  // offered[s-1]: a pixel is offered to stage s
  logic [NSt:1] rdy;      // stage s may load
  logic [NSt:1] en;       // stage s loads

  assign offered = {vld_q, in_valid_i};
  for (genvar s = 1; s <= NSt; s++) begin : g_ctrl
    // Free: the output is taken, or there is an empty stage at or after s to move into.
    assign rdy[s] = out_ready_i || !(&vld_q[NSt:s]);
    assign en[s]  = rdy[s] && offered[s-1];
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      vld_q <= '0;
    end else begin
      for (int s = 1; s <= NSt; s++) begin
        if (rdy[s]) vld_q[s] <= offered[s-1];
      end
    end
  end

  assign in_ready_o  = rdy[1];
  assign out_valid_o = vld_q[NSt];

  // ---------------------------------------------------------------------------------------------
  // Side data, one register per stage that still needs it.
  logic [3*VW-1:0]  n0_q   [SDelta:SProd];  // N0 until N' is formed
  logic [AW-1:0]    a_q;                     // a, stage SDelta
  logic [3*VW-1:0]  v_q    [SDelta:SDot];   // V until R is formed
  logic [3*VW-1:0]  l_q    [SDelta:SR];     // L until D is formed
  logic [ShinW-1:0] shin_q [SDelta:SDd];    // n until x is formed

  `MY_LYON_FF(en[SDelta], n0_q[SDelta], in_n0_i)
  `MY_LYON_FF(en[SDelta], a_q, in_a_i)
  `MY_LYON_FF(en[SDelta], v_q[SDelta], in_v_i)
  `MY_LYON_FF(en[SDelta], l_q[SDelta], in_l_i)
  `MY_LYON_FF(en[SDelta], shin_q[SDelta], in_shin_i)
  for (genvar s = SDelta + 1; s <= SDd; s++) begin : g_side
    if (s <= SProd) begin : g_n0
      `MY_LYON_FF(en[s], n0_q[s], n0_q[s-1])
    end
    if (s <= SDot) begin : g_v
      `MY_LYON_FF(en[s], v_q[s], v_q[s-1])
    end
    if (s <= SR) begin : g_l
      `MY_LYON_FF(en[s], l_q[s], l_q[s-1])
    end
    `MY_LYON_FF(en[s], shin_q[s], shin_q[s-1])
  end

  // ---------------------------------------------------------------------------------------------
  // Stages SDelta, SProd, SNp: N' = rq(N0 + a (N1 - N0), np), per component.
  // 3-vectors are packed like the ports: component c in bits [c*W +: W].
  wire  [3*DeltaW-1:0] delta_d;
  logic [3*DeltaW-1:0] delta_q;
  wire  [3*ProdW-1:0]  prod_d;
  logic [3*ProdW-1:0]  prod_q;
  wire  [3*NpW-1:0]    np_d;
  logic [3*NpW-1:0]    np_q [SNp:SN-1];  // N' in stages SNp .. SN-1 (used again for N = g N')

  for (genvar c = 0; c < 3; c++) begin : g_lirp
    logic signed [NpXW-1:0] np_full;
    assign delta_d[c*DeltaW+:DeltaW] = DeltaW'($signed(in_n1_i[c*VW+:VW]))
                                     - DeltaW'($signed(in_n0_i[c*VW+:VW]));
    assign prod_d[c*ProdW+:ProdW] = $signed({1'b0, a_q}) * $signed(delta_q[c*DeltaW+:DeltaW]);
    assign np_full = (NpXW'($signed(n0_q[SProd][c*VW+:VW])) <<< AF)
                + NpXW'($signed(prod_q[c*ProdW+:ProdW]));
    assign np_d[c*NpW+:NpW] = `MY_LYON_RQ(NpW, np_full, AF + VF, NpFmt);
  end

  `MY_LYON_FF(en[SDelta], delta_q, delta_d)
  `MY_LYON_FF(en[SProd], prod_q, prod_d)
  `MY_LYON_FF(en[SNp], np_q[SNp], np_d)
  for (genvar s = SNp + 1; s < SN; s++) begin : g_np
    `MY_LYON_FF(en[s], np_q[s], np_q[s-1])
  end

  // ---------------------------------------------------------------------------------------------
  // Stages SZ, SG, SN: normalization. z = rq(N'.N', z); y = rq(1 - z, y);
  // g = rq(1 + (y + y^2)/2, g) (g2) or rq(1 + y/2, g) (g1); N = rq(g N', n).
  wire  [3*NW-1:0] n_d;
  logic [3*NW-1:0] n_q [SN:SDot];  // N in stages SN (for dot, diff) and SDot (for R)

  if (Norm != my_lyon_types::NormNone) begin : g_norm
    wire  [ZXW-1:0] z_full;
    wire  [ZW-1:0]  z_d;
    logic [ZW-1:0]  z_q;
    logic signed [YXW-1:0]  y_full;
    wire  [YW-1:0]  y_d;
    logic [YW-1:0]  y_q;  // kept for the waveform, next to g
    logic signed [GXW-1:0]  g_full;
    wire  [GW-1:0]  g_d;
    logic [GW-1:0]  g_q;
    localparam int GFr = Norm == my_lyon_types::NormG1 ? YF + 1 : 2 * YF + 1;

    // Array words go to submodule ports through plain wires: Yosys 0.23 defers a module that
    // connects a memory word to a port and re-derives it under a $paramod name.
    wire [3*NpW-1:0] np_at_z;
    assign np_at_z = np_q[SNp];
    my_lyon_dot3 #(.AW(NpW), .BW(NpW)) u_z (.a_i(np_at_z), .b_i(np_at_z), .sum_o(z_full));
    assign z_d  = `MY_LYON_RQ(ZW, $signed(z_full), 2 * NpF, ZFmt);

    assign y_full  = (YXW'(1) <<< ZF) - $signed({2'b00, z_q});
    assign y_d  = `MY_LYON_RQ(YW, y_full, ZF, YFmt);
    if (Norm == my_lyon_types::NormG1) begin : g_g1
      assign g_full = (GXW'(1) <<< (YF + 1)) + GXW'($signed(y_d));
    end else begin : g_g2
`ifdef MY_LYON_BUG_G2
      // BUG (deliberate): the y^2 term is dropped, g = 1 + y/2.
      assign g_full = (GXW'(1) <<< (2 * YF + 1)) + (GXW'($signed(y_d)) <<< YF);
`else
      logic signed [2*YW-1:0] yy_full;  // y^2, frac 2 YF
      assign yy_full = $signed(y_d) * $signed(y_d);
      assign g_full  = (GXW'(1) <<< (2 * YF + 1)) + (GXW'($signed(y_d)) <<< YF) + GXW'(yy_full);
`endif
    end
    assign g_d = `MY_LYON_RQ(GW, g_full, GFr, GFmt);

    `MY_LYON_FF(en[SZ], z_q, z_d)
    `MY_LYON_FF(en[SG], y_q, y_d)
    `MY_LYON_FF(en[SG], g_q, g_d)

    for (genvar c = 0; c < 3; c++) begin : g_n
      logic signed [NXW-1:0] n_full;
      assign n_full = $signed({1'b0, g_q}) * $signed(np_q[SN-1][c*NpW+:NpW]);
      assign n_d[c*NW+:NW] = `MY_LYON_RQ(NW, n_full, GF + NpF, NFmt);
    end

    // y_q only shows y in a waveform; a hardware team would let synthesis remove it.
    logic unused_y;
    assign unused_y = ^y_q;
  end else begin : g_no_norm
    for (genvar c = 0; c < 3; c++) begin : g_n
      assign n_d[c*NW+:NW] = `MY_LYON_RQ(NW, $signed(np_q[SN-1][c*NpW+:NpW]), NpF, NFmt);
    end
  end

  `MY_LYON_FF(en[SN], n_q[SN], n_d)
  `MY_LYON_FF(en[SDot], n_q[SDot], n_q[SN])

  // ---------------------------------------------------------------------------------------------
  // Stage SDot: dot = rq(N.V, dot); diff = rq(N.L, diff) (unsigned: negative saturates to 0).
  wire  [DotXW-1:0] dot_full, diff_full;
  wire  [DotW-1:0]  dot_d;
  logic [DotW-1:0]  dot_q;
  wire  [DiffW-1:0] diff_d;
  logic [DiffW-1:0] diff_q [SDot:NSt];  // the diffuse term rides along to the output

  wire  [3*NW-1:0] n_at_dot;
  wire  [3*VW-1:0] v_at_dot, l_at_dot;
  assign n_at_dot = n_q[SN];
  assign v_at_dot = v_q[SN];
  assign l_at_dot = l_q[SN];
  my_lyon_dot3 #(.AW(NW), .BW(VW)) u_dot (.a_i(n_at_dot), .b_i(v_at_dot), .sum_o(dot_full));
  my_lyon_dot3 #(.AW(NW), .BW(VW)) u_diff (.a_i(n_at_dot), .b_i(l_at_dot), .sum_o(diff_full));
  assign dot_d  = `MY_LYON_RQ(DotW, $signed(dot_full), NF + VF, DotFmt);
  assign diff_d = `MY_LYON_RQ(DiffW, $signed(diff_full), NF + VF, DiffFmt);

  `MY_LYON_FF(en[SDot], dot_q, dot_d)
  `MY_LYON_FF(en[SDot], diff_q[SDot], diff_d)
  for (genvar s = SDot + 1; s <= NSt; s++) begin : g_diff
    `MY_LYON_FF(en[s], diff_q[s], diff_q[s-1])
  end

  // ---------------------------------------------------------------------------------------------
  // Stages SR, SD: R = rq(2 (N.V) N - V, r); D = rq(R - L, d), per component.
  wire  [3*RW-1:0] r_d;
  logic [3*RW-1:0] r_q;
  wire  [3*DW-1:0] d_d;
  logic [3*DW-1:0] d_q;

  for (genvar c = 0; c < 3; c++) begin : g_reflect
    logic signed [DotW+NW-1:0] dn_full;  // (N.V) N_c, frac DotF + NF
    logic signed [RXW-1:0]     r_full;
    logic signed [DXW-1:0]     d_full;
    assign dn_full = $signed(dot_q) * $signed(n_q[SDot][c*NW+:NW]);
    assign r_full  = (RXW'(dn_full) <<< 1) - (RXW'($signed(v_q[SDot][c*VW+:VW])) <<< RShift);
    assign r_d[c*RW+:RW] = `MY_LYON_RQ(RW, r_full, DotF + NF, RFmt);
    assign d_full  = (DXW'($signed(r_q[c*RW+:RW])) <<< (DFr - RF))
                - (DXW'($signed(l_q[SR][c*VW+:VW])) <<< (DFr - VF));
    assign d_d[c*DW+:DW] = `MY_LYON_RQ(DW, d_full, DFr, DFmt);
  end

  `MY_LYON_FF(en[SR], r_q, r_d)
  `MY_LYON_FF(en[SD], d_q, d_d)

  // ---------------------------------------------------------------------------------------------
  // Stages SDd, SXf: dd = rq(D.D, dd); x/2^k = n dd 2^-(k+1) exact; zero = (x/2^k >= 1);
  // xf = rq(x/2^k, xf).
  wire  [DdXW-1:0] dd_full;
  wire  [DdW-1:0]  dd_d;
  logic [DdW-1:0]  dd_q;
  logic [XXW-1:0]  xk;
  wire  [XfW-1:0]  xf_d;
  logic [XfW-1:0]  xf_q;
  logic            zero_d;
  logic [NSt:SXf]  zero_q;  // spec is forced to 0 at the output

  my_lyon_dot3 #(.AW(DW), .BW(DW)) u_dd (.a_i(d_q), .b_i(d_q), .sum_o(dd_full));
  assign dd_d   = `MY_LYON_RQ(DdW, $signed(dd_full), 2 * DF, DdFmt);

  assign xk    = shin_q[SDd] * dd_q;
  assign zero_d = (xk >> XFr) != '0;
  assign xf_d   = `MY_LYON_RQ(XfW, $signed({1'b0, xk}), XFr, XfFmt);

  `MY_LYON_FF(en[SDd], dd_q, dd_d)
  `MY_LYON_FF(en[SXf], xf_q, xf_d)
  `MY_LYON_FF(en[SXf], zero_q[SXf], zero_d)
  for (genvar s = SXf + 1; s <= NSt; s++) begin : g_zero
    `MY_LYON_FF(en[s], zero_q[s], zero_q[s-1])
  end

  // ---------------------------------------------------------------------------------------------
  // Stages SSq0 .. SSq0 + K: sq_0 = rq(1 - xf, sq); sq_j = rq(sq_(j-1)^2, sq).
  // Output stage: spec = zero ? 0 : rq(sq_K, spec).
  logic [SqW-1:0] sq_0_q, sq_1_q, sq_2_q, sq_3_q;  // sq_j in stage SSq0 + j; 0 for j > K
  logic signed [Sq0XW-1:0] sq0_full;
  wire  [SqW-1:0]   sq_0_d, sq_k;
  wire  [SpecW-1:0] spec_d;
  logic [SpecW-1:0] spec_q;

  assign sq0_full = (Sq0XW'(1) <<< XfF) - $signed({2'b00, xf_q});
  assign sq_0_d   = `MY_LYON_RQ(SqW, sq0_full, XfF, SqFmt);
  `MY_LYON_FF(en[SSq0], sq_0_q, sq_0_d)

  if (K >= 1) begin : g_sq_1
    wire [SqW-1:0] sq_1_d;
    assign sq_1_d = `MY_LYON_SQUARE(sq_0_q);
    `MY_LYON_FF(en[SSq0+1], sq_1_q, sq_1_d)
  end else begin : g_no_sq_1
    assign sq_1_q = '0;
  end
  if (K >= 2) begin : g_sq_2
    wire [SqW-1:0] sq_2_d;
    assign sq_2_d = `MY_LYON_SQUARE(sq_1_q);
    `MY_LYON_FF(en[SSq0+2], sq_2_q, sq_2_d)
  end else begin : g_no_sq_2
    assign sq_2_q = '0;
  end
  if (K >= 3) begin : g_sq_3
    wire [SqW-1:0] sq_3_d;
    assign sq_3_d = `MY_LYON_SQUARE(sq_2_q);
    `MY_LYON_FF(en[SSq0+3], sq_3_q, sq_3_d)
  end else begin : g_no_sq_3
    assign sq_3_q = '0;
  end
  assign sq_k = K == 0 ? sq_0_q : K == 1 ? sq_1_q : K == 2 ? sq_2_q : sq_3_q;

  assign spec_d = zero_q[SSpec-1] ? '0
                : `MY_LYON_RQ(SpecW, $signed({1'b0, sq_k}), SqF, SpecFmt);
  `MY_LYON_FF(en[SSpec], spec_q, spec_d)

  assign out_spec_o = spec_q;
  assign out_diff_o = diff_q[NSt];

  // ---------------------------------------------------------------------------------------------
  // What this unit does not implement. Each check twice: as an elaboration-time $error (Yosys
  // stops on it; Verilator 5.006 only warns, and Icarus 11 has none) and as a $fatal at time 0
  // (stops a Verilator or Icarus simulation, so phongsim fails the run instead of reporting
  // mismatches; not for synthesis, where Yosys cannot run it).
  localparam bit BadArrangement = Arrangement != my_lyon_types::ArrangementNDD;
  localparam bit BadHalfway     = Halfway != 0 || HNorm != 0;
  localparam bit BadNorm        = Norm > my_lyon_types::NormG2;
  localparam bit BadK           = K > 3;
  localparam bit BadRound       = Round > my_lyon_types::RoundHalfEven;
  localparam bit BadSigned      = `MY_LYON_FMT_S(VecFmt) != 1 || `MY_LYON_FMT_S(NpFmt) != 1
      || `MY_LYON_FMT_S(NFmt) != 1 || `MY_LYON_FMT_S(DotFmt) != 1 || `MY_LYON_FMT_S(RFmt) != 1
      || `MY_LYON_FMT_S(DFmt) != 1 || (Norm != 0 && `MY_LYON_FMT_S(YFmt) != 1);
  localparam bit BadUnsigned    = `MY_LYON_FMT_S(AFmt) != 0 || `MY_LYON_FMT_S(ShinFmt) != 0
      || `MY_LYON_FMT_S(DdFmt) != 0 || `MY_LYON_FMT_S(XfFmt) != 0 || `MY_LYON_FMT_S(SqFmt) != 0
      || (Norm != 0 && (`MY_LYON_FMT_S(ZFmt) != 0 || `MY_LYON_FMT_S(GFmt) != 0));
  localparam bit BadDot         = RShift < 0;
  // Every exact value, aligned to its output's binary point, must fit the exact word.
  localparam bit BadExactW      = XXW + 2 + XfF > `MY_LYON_EXACT_W
      || RXW + 2 + RF > `MY_LYON_EXACT_W || SqXW + 2 + SpecF > `MY_LYON_EXACT_W
      || NpXW + 2 + NpF > `MY_LYON_EXACT_W || DdXW + 2 + DdF > `MY_LYON_EXACT_W;

`define MY_LYON_MSG_ARRANGEMENT "my_lyon: only Arrangement 7 (x from n D.D) is implemented"
`define MY_LYON_MSG_HALFWAY "my_lyon: only Halfway 0 (R = 2 (N.V) N - V, HNorm 0) is implemented"
`define MY_LYON_MSG_NORM "my_lyon: Norm must be 0, 1 or 2"
`define MY_LYON_MSG_K "my_lyon: K must be 0..3"
`define MY_LYON_MSG_ROUND "my_lyon: Round must be 0, 1 or 2"
`define MY_LYON_MSG_SIGNED "my_lyon: vec, np, y, n, dot, r and d must be signed formats"
`define MY_LYON_MSG_UNSIGNED "my_lyon: a, shin, z, g, dd, xf and sq must be unsigned formats"
`define MY_LYON_MSG_DOT "my_lyon: dot and n together need at least as many fraction bits as vec"
`define MY_LYON_MSG_EXACT_W "my_lyon: these formats need a wider MY_LYON_EXACT_W"

`ifndef __ICARUS__
  if (BadArrangement) begin : g_bad_arrangement
    $error(`MY_LYON_MSG_ARRANGEMENT);
  end
  if (BadHalfway) begin : g_bad_halfway
    $error(`MY_LYON_MSG_HALFWAY);
  end
  if (BadNorm) begin : g_bad_norm
    $error(`MY_LYON_MSG_NORM);
  end
  if (BadK) begin : g_bad_k
    $error(`MY_LYON_MSG_K);
  end
  if (BadRound) begin : g_bad_round
    $error(`MY_LYON_MSG_ROUND);
  end
  if (BadSigned) begin : g_bad_signed
    $error(`MY_LYON_MSG_SIGNED);
  end
  if (BadUnsigned) begin : g_bad_unsigned
    $error(`MY_LYON_MSG_UNSIGNED);
  end
  if (BadDot) begin : g_bad_dot
    $error(`MY_LYON_MSG_DOT);
  end
  if (BadExactW) begin : g_bad_exact_w
    $error(`MY_LYON_MSG_EXACT_W);
  end
`endif

`ifndef SYNTHESIS
  initial begin
    if (BadArrangement) $fatal(1, `MY_LYON_MSG_ARRANGEMENT);
    if (BadHalfway) $fatal(1, `MY_LYON_MSG_HALFWAY);
    if (BadNorm) $fatal(1, `MY_LYON_MSG_NORM);
    if (BadK) $fatal(1, `MY_LYON_MSG_K);
    if (BadRound) $fatal(1, `MY_LYON_MSG_ROUND);
    if (BadSigned) $fatal(1, `MY_LYON_MSG_SIGNED);
    if (BadUnsigned) $fatal(1, `MY_LYON_MSG_UNSIGNED);
    if (BadDot) $fatal(1, `MY_LYON_MSG_DOT);
    if (BadExactW) $fatal(1, `MY_LYON_MSG_EXACT_W);
  end
`endif

endmodule
