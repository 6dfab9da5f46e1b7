// fx_resize: requantize a fixed-point value from InFmt to OutFmt in any rounding and overflow
// mode (model: fx::resize_raw; specification: docs/fixed-point.md "Requantization"):
// 1. Align the binary point: shift left when OutFmt has more fraction bits (exact), or drop
//    bits with rounding Round (fx_pkg::FxTruncate: floor, fx_pkg::FxHalfUp: floor(x + 1/2),
//    fx_pkg::FxHalfEven: ties to even) when it has fewer.
// 2. Fit the integer part: fx_pkg::FxSaturate clamps to OutFmt's range, fx_pkg::FxWrap keeps the
//    low bits.
// The one implementation of rounding and saturation: fx_rq (round and saturate, what every
// pipeline stage uses) and the exact alignments of fx_add/fx_sub/fx_neg instantiate it.
//
// Latency 0 (combinational).
// Parameters:
//   InFmt    - format word (fx_pkg::fx_fmt) of in_i
//   OutFmt   - format word of out_o
//   Round    - fx_pkg::FxTruncate, fx_pkg::FxHalfUp or fx_pkg::FxHalfEven
//   Overflow - fx_pkg::FxWrap or fx_pkg::FxSaturate
// Ports:
//   in_i     - value in InFmt (raw bits)
//   out_o    - the value requantized to OutFmt (raw bits)
//
// Assertions: Round and Overflow are checked at elaboration (end of the module).
module fx_resize #(
  parameter bit [31:0] InFmt    = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] OutFmt   = fx_pkg::fx_fmt(1'b1, 1, 10),
  parameter bit [31:0] Round    = fx_pkg::FxHalfEven,
  parameter bit [31:0] Overflow = fx_pkg::FxSaturate,
  // Derived, do not override.
  localparam bit [31:0] InW     = fx_pkg::fx_width(InFmt),
  localparam bit [31:0] OutW    = fx_pkg::fx_width(OutFmt)
) (
  input  logic [ InW-1:0] in_i,
  output logic [OutW-1:0] out_o
);

  localparam bit [31:0] InFrac  = fx_pkg::fx_frac(InFmt);
  localparam bit [31:0] OutFrac = fx_pkg::fx_frac(OutFmt);
  localparam bit [31:0] Grow    = OutFrac > InFrac ? OutFrac - InFrac : 0;
  localparam bit [31:0] Drop    = InFrac > OutFrac ? InFrac - OutFrac : 0;
  // Internal signed width: the aligned input, one bit to hold an unsigned input as signed and
  // one for the rounding carry. Comparison width: also holds the output bounds with a sign.
  localparam bit [31:0] IntW    = InW + Grow + 2;
  localparam bit [31:0] CmpW    = fx_pkg::fx_max(IntW, OutW + 1);

  logic signed [IntW-1:0] in_ext, aligned, rounded;
  logic signed [CmpW-1:0] wide;

  if (fx_pkg::fx_signed(InFmt)) begin : g_sign_extend
    assign in_ext = IntW'($signed(in_i));
  end else begin : g_zero_extend
    assign in_ext = $signed(IntW'(in_i));
  end

  assign aligned = in_ext <<< Grow;

  if (Drop == 0) begin : g_exact
    assign rounded = aligned;
  end else begin : g_round
    localparam logic signed [IntW-1:0] Half = IntW'(1) <<< (Drop - 1);
    logic signed [IntW-1:0] bias;
    if (Round == fx_pkg::FxTruncate) begin : g_truncate
      assign bias = '0;
    end else if (Round == fx_pkg::FxHalfUp) begin : g_half_up
      assign bias = Half;
    end else begin : g_half_even
      // Ties round up exactly when the lowest kept bit is odd.
      assign bias = Half - IntW'(1) + $signed(IntW'(aligned[Drop]));
    end
    assign rounded = (aligned + bias) >>> Drop;
  end

  assign wide = CmpW'(rounded);

  if (Overflow == fx_pkg::FxSaturate) begin : g_saturate
    localparam logic signed [CmpW-1:0] MaxV =
        fx_pkg::fx_signed(OutFmt) ? (CmpW'(1) <<< (OutW - 1)) - CmpW'(1) : (CmpW'(1) <<< OutW) - CmpW'(1);
    localparam logic signed [CmpW-1:0] MinV = fx_pkg::fx_signed(OutFmt) ? -(CmpW'(1) <<< (OutW - 1)) : '0;
    always_comb begin
      if (wide > MaxV) begin
        out_o = MaxV[OutW-1:0];  // phongsim: waive saturate.high (instances that cannot saturate)
      end else if (wide < MinV) begin
        out_o = MinV[OutW-1:0];  // phongsim: waive saturate.low (instances that cannot saturate)
      end else begin
        out_o = wide[OutW-1:0];
      end
    end
  end else begin : g_wrap
    assign out_o = wide[OutW-1:0];
    if (CmpW > OutW) begin : g_unused
      logic unused_high_bits;
      assign unused_high_bits = ^wide[CmpW-1:OutW];
    end
  end

  // Assertions: elaboration-time parameter checks.
`ifndef __ICARUS__  // Icarus 11 has no elaboration-time $error
  if (Round > fx_pkg::FxHalfEven) begin : g_bad_round
    $error("fx_resize: Round must be fx_pkg::FxTruncate, fx_pkg::FxHalfUp or fx_pkg::FxHalfEven");
  end
  if (Overflow > fx_pkg::FxSaturate) begin : g_bad_overflow
    $error("fx_resize: Overflow must be fx_pkg::FxWrap or fx_pkg::FxSaturate");
  end
`endif

endmodule
