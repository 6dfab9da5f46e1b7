// pipe_ctrl_tb: pipe_ctrl as a stream for tests/stream_rtl_test.cpp. Each stage's data register
// loads on the controller's en_o[i], as a pipeline datapath does (lirp_core, lyon_top), so a
// controller that loads a stage at the wrong time loses, duplicates or reorders data.
//
// Parameters: Depth - pipe_ctrl stages; Width - data bits.
// Ports: the stream_skid port set (clk_i, rst_ni, in_valid_i, in_ready_o, in_data_i,
//        out_valid_o, out_ready_i, out_data_o).
module pipe_ctrl_tb #(
  parameter int unsigned Depth = 4,
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

  logic [Width-1:0] data_q[Depth];
  for (genvar i = 0; i < Depth; i++) begin : g_stage
    always_ff @(posedge clk_i) begin
      if (en[i]) data_q[i] <= i == 0 ? in_data_i : data_q[i == 0 ? 0 : i-1];
    end
  end
  assign out_data_o = data_q[Depth-1];

endmodule
