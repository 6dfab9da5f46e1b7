// pipe_ctrl: valid/ready control of a Depth-stage pipeline whose data registers live in the
// datapath modules. Stage i holds at most one transaction; it loads (en_o[i]) whenever data is
// offered to it and it is empty or its own transaction leaves in the same cycle
// (ready = ready_next | ~valid_q, the common_cells stream register rule), so the pipeline runs at
// one transaction per clock and bubbles collapse under backpressure. in_ready_o depends
// combinationally on out_ready_i through every stage: end the pipeline in a stream_skid.
//
// Latency Depth cycles; throughput 1 transaction per clock.
// Parameters:
//   Depth       - number of register stages (>= 1)
// Ports:
//   clk_i       - clock
//   rst_ni      - asynchronous reset, active low (clears every stage's valid bit)
//   in_valid_i  - upstream offers a transaction
//   in_ready_o  - stage 0 can take it (a transfer when both are high)
//   out_valid_o - the last stage holds a transaction (its data: the last stage's registers)
//   out_ready_i - downstream takes it
//   en_o        - en_o[i]: load enable of stage i's data registers (a transfer into stage i)
//
// Assertions (checked by tests/stream_rtl_test.cpp): no output valid during or right after reset;
// out_valid_o stays high and the last stage's registers keep their value (en_o[Depth-1] low)
// until out_ready_i; every accepted transaction leaves once, in order.
module pipe_ctrl #(
  parameter int unsigned Depth = 2
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             in_valid_i,
  output logic             in_ready_o,
  output logic             out_valid_o,
  input  logic             out_ready_i,
  output logic [Depth-1:0] en_o
);

  logic [Depth-1:0] valid_q, offered;
  // ready[i] depends on ready[i+1]: split so Verilator does not see one circular signal.
  logic [Depth-1:0] ready  /* verilator split_var */;

  for (genvar i = 0; i < Depth; i++) begin : g_stage
    if (i == 0) begin : g_first
      assign offered[i] = in_valid_i;
    end else begin : g_next
      assign offered[i] = valid_q[i-1];
    end
    if (i == Depth - 1) begin : g_last
      assign ready[i] = out_ready_i | ~valid_q[i];
    end else begin : g_inner
      assign ready[i] = ready[i+1] | ~valid_q[i];
    end
    assign en_o[i] = offered[i] & ready[i];

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        valid_q[i] <= 1'b0;
      end else if (ready[i]) begin
        valid_q[i] <= offered[i];
      end
    end
  end

  assign in_ready_o  = ready[0];
  assign out_valid_o = valid_q[Depth-1];

endmodule
