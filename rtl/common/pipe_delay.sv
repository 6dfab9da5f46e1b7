// pipe_delay: carries a value alongside a pipe_ctrl pipeline for Depth stages (stage j loads
// when en_i[j]), so side data arrives at the stage that needs it with its own transaction.
//
// Latency Depth cycles (in step with the stages whose enables it gets); throughput 1 per clock.
// Parameters:
//   Width - data bits
//   Depth - stages (>= 1)
// Ports:
//   clk_i - clock (no reset: the pipe_ctrl's valid bits say when a stage holds a transaction)
//   en_i  - load enables of the spanned stages (pipe_ctrl en_o[first +: Depth])
//   d_i   - value entering the first stage
//   q_o   - value held by the last stage
//
// Assertions (checked by tests/stream_rtl_test.cpp): q_o is the d_i of the transaction the
// pipe_ctrl's last spanned stage holds, and does not change while that stage's enable is low.
module pipe_delay #(
  parameter int unsigned Width = 8,
  parameter int unsigned Depth = 1
) (
  input  logic             clk_i,
  input  logic [Depth-1:0] en_i,
  input  logic [Width-1:0] d_i,
  output logic [Width-1:0] q_o
);

  // Stage j at [j*Width +: Width]; flat so every tool sees plain registers.
  logic [Depth*Width-1:0] stage_q;
  logic [Depth*Width-1:0] stage_d;

  // What each stage loads: the input for stage 0, the previous stage otherwise.
  if (Depth == 1) begin : g_single
    assign stage_d = d_i;
  end else begin : g_chain
    assign stage_d = {stage_q[(Depth-1)*Width-1:0], d_i};
  end

  for (genvar j = 0; j < Depth; j++) begin : g_stage
    always_ff @(posedge clk_i) begin
      if (en_i[j]) begin
        stage_q[j*Width+:Width] <= stage_d[j*Width+:Width];
      end
    end
  end

  assign q_o = stage_q[(Depth-1)*Width+:Width];

endmodule
