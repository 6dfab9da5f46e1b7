// pipe_delay_tb: pipe_delay as the datapath of a pipe_ctrl pipeline for
// tests/stream_rtl_test.cpp: the data travels only in the pipe_delay, so out_data_o is right only
// if pipe_delay moves each value exactly when its stage's enable says so.
//
// Parameters: Depth - stages of both; Width - data bits.
// Ports: the stream_skid port set.
module pipe_delay_tb #(
  parameter int unsigned Depth = 3,
  parameter int unsigned Width = 16
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

  logic [Depth-1:0] en;
  pipe_ctrl #(.Depth(Depth)) u_ctrl (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .out_valid_o,
    .out_ready_i,
    .en_o(en)
  );

  pipe_delay #(.Width(Width), .Depth(Depth)) u_delay (
    .clk_i,
    .en_i(en),
    .d_i (in_data_i),
    .q_o (out_data_o)
  );

endmodule
