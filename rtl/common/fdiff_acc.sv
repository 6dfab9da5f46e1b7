// fdiff_acc: the two accumulators of forward differencing (Kuijk & Blake: "two additions per
// pixel"): on step, f <- f + d1 and d1 <- d1 + d2, modulo 2^Width (two's complement wrap, as a
// plain adder does; the true values must stay in range, which the setup guarantees). The caller
// supplies the d1 and d2 of each step, so it can change d2 at a section boundary or reload d1.
// Shared by the Kuijk–Blake engine and the quadratic colour interpolator.
//
// Latency: f_o and d1_o are registers (the value after a load or step shows the next cycle);
// throughput one step per clock.
// Parameters:
//   Width     - accumulator bits
// Ports:
//   clk_i     - clock (no reset: the caller loads before it steps)
//   load_i    - f <- f_i, d1 <- d1_i (has priority over step_i)
//   f_i, d1_i - values loaded
//   step_i    - advance one pixel: f <- f + d1_step_i, d1 <- d1_step_i + d2_step_i
//   d1_step_i - the first difference of this step (normally d1_o; another value reloads it)
//   d2_step_i - the second difference of this step
//   f_o, d1_o - the accumulators
//
// Assertions (checked by tests/stream_rtl_test.cpp): f_o and d1_o change only on load_i or
// step_i, and then to exactly the sums above.
module fdiff_acc #(
  parameter int unsigned Width = 32
) (
  input  logic             clk_i,
  input  logic             load_i,
  input  logic [Width-1:0] f_i,
  input  logic [Width-1:0] d1_i,
  input  logic             step_i,
  input  logic [Width-1:0] d1_step_i,
  input  logic [Width-1:0] d2_step_i,
  output logic [Width-1:0] f_o,
  output logic [Width-1:0] d1_o
);

  logic [Width-1:0] f_q, d1_q;

  always_ff @(posedge clk_i) begin
    if (load_i) begin
      f_q  <= f_i;
      d1_q <= d1_i;
    end else if (step_i) begin
      f_q  <= f_q + d1_step_i;
      d1_q <= d1_step_i + d2_step_i;
    end
  end

  assign f_o  = f_q;
  assign d1_o = d1_q;

endmodule
