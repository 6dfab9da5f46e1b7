// Bounded proofs of the stream primitives (tests/formal_test.sh, yosys-smtbmc): each wrapper
// drives a primitive with unconstrained inputs after one reset cycle and checks it against a
// reference FIFO of the transactions it accepted:
//   - an offered output stays valid and unchanged until taken;
//   - what leaves is the oldest accepted transaction, unchanged (nothing lost, duplicated or
//     reordered), and never more than the primitive can hold;
//   - no output valid in the cycle after reset.

// A reference FIFO of Depth entries: push on an accepted input, pop on a taken output.
module ref_fifo #(
  parameter int Width = 4,
  parameter int Depth = 2
) (
  input  logic             clk_i,
  input  logic             rst_ni,
  input  logic             push_i,
  input  logic [Width-1:0] data_i,
  input  logic             pop_i,
  output logic [Width-1:0] head_o,
  output logic [31:0]      count_o
);
  logic [Width-1:0] mem_q[Depth+1];
  always_ff @(posedge clk_i) begin
    if (!rst_ni) begin
      count_o <= 0;
    end else begin
      if (pop_i) begin
        for (int i = 0; i < Depth; i++) mem_q[i] <= mem_q[i+1];
      end
      if (push_i) mem_q[count_o-(pop_i ? 1 : 0)] <= data_i;
      count_o <= count_o + (push_i ? 1 : 0) - (pop_i ? 1 : 0);
    end
  end
  assign head_o = mem_q[0];
endmodule

module stream_skid_props (
  input logic       clk_i,
  input logic       rst_ni,
  input logic       in_valid_i,
  input logic [3:0] in_data_i,
  input logic       out_ready_i
);
  logic in_ready_o, out_valid_o;
  logic [3:0] out_data_o, head;
  logic [31:0] count;
  stream_skid #(.Width(4)) dut (.*);
  ref_fifo #(.Width(4), .Depth(2)) fifo (.clk_i, .rst_ni, .push_i(in_valid_i && in_ready_o),
    .data_i(in_data_i), .pop_i(out_valid_o && out_ready_i), .head_o(head), .count_o(count));

  logic init = 1'b1;
  always_ff @(posedge clk_i) init <= 1'b0;
  always_comb begin
    if (init) assume (!rst_ni);
    else assume (rst_ni);
  end
  always_ff @(posedge clk_i) begin
    if (!init && rst_ni) begin
      assert (count <= 2);
      assert (out_valid_o == (count != 0));  // the skid buffer has no bubbles
      if (out_valid_o) assert (out_data_o == head);
      if ($past(rst_ni) && $past(out_valid_o && !out_ready_i)) begin
        assert (out_valid_o && out_data_o == $past(out_data_o));
      end
      if (!$past(rst_ni)) assert (!out_valid_o);
    end
  end
endmodule

// pipe_ctrl with its data registers in pipe_delay, as every unit uses them.
module pipe_props (
  input logic       clk_i,
  input logic       rst_ni,
  input logic       in_valid_i,
  input logic [3:0] in_data_i,
  input logic       out_ready_i
);
  localparam int Depth = 3;
  logic in_ready_o, out_valid_o;
  logic [Depth-1:0] en;
  logic [3:0] out_data, head;
  logic [31:0] count;
  pipe_ctrl #(.Depth(Depth)) ctrl (.clk_i, .rst_ni, .in_valid_i, .in_ready_o, .out_valid_o,
    .out_ready_i, .en_o(en));
  pipe_delay #(.Width(4), .Depth(Depth)) data (.clk_i, .en_i(en), .d_i(in_data_i),
    .q_o(out_data));
  ref_fifo #(.Width(4), .Depth(Depth)) fifo (.clk_i, .rst_ni, .push_i(in_valid_i && in_ready_o),
    .data_i(in_data_i), .pop_i(out_valid_o && out_ready_i), .head_o(head), .count_o(count));

  logic init = 1'b1;
  always_ff @(posedge clk_i) init <= 1'b0;
  always_comb begin
    if (init) assume (!rst_ni);
    else assume (rst_ni);
  end
  always_ff @(posedge clk_i) begin
    if (!init && rst_ni) begin
      assert (count <= Depth);
      if (out_valid_o) assert (count != 0 && out_data == head);
      if ($past(rst_ni) && $past(out_valid_o && !out_ready_i)) begin
        assert (out_valid_o && out_data == $past(out_data) && !$past(en[Depth-1]));
      end
      if (!$past(rst_ni)) assert (!out_valid_o);
      if (count == 0) assert (in_ready_o);  // an empty pipeline takes input
    end
  end
endmodule
