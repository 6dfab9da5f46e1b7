// fx_scale: exact a · 2^Shift in fx_pkg::fx_scale_fmt(AFmt, Shift) (model: fx::scale). Moves
// the binary point; the bits stay, zeros are appended only when the point would pass the last
// fraction bit, and the value is sign- or zero-extended when the point passes the first integer
// bit. Pure wiring.
//
// Latency 0 (combinational).
// Parameters:
//   AFmt     - operand format word (fx_pkg::fx_fmt)
//   Shift    - power of two (negative: divide)
// Ports:
//   a_i      - operand (raw bits)
//   scaled_o - a · 2^Shift in fx_scale_fmt(AFmt, Shift)
//
// Assertions: none (no parameter value is invalid).
module fx_scale #(
  parameter int unsigned AFmt     = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int          Shift    = 1,
  // Derived, do not override.
  localparam int unsigned OutFmt  = fx_pkg::fx_scale_fmt(AFmt, Shift),
  localparam int unsigned AW      = fx_pkg::fx_width(AFmt),
  localparam int unsigned OutW    = fx_pkg::fx_width(OutFmt)
) (
  input  logic [  AW-1:0] a_i,
  output logic [OutW-1:0] scaled_o
);

  // Zeros appended below the old LSB (only when Shift exceeds the fraction bits).
  localparam int          AFrac  = fx_pkg::fx_frac(AFmt);
  localparam int unsigned Append = Shift > AFrac ? Shift - AFrac : 0;

  logic [OutW-1:0] extended;
  if (fx_pkg::fx_signed(AFmt)) begin : g_sign_extend
    assign extended = OutW'($signed(a_i));
  end else begin : g_zero_extend
    assign extended = OutW'(a_i);
  end
  assign scaled_o = extended << Append;

endmodule
