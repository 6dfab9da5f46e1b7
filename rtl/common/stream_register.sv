// stream_register: one pipeline stage of a valid/ready stream (as common_cells' stream
// register). Holds one transaction; accepts a new one whenever it is empty or its current one
// leaves in the same cycle, so a chain of these runs at one transaction per clock and collapses
// bubbles. in_ready_o depends combinationally on out_ready_i; put a stream_skid at the end of a
// chain to cut that path.
//
// Latency 1 cycle, throughput 1 per cycle.
// Parameters: Width - data bits.
// Ports: clk_i, rst_ni (asynchronous, active low); in_* - upstream stream; out_* - downstream.
module stream_register #(
  parameter int unsigned Width = 8
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             in_valid_i,
  output logic             in_ready_o,
  input  logic [Width-1:0] in_data_i,
  output logic             out_valid_o,
  input  logic             out_ready_i,
  output logic [Width-1:0] out_data_o
);

  logic             valid_q;
  logic [Width-1:0] data_q;

  assign in_ready_o  = out_ready_i | ~valid_q;
  assign out_valid_o = valid_q;
  assign out_data_o  = data_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= 1'b0;
    end else if (in_ready_o) begin
      valid_q <= in_valid_i;
    end
  end

  // Data registers need no reset: they are only read while valid_q is set.
  always_ff @(posedge clk_i) begin
    if (in_valid_i && in_ready_o) begin
      data_q <= in_data_i;
    end
  end

endmodule
