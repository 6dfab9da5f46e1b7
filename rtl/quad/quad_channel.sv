// quad_channel: one colour channel of the quadratic interpolator (Vlasic §3.5, §4.3): the
// channel's value f(i, j) = a·i² + b·i·j + c·j² + d·i + e·j + g over pixel offsets (i, j) from
// the triangle's origin pixel, by forward differencing — two additions per pixel:
//   along a row:     f <- f + g,  g <- g + 2a                       (fdiff_acc)
//   down the column: F <- F + GY, GY <- GY + 2c, G0 <- G0 + b       (values at i = 0)
//   row start at i = k:  f = F + k·G0 + a·k(k - 1),  g = G0 + 2a·k  (exact products)
// All arithmetic in AccFmt bits with two's complement wrap (the setup keeps the true values in
// range). The output is f clamped to [0, 1] and rounded to OutFmt. Specification: docs/quad.md.
//
// Latency 0 from f to value_o (combinational); the accumulators are registers.
// Parameters: AccFmt - signed accumulator format word; OutFmt - output format; OutRound - its
//             rounding; KBits - bits of the row-start offset k.
// Ports: clk_i; load_i - start a triangle from f00_i (F), gy0_i (GY), gx0_i (G0), a_i, b_i, c_i;
//        row_start_i - start row pixels at offset k_i; pixel_i - step to the next pixel;
//        row_next_i - step the column accumulators to the next row; value_o - the pixel value.
module quad_channel #(
  parameter int unsigned AccFmt   = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter int unsigned OutFmt   = fx_pkg::fx_fmt(1'b0, 0, 8),
  parameter int unsigned OutRound = fx_pkg::FxHalfEven,
  parameter int unsigned KBits    = 11,
  // Derived, do not override.
  localparam int unsigned AccW    = fx_pkg::fx_width(AccFmt),
  localparam int unsigned OutW    = fx_pkg::fx_width(OutFmt)
) (
  input  logic             clk_i,
  input  logic             load_i,
  input  logic [ AccW-1:0] f00_i,
  input  logic [ AccW-1:0] gy0_i,
  input  logic [ AccW-1:0] gx0_i,
  input  logic [ AccW-1:0] a_i,
  input  logic [ AccW-1:0] b_i,
  input  logic [ AccW-1:0] c_i,
  input  logic             row_start_i,
  input  logic [KBits-1:0] k_i,
  input  logic             pixel_i,
  input  logic             row_next_i,
  output logic [ OutW-1:0] value_o
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

  // Row start: jump from i = 0 to i = k with exact (modulo 2^AccW) products.
  logic [AccW-1:0] k_ext, k_km1, f_start, g_start;
  assign k_ext   = AccW'(k_i);
  assign k_km1   = AccW'(k_i) * (AccW'(k_i) - 1'b1);
  assign f_start = col_f + k_ext * g0_q + a_q * k_km1;
  assign g_start = g0_q + ((a_q * k_ext) << 1);

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
  fx_resize #(
    .InFmt   (AccFmt),
    .OutFmt  (OutFmt),
    .Round   (OutRound),
    .Overflow(fx_pkg::FxSaturate)
  ) u_round (
    .in_i (clamped),
    .out_o(value_o)
  );

endmodule
