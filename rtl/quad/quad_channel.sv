// quad_channel: one colour channel of the quadratic interpolator (Vlasic §3.5, §4.3): the
// channel's value at pixel offsets (i, j) from the triangle's origin pixel, the polynomial of the
// program's words p(i, j) = f + gx·i + gy·j + a·i(i - 1) + b·i·j + c·j(j - 1), by forward
// differencing, two additions per pixel:
//   along a row:     f <- f + g,  g <- g + 2a                       (fdiff_acc u_row)
//   down the column: F <- F + GY, GY <- GY + 2c                     (fdiff_acc u_column, i = 0)
//                    G0 <- G0 + b                                   (g at i = 0)
//   row start at i = i0:  f = F + i0·G0 + a·i0(i0 - 1),  g = G0 + 2a·i0  (exact products)
// All arithmetic in AccFmt bits with two's complement wrap (the setup keeps the true values in
// range). The output is rq(clamp01(f), OutFmt): clamped to [0, 1], rounded with OutRound,
// saturated. Specification: docs/quad.md ("Per row and per pixel").
//
// Latency 0 from f to value_o (combinational); the accumulators are registers; one pixel per
// clock.
// Parameters:
//   AccFmt      - signed accumulator format word
//   OutFmt      - output format word
//   OutRound    - fx_pkg rounding mode of the output
//   I0Bits      - bits of the row-start offset i0
// Ports:
//   clk_i       - clock (data registers only, no reset)
//   load_i      - start a triangle: F <- f00_i, GY <- gy0_i, G0 <- gx0_i, and a_i, b_i, c_i
//   f00_i, gy0_i, gx0_i, a_i, b_i, c_i - the channel's program words f, gy, gx, a, b, c
//   row_start_i - start the row's pixels at offset i0_i
//   i0_i        - offset of the row's first pixel from the box's left column x0
//   pixel_i     - step to the next pixel of the row
//   row_next_i  - step the column accumulators to the next row
//   value_o     - the current pixel's value
//
// Assertions: none (the caller sequences load, row start, pixel and row steps).
module quad_channel #(
  parameter int unsigned AccFmt   = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter int unsigned OutFmt   = fx_pkg::fx_fmt(1'b0, 0, 8),
  parameter int unsigned OutRound = fx_pkg::FxHalfEven,
  parameter int unsigned I0Bits   = 11,
  // Derived, do not override.
  localparam int unsigned AccW    = fx_pkg::fx_width(AccFmt),
  localparam int unsigned OutW    = fx_pkg::fx_width(OutFmt)
) (
  input  logic              clk_i,
  input  logic              load_i,
  input  logic [  AccW-1:0] f00_i,
  input  logic [  AccW-1:0] gy0_i,
  input  logic [  AccW-1:0] gx0_i,
  input  logic [  AccW-1:0] a_i,
  input  logic [  AccW-1:0] b_i,
  input  logic [  AccW-1:0] c_i,
  input  logic              row_start_i,
  input  logic [I0Bits-1:0] i0_i,
  input  logic              pixel_i,
  input  logic              row_next_i,
  output logic [  OutW-1:0] value_o
);

  logic [AccW-1:0] a_q, b_q, c_q, g0_q;
  logic [AccW-1:0] col_f, col_gy, f, g;

  always_ff @(posedge clk_i) begin
    if (load_i) begin
      a_q  <= a_i;
      b_q  <= b_i;
      c_q  <= c_i;
      g0_q <= gx0_i;
    end else if (row_next_i) begin
      g0_q <= g0_q + b_q;
    end
  end

  // Down the column at i = 0: F and its row difference GY.
  fdiff_acc #(.Width(AccW)) u_column (
    .clk_i,
    .load_i   (load_i),
    .f_i      (f00_i),
    .d1_i     (gy0_i),
    .step_i   (row_next_i),
    .d1_step_i(col_gy),
    .d2_step_i(c_q << 1),
    .f_o      (col_f),
    .d1_o     (col_gy)
  );

  // Row start: jump from i = 0 to i = i0 with exact (modulo 2^AccW) products.
  logic [AccW-1:0] i0_ext, i0_i0m1, f_start, g_start;
  assign i0_ext  = AccW'(i0_i);
  assign i0_i0m1 = AccW'(i0_i) * (AccW'(i0_i) - 1'b1);
  assign f_start = col_f + i0_ext * g0_q + a_q * i0_i0m1;
  assign g_start = g0_q + ((a_q * i0_ext) << 1);

  // Along the row.
  fdiff_acc #(.Width(AccW)) u_row (
    .clk_i,
    .load_i   (row_start_i),
    .f_i      (f_start),
    .d1_i     (g_start),
    .step_i   (pixel_i),
    .d1_step_i(g),
    .d2_step_i(a_q << 1),
    .f_o      (f),
    .d1_o     (g)
  );

  // Output: clamp to [0, 1], round.
  logic [AccW-1:0] clamped;
  fx_clamp01 #(.AFmt(AccFmt)) u_clamp (
    .a_i      (f),
    .clamped_o(clamped)
  );
  fx_rq #(.InFmt(AccFmt), .OutFmt(OutFmt), .Round(OutRound))
      u_value (.in_i(clamped), .out_o(value_o));

endmodule
