// stream_check: the valid/ready rules of one stream, checked in simulation; nothing in
// synthesis. Once offered, a transaction stays offered (valid held) and unchanged until it is
// taken, and a valid transaction carries no X or Z bit (seen by four-state simulators such as
// Icarus; Verilator is two-state). Nothing is checked in reset, and the stall rules only from
// the second cycle after it, so a randomized power-up state cannot trip them. A broken rule is an $error naming the instance
// (%m), which the co-simulation harness reports as a handshake violation in that cycle.
// stream_skid checks both of its sides with it: every stream seam of phongsim's RTL.
// Parameters:
//   Width - data bits
// Ports:
//   clk_i, rst_ni    - clock; asynchronous reset, active low
//   valid_i, ready_i - the handshake watched
//   data_i           - the data watched
module stream_check #(
  parameter bit [31:0] Width = 1
) (
  input logic             clk_i,
  input logic             rst_ni,
  input logic             valid_i,
  input logic             ready_i,
  input logic [Width-1:0] data_i
);

`ifndef SYNTHESIS
`ifndef FORMAL  // Yosys's formal front end reads the file without SYNTHESIS and has no $error
  // A check, not design logic: left out of RTL coverage.
  // verilator coverage_off
  logic             stalled_q;  // offered and not taken in the previous cycle
  logic [Width-1:0] data_q;
  // Checked at the clock edge (the cycle's settled values), out of reset only.
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      stalled_q <= 1'b0;
    end else begin
      if (stalled_q && !valid_i) $error("%m: valid dropped while stalled");
      if (stalled_q && valid_i && data_i != data_q) $error("%m: data changed while stalled");
      if (valid_i && $isunknown(data_i)) $error("%m: X or Z on valid data");
      stalled_q <= valid_i & ~ready_i;
    end
  end
  always_ff @(posedge clk_i) begin
    data_q <= data_i;
  end
  // verilator coverage_on
`endif
`endif

endmodule
