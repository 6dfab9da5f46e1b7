// lirp_unit: linear interpolation of 3-component vectors, p = (1 - a)·p0 + a·p1, the "LIRP" of
// Lyon, TR #43, Fig. 7a (N' = LIRP(N0, N1, a)), as a stream: lirp_core's two stages under a
// pipe_ctrl, then the rounded result in an output skid buffer. Specification: docs/lirp.md.
//
//   stage delta:  delta = p1 - p0                   exact, fx_sub_fmt(P, P)
//   stage prod:   prod  = a · delta                 exact, fx_mul_fmt(A, Delta)
//   stage out:    p     = resize(p0 + prod, Out)    OutRound, OutOverflow
//
// Latency 3 cycles; throughput 1 transaction per clock; valid/ready with any backpressure.
// Parameters:
//   PFmt        - format word (fx_pkg::fx_fmt) of p0's and p1's components
//   AFmt        - format word of a
//   OutFmt      - format word of p's components
//   OutRound    - fx_pkg rounding mode of the output requantization
//   OutOverflow - fx_pkg overflow mode of the output requantization
// Ports:
//   clk_i       - clock
//   rst_ni      - asynchronous reset, active low
//   in_valid_i, in_ready_o - input handshake
//   in_p0_i, in_p1_i - end points, x, y, z packed from the LSB (component c at [c*PW +: PW])
//   in_a_i      - interpolation factor
//   out_valid_o, out_ready_i - output handshake
//   out_p_o     - the interpolated vector, packed the same way
//
// Assertions (simulation only): the skid buffer's stream_check on the core's stream and the output.
module lirp_unit #(
  parameter bit [31:0] PFmt        = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] AFmt        = fx_pkg::fx_fmt(1'b0, 1, 10),
  parameter bit [31:0] OutFmt      = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] OutRound    = fx_pkg::FxHalfEven,
  parameter bit [31:0] OutOverflow = fx_pkg::FxSaturate,
  // Derived, do not override.
  localparam bit [31:0] PW         = fx_pkg::fx_width(PFmt),
  localparam bit [31:0] AW         = fx_pkg::fx_width(AFmt),
  localparam bit [31:0] OutW       = fx_pkg::fx_width(OutFmt)
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

  logic              core_valid, core_ready;
  logic [       1:0] core_en;
  logic [3*OutW-1:0] p_d;

  pipe_ctrl #(.Depth(2)) u_ctrl (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .out_valid_o(core_valid),
    .out_ready_i(core_ready),
    .en_o       (core_en)
  );

  lirp_core #(
    .PFmt       (PFmt),
    .AFmt       (AFmt),
    .OutFmt     (OutFmt),
    .OutRound   (OutRound),
    .OutOverflow(OutOverflow)
  ) u_core (
    .clk_i,
    .en_i(core_en),
    .p0_i(in_p0_i),
    .p1_i(in_p1_i),
    .a_i (in_a_i),
    .p_o (p_d)
  );

  // The skid buffer registers the output and cuts the ready path from out_ready_i.
  stream_skid #(.Width(3 * OutW)) u_stage_out (
    .clk_i,
    .rst_ni,
    .in_valid_i (core_valid),
    .in_ready_o (core_ready),
    .in_data_i  (p_d),
    .out_valid_o,
    .out_ready_i,
    .out_data_o (out_p_o)
  );

  // Assertions (simulation only): the valid/ready rules of the input (stream_check); the output
  // skid buffer checks the core's stream and the output.
  stream_check #(.Width(6 * PW + AW)) u_check_in (
    .clk_i,
    .rst_ni,
    .valid_i(in_valid_i),
    .ready_i(in_ready_o),
    .data_i ({in_a_i, in_p1_i, in_p0_i})
  );

endmodule
