// depth_tree_stage: one register of depth_tree (tests/synth_tb/depth_tree.sv) inside an instance,
// so the depth table must name it by its hierarchy path: q_o = a_i & b_i, registered (1 level).
module depth_tree_stage (
    input  logic clk_i,
    input  logic a_i,
    input  logic b_i,
    output logic q_o
);
  logic both_q;
  always_ff @(posedge clk_i) both_q <= a_i & b_i;
  assign q_o = both_q;
endmodule
