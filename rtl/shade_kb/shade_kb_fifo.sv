// shade_kb_fifo: a first-in first-out buffer for a valid/ready stream, 2^AddrBits entries.
// in_ready_o and out_valid_o come from the occupancy register alone, so neither side's ready or
// valid reaches the other combinationally. A word written in one cycle can be read from the next
// (no fall-through): latency 1 cycle, throughput 1 word per clock.
// shade_kb keeps a whole span program of one channel in one (docs/shade_kb.md, "Why a FIFO per
// channel") and the x0, y of the spans in flight in another.
// Parameters:
//   Width    - data bits
//   AddrBits - log2 of the number of entries
// Ports:
//   clk_i, rst_ni            - clock; asynchronous reset, active low (empties the FIFO)
//   in_valid_i, in_ready_o   - write handshake (ready: not full)
//   in_data_i                - the word written
//   out_valid_o, out_ready_i - read handshake (valid: not empty)
//   out_data_o               - the oldest word held
//
// Assertions: both sides keep the valid/ready rules (stream_check).
module shade_kb_fifo #(
  parameter bit [31:0] Width    = 8,
  parameter bit [31:0] AddrBits = 2,
  // Derived, do not override.
  localparam bit [31:0] Depth   = 32'd1 << AddrBits
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

  logic [   Width-1:0] mem_q[0:Depth-1];
  logic [AddrBits-1:0] wr_q, rd_q;
  logic [  AddrBits:0] count_q;
  logic                push, pop;

  assign in_ready_o  = count_q != (AddrBits + 1)'(Depth);
  assign out_valid_o = count_q != '0;
  assign out_data_o  = mem_q[rd_q];
  assign push        = in_valid_i & in_ready_o;
  assign pop         = out_valid_o & out_ready_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      wr_q    <= '0;
      rd_q    <= '0;
      count_q <= '0;
    end else begin
      if (push) wr_q <= wr_q + 1'b1;
      if (pop) rd_q <= rd_q + 1'b1;
      count_q <= count_q + (AddrBits + 1)'(push) - (AddrBits + 1)'(pop);
    end
  end

  // The entries need no reset: an entry is read only after it was written.
  always_ff @(posedge clk_i) begin
    if (push) mem_q[wr_q] <= in_data_i;
  end

  // Assertions (simulation only): both sides keep the valid/ready rules.
  stream_check #(.Width(Width)) u_check_in (
    .clk_i,
    .rst_ni,
    .valid_i(in_valid_i),
    .ready_i(in_ready_o),
    .data_i (in_data_i)
  );
  stream_check #(.Width(Width)) u_check_out (
    .clk_i,
    .rst_ni,
    .valid_i(out_valid_o),
    .ready_i(out_ready_i),
    .data_i (out_data_o)
  );

endmodule
