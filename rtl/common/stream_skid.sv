// stream_skid: skid buffer (spill register) for a valid/ready stream. in_ready_o and the outputs
// come straight from registers, so it cuts every combinational path between its two sides at
// full throughput. A second slot ("spare") catches the transaction that arrives in the cycle the
// downstream stalls.
//
// Latency 1 cycle; throughput 1 transaction per clock.
// Parameters:
//   Width       - data bits
// Ports:
//   clk_i       - clock
//   rst_ni      - asynchronous reset, active low (empties both slots)
//   in_valid_i  - upstream offers in_data_i
//   in_ready_o  - the buffer can take it (the spare slot is empty)
//   in_data_i   - upstream data
//   out_valid_o - out_data_o holds a transaction
//   out_ready_i - downstream takes it
//   out_data_o  - the oldest transaction held
//
// Assertions (checked by tests/stream_rtl_test.cpp): no output valid during or right after reset;
// out_valid_o stays high and out_data_o unchanged until out_ready_i; every accepted transaction
// leaves once, in order, unchanged.
module stream_skid #(
  parameter bit [31:0] Width = 8
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

  // Slot "main" drives the output; slot "spare" holds the transaction that arrived while main
  // was stalled. in_ready_o is simply "spare is empty".
  logic             main_valid_q, main_valid_d, spare_valid_q, spare_valid_d;
  logic [Width-1:0] main_q, main_d, spare_q, spare_d;
  logic             in_fire;

  assign in_ready_o  = ~spare_valid_q;
  assign out_valid_o = main_valid_q;
  assign out_data_o  = main_q;
  assign in_fire     = in_valid_i & ~spare_valid_q;

  always_comb begin
    main_valid_d  = main_valid_q;
    main_d        = main_q;
    spare_valid_d = spare_valid_q;
    spare_d       = spare_q;
    if (!main_valid_q || out_ready_i) begin
      // Main is free this cycle: refill it from spare first (input is not accepted then),
      // otherwise from the input.
      if (spare_valid_q) begin
        main_valid_d  = 1'b1;
        main_d        = spare_q;
        spare_valid_d = 1'b0;
      end else begin
        main_valid_d = in_fire;
        main_d       = in_data_i;
      end
    end else if (in_fire) begin
      spare_valid_d = 1'b1;
      spare_d       = in_data_i;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      main_valid_q  <= 1'b0;
      spare_valid_q <= 1'b0;
    end else begin
      main_valid_q  <= main_valid_d;
      spare_valid_q <= spare_valid_d;
    end
  end

  // Data registers need no reset: they are only read while their valid bit is set.
  always_ff @(posedge clk_i) begin
    main_q  <= main_d;
    spare_q <= spare_d;
  end

  // Assertions (simulation only): both sides keep the valid/ready rules (stream_check).
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
