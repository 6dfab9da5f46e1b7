// lirp_unit: linear interpolation of 3-component vectors, p = (1 - a)·p0 + a·p1, the "LIRP" of
// Lyon, TR #43, Fig. 7a (N' = LIRP(N0, N1, a)). Computed as p0 + a·(p1 - p0), which equals
// Lyon's two-multiplier form exactly before the one rounding at the output ("an equivalent
// linear interpolation hardware structure might merge the subtraction and two multipliers").
// Numerical specification: docs/lirp.md.
//
//   stage diff:  diff = p1 - p0                     exact, fx_sub_fmt(P, P)
//   stage prod:  prod = a · diff                    exact, fx_mul_fmt(A, Diff)
//   stage out:   p    = resize(p0 + prod, Out)      OutRound, OutOverflow
//
// Latency 3 cycles, throughput 1 transaction per clock; valid/ready with backpressure.
// Parameters: PFmt, AFmt, OutFmt - format words (fx_pkg::fx_fmt) of p0/p1 components, a, and p
//             components; OutRound, OutOverflow - fx_pkg modes of the output requantization.
// Ports: clk_i, rst_ni - clock, asynchronous active-low reset;
//        in_valid_i, in_ready_o, in_p0_i, in_p1_i, in_a_i - input stream; vectors are packed
//        x, y, z from the least significant end (component c at [c*PW +: PW]);
//        out_valid_o, out_ready_i, out_p_o - output stream, packed the same way.
module lirp_unit #(
  parameter int unsigned PFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned AFmt        = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter int unsigned OutFmt      = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned OutRound    = fx_pkg::FxHalfEven,
  parameter int unsigned OutOverflow = fx_pkg::FxSaturate,
  // Derived, do not override.
  localparam int unsigned PW         = fx_pkg::fx_width(PFmt),
  localparam int unsigned AW         = fx_pkg::fx_width(AFmt),
  localparam int unsigned OutW       = fx_pkg::fx_width(OutFmt)
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic            in_valid_i,
  output logic            in_ready_o,
  input  logic [3*PW-1:0] in_p0_i,
  input  logic [3*PW-1:0] in_p1_i,
  input  logic [  AW-1:0] in_a_i,
  output logic              out_valid_o,
  input  logic              out_ready_i,
  output logic [3*OutW-1:0] out_p_o
);

  localparam int unsigned DiffFmt = fx_pkg::fx_sub_fmt(PFmt, PFmt);
  localparam int unsigned ProdFmt = fx_pkg::fx_mul_fmt(AFmt, DiffFmt);
  localparam int unsigned SumFmt  = fx_pkg::fx_add_fmt(PFmt, ProdFmt);
  localparam int unsigned DiffW   = fx_pkg::fx_width(DiffFmt);
  localparam int unsigned ProdW   = fx_pkg::fx_width(ProdFmt);
  localparam int unsigned SumW    = fx_pkg::fx_width(SumFmt);

  // ---- Stage diff: diff = p1 - p0 ----
  logic [3*DiffW-1:0] diff_d, diff_q;
  logic [   3*PW-1:0] p0_q, p0_q2;
  logic [     AW-1:0] a_q;
  logic               diff_valid_q, diff_ready;

  for (genvar c = 0; c < 3; c++) begin : g_diff
    fx_sub #(.AFmt(PFmt), .BFmt(PFmt)) u_sub (
      .a_i   (in_p1_i[c*PW+:PW]),
      .b_i   (in_p0_i[c*PW+:PW]),
      .diff_o(diff_d[c*DiffW+:DiffW])
    );
  end

  stream_register #(.Width(3 * PW + AW + 3 * DiffW)) u_stage_diff (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .in_data_i  ({in_p0_i, in_a_i, diff_d}),
    .out_valid_o(diff_valid_q),
    .out_ready_i(diff_ready),
    .out_data_o ({p0_q, a_q, diff_q})
  );

  // ---- Stage prod: prod = a * diff ----
  logic [3*ProdW-1:0] prod_d, prod_q;
  logic               prod_valid_q, prod_ready;

  for (genvar c = 0; c < 3; c++) begin : g_prod
    fx_mul #(.AFmt(AFmt), .BFmt(DiffFmt)) u_mul (
      .a_i   (a_q),
      .b_i   (diff_q[c*DiffW+:DiffW]),
      .prod_o(prod_d[c*ProdW+:ProdW])
    );
  end

  stream_register #(.Width(3 * PW + 3 * ProdW)) u_stage_prod (
    .clk_i,
    .rst_ni,
    .in_valid_i (diff_valid_q),
    .in_ready_o (diff_ready),
    .in_data_i  ({p0_q, prod_d}),
    .out_valid_o(prod_valid_q),
    .out_ready_i(prod_ready),
    .out_data_o ({p0_q2, prod_q})
  );

  // ---- Stage out: p = resize(p0 + prod) ----
  logic [3*OutW-1:0] p_d;

  for (genvar c = 0; c < 3; c++) begin : g_out
    logic [SumW-1:0] sum;
    fx_add #(.AFmt(PFmt), .BFmt(ProdFmt)) u_add (
      .a_i  (p0_q2[c*PW+:PW]),
      .b_i  (prod_q[c*ProdW+:ProdW]),
      .sum_o(sum)
    );
    fx_resize #(
      .InFmt   (SumFmt),
      .OutFmt  (OutFmt),
      .Round   (OutRound),
      .Overflow(OutOverflow)
    ) u_round (
      .in_i (sum),
      .out_o(p_d[c*OutW+:OutW])
    );
  end

  // The skid buffer registers the output and cuts the ready path from out_ready_i.
  stream_skid #(.Width(3 * OutW)) u_stage_out (
    .clk_i,
    .rst_ni,
    .in_valid_i (prod_valid_q),
    .in_ready_o (prod_ready),
    .in_data_i  (p_d),
    .out_valid_o,
    .out_ready_i,
    .out_data_o (out_p_o)
  );

  // Assertions (simulation only): an offered output stays valid and unchanged until taken.
`ifndef SYNTHESIS
  logic             stalled_q;
  logic [3*OutW-1:0] stalled_p_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      stalled_q <= 1'b0;
    end else begin
      stalled_q <= out_valid_o & ~out_ready_i;
    end
  end
  always_ff @(posedge clk_i) begin
    stalled_p_q <= out_p_o;
  end
  always_comb begin
    if (stalled_q) begin
      assert (out_valid_o && out_p_o == stalled_p_q)
      else $error("lirp_unit: output changed or dropped while stalled");
    end
  end
`endif

endmodule
