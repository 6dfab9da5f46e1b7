// fx_rq: requantize, the `rq(v, F)` of the specifications: round a value from InFmt to OutFmt
// with Round, then saturate to OutFmt's range (model: fx::resize(x, to, round,
// fx::Overflow::saturate)). Every rounding point of the pipelines is one of these; it is
// fx_resize with the overflow mode fixed to fx_pkg::FxSaturate, so rounding and saturation are
// written once (fx_resize.sv, docs/fixed-point.md "Requantization"). A configurable overflow mode
// (the LIRP unit's out_overflow) uses fx_resize directly.
//
// Latency 0 (combinational).
// Parameters:
//   InFmt  - format word (fx_pkg::fx_fmt) of in_i
//   OutFmt - format word of out_o
//   Round  - fx_pkg::FxTruncate, fx_pkg::FxHalfUp or fx_pkg::FxHalfEven
// Ports:
//   in_i   - value in InFmt (raw bits)
//   out_o  - rq(in_i, OutFmt) (raw bits)
//
// Assertions: Round is checked at elaboration (fx_resize).
module fx_rq #(
  parameter int unsigned InFmt  = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned OutFmt = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter int unsigned Round  = fx_pkg::FxHalfEven,
  // Derived, do not override.
  localparam int unsigned InW   = fx_pkg::fx_width(InFmt),
  localparam int unsigned OutW  = fx_pkg::fx_width(OutFmt)
) (
  input  logic [ InW-1:0] in_i,
  output logic [OutW-1:0] out_o
);

  fx_resize #(
    .InFmt   (InFmt),
    .OutFmt  (OutFmt),
    .Round   (Round),
    .Overflow(fx_pkg::FxSaturate)
  ) u_resize (
    .in_i,
    .out_o
  );

endmodule
