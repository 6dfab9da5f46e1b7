// lirp_core: the LIRP datapath, p = (1 - a)·p0 + a·p1 on 3-component vectors (Lyon, TR #43,
// Fig. 7a), computed as p0 + a·(p1 - p0) with one rounding at the end; exact before it, so equal
// to Lyon's two-multiplier form. Specification: docs/lirp.md. Two register stages driven by the
// caller's pipe_ctrl; the rounded result leaves combinationally from the second:
//
//   stage delta (en_i[0]):  delta = p1 - p0               exact, fx_sub_fmt(P, P)
//   stage prod  (en_i[1]):  prod  = a · delta             exact, fx_mul_fmt(A, Delta)
//   output (comb):          p     = resize(p0 + prod, Out) OutRound, OutOverflow
//
// Latency 2 register stages (in step with en_i); throughput 1 per clock.
// Parameters:
//   PFmt        - format word of p0's and p1's components
//   AFmt        - format word of a
//   OutFmt      - format word of p's components
//   OutRound    - fx_pkg rounding mode of the output requantization
//   OutOverflow - fx_pkg overflow mode of the output requantization
// Ports:
//   clk_i       - clock (data registers only, no reset)
//   en_i        - load enables of stages delta (bit 0) and prod (bit 1)
//   p0_i, p1_i  - end points, x, y, z packed from the LSB
//   a_i         - interpolation factor
//   p_o         - the result of the transaction in stage prod, packed like p0_i
//
// Assertions: none here (the stream top checks its handshake; lirp_unit.sv).
module lirp_core #(
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
  input  logic              clk_i,
  input  logic [       1:0] en_i,
  input  logic [  3*PW-1:0] p0_i,
  input  logic [  3*PW-1:0] p1_i,
  input  logic [    AW-1:0] a_i,
  output logic [3*OutW-1:0] p_o
);

  localparam int unsigned DeltaFmt = fx_pkg::fx_sub_fmt(PFmt, PFmt);
  localparam int unsigned ProdFmt  = fx_pkg::fx_mul_fmt(AFmt, DeltaFmt);
  localparam int unsigned SumFmt   = fx_pkg::fx_add_fmt(PFmt, ProdFmt);
  localparam int unsigned DeltaW   = fx_pkg::fx_width(DeltaFmt);
  localparam int unsigned ProdW    = fx_pkg::fx_width(ProdFmt);
  localparam int unsigned SumW     = fx_pkg::fx_width(SumFmt);

  logic [3*DeltaW-1:0] delta_d, delta_q;
  logic [ 3*ProdW-1:0] prod_d, prod_q;
  logic [    3*PW-1:0] p0_q, p0_q2;
  logic [      AW-1:0] a_q;

  for (genvar c = 0; c < 3; c++) begin : g_comp
    // Stage delta.
    fx_sub #(.AFmt(PFmt), .BFmt(PFmt)) u_sub (
      .a_i    (p1_i[c*PW+:PW]),
      .b_i    (p0_i[c*PW+:PW]),
      .delta_o(delta_d[c*DeltaW+:DeltaW])
    );
    // Stage prod.
    fx_mul #(.AFmt(AFmt), .BFmt(DeltaFmt)) u_mul (
      .a_i   (a_q),
      .b_i   (delta_q[c*DeltaW+:DeltaW]),
      .prod_o(prod_d[c*ProdW+:ProdW])
    );
    // Output.
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
      .out_o(p_o[c*OutW+:OutW])
    );
  end

  // Data registers need no reset: pipe_ctrl's valid bits say when they hold a transaction.
  always_ff @(posedge clk_i) begin
    if (en_i[0]) begin
      delta_q <= delta_d;
      p0_q    <= p0_i;
      a_q     <= a_i;
    end
    if (en_i[1]) begin
      prod_q <= prod_d;
      p0_q2  <= p0_q;
    end
  end

endmodule
