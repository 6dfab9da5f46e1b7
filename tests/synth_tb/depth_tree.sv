// depth_tree: a design whose logic depth is known without Yosys, for the depth count of
// sim/explore/synth.h (tests/synth_test.cpp). With two-input gates the parity of 16 bits takes at
// least log2(16) = 4 levels and the AND of 8 bits at least log2(8) = 3; balanced trees reach both
// bounds, so a correct count on a good mapping gives exactly 4 and 3.
//   a_q       <- a_i                       0 levels, from the input port a_i
//   parity_q  <- ^a_q                      4 levels, from a_q
//   all_q     <- &a_q[7:0]                 3 levels, from a_q
//   u_stage.both_q <- parity_q & all_q     1 level (named inside the instance, not by stage_q)
//   parity_o = parity_q, both_o = stage_q  0 levels; mixed_o = parity_q ^ a_i[15]: 1 level
module depth_tree (
    input  logic        clk_i,
    input  logic [15:0] a_i,
    output logic        parity_o,
    output logic        both_o,
    output logic        mixed_o
);
  logic [15:0] a_q;
  logic parity_q, all_q, stage_q;

  always_ff @(posedge clk_i) begin
    a_q      <= a_i;
    parity_q <= ^a_q;
    all_q    <= &a_q[7:0];
  end

  depth_tree_stage u_stage (
      .clk_i(clk_i),
      .a_i  (parity_q),
      .b_i  (all_q),
      .q_o  (stage_q)
  );

  assign parity_o = parity_q;
  assign both_o   = stage_q;
  assign mixed_o  = parity_q ^ a_i[15];
endmodule
