// fx_clamp01: clamp a value to [0, 1] in its own format (model: fx::clamp01_raw): negative
// values become 0, values above 1.0 become 1.0 (when the format has an integer bit; otherwise it
// cannot exceed 1). Used before rounding a colour or intensity to its output format.
//
// Latency 0 (combinational).
// Parameters:
//   AFmt      - format word (fx_pkg::fx_fmt) of a_i and clamped_o
// Ports:
//   a_i       - value (raw bits)
//   clamped_o - min(max(a, 0), 1) in AFmt
//
// Assertions: none (no parameter value is invalid).
module fx_clamp01 #(
  parameter int unsigned AFmt = fx_pkg::fx_fmt(1'b1, 2, 16),
  // Derived, do not override.
  localparam int unsigned AW  = fx_pkg::fx_width(AFmt)
) (
  input  logic [AW-1:0] a_i,
  output logic [AW-1:0] clamped_o
);

  localparam int unsigned Frac = fx_pkg::fx_frac(AFmt);
  logic negative;
  if (fx_pkg::fx_signed(AFmt)) begin : g_signed
    assign negative = a_i[AW-1];
  end else begin : g_unsigned
    assign negative = 1'b0;
  end

  if (fx_pkg::fx_int(AFmt) >= 1) begin : g_clamp_one
    localparam logic [AW-1:0] One = AW'(1) << Frac;
    always_comb begin
      if (negative) begin
        clamped_o = '0;
      end else if (a_i > One) begin
        clamped_o = One;
      end else begin
        clamped_o = a_i;
      end
    end
  end else begin : g_below_one
    assign clamped_o = negative ? '0 : a_i;
  end

endmodule
