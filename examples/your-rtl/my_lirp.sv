// my_lirp: a LIRP written independently of phongsim's rtl/, as a user would bring their own
// unit (docs/your-rtl.md). It implements the lirp pipeline's port contract (`phongsim contract
// lirp`) with another structure than rtl/lirp/lirp_unit.sv:
//
//   p = (1 - a)·p0 + a·p1   two products per component (rtl/ computes p0 + a·(p1 - p0)),
//                           the exact sum rounded once, so the result is the same value
//   4 register stages        inputs, products, sum, rounded output: latency 4 (rtl/: 3)
//   one stall signal         every stage holds while the output waits (rtl/: per-stage ready)
//
// Self-contained: no rtl/common, no package. Rounding and overflow follow docs/fixed-point.md.
// Parameters (all five are set from the configuration by phongsim, named as the contract names
// them): PFmt, AFmt, OutFmt - format words (signed * 65536 + int bits * 256 + fraction bits);
// OutRound - 0 floor, 1 nearest ties up, 2 nearest ties to even; OutOverflow - 0 wrap,
// 1 saturate. TiesUp - a deliberate bug for the failing example (my_lirp_wrong.sv): ties round
// up even in mode 2.
module my_lirp #(
  parameter int PFmt        = 32'h1010a,
  parameter int AFmt        = 32'h0010a,
  parameter int OutFmt      = 32'h1010a,
  parameter int OutRound    = 2,
  parameter int OutOverflow = 1,
  parameter bit TiesUp      = 1'b0,
  localparam int PS = PFmt / 65536, PF = PFmt % 256, PW = PS + (PFmt / 256) % 256 + PF,
  localparam int AS = AFmt / 65536, AF = AFmt % 256, AW = AS + (AFmt / 256) % 256 + AF,
  localparam int OS = OutFmt / 65536, OF = OutFmt % 256,
  localparam int OW = OS + (OutFmt / 256) % 256 + OF
) (
  input  logic            clk_i,
  input  logic            rst_ni,
  input  logic            in_valid_i,
  output logic            in_ready_o,
  input  logic [3*PW-1:0] in_p0_i,
  input  logic [3*PW-1:0] in_p1_i,
  input  logic [  AW-1:0] in_a_i,
  output logic            out_valid_o,
  input  logic            out_ready_i,
  output logic [3*OW-1:0] out_p_o
);

  // Wide enough for any product, sum and left shift these formats allow.
  localparam int EW   = PW + AW + OW + 8;
  localparam int Drop = PF + AF - OF;  // fraction bits the rounding removes (may be < 0)

  typedef logic signed [EW-1:0] wide_t;

  function automatic wide_t widen(input logic [63:0] bits, input int width, input bit is_signed);
    widen = '0;
    for (int i = 0; i < EW; i++) widen[i] = i < width ? bits[i] : (is_signed ? bits[width-1] : 1'b0);
  endfunction

  // One component: round the exact value (PF + AF fraction bits) to OF bits, then overflow.
  function automatic logic [OW-1:0] requantize(input wide_t exact);
    wide_t q, lo, rem, half, min_v, max_v;
    if (Drop <= 0) begin
      q = exact <<< (-Drop);
    end else begin
      lo   = exact >>> Drop;
      rem  = exact - (lo <<< Drop);
      half = EW'(1) <<< (Drop - 1);
      case (OutRound)
        0:       q = lo;
        1:       q = lo + EW'(rem >= half);
        default: q = lo + EW'(rem > half || (rem == half && (lo[0] || TiesUp)));
      endcase
    end
    min_v = OS != 0 ? -(EW'(1) <<< (OW - 1)) : '0;
    max_v = OS != 0 ? (EW'(1) <<< (OW - 1)) - 1 : (EW'(1) <<< OW) - 1;
    if (OutOverflow != 0) q = q < min_v ? min_v : (q > max_v ? max_v : q);
    requantize = q[OW-1:0];
  endfunction

  // One stall signal: everything moves when the output register is free or being taken.
  logic [3:0] valid_q;  // stage 1..4
  logic       move;
  assign move        = !valid_q[3] || out_ready_i;
  assign in_ready_o  = move;
  assign out_valid_o = valid_q[3];

  logic [3*PW-1:0] p0_q, p1_q;
  logic [  AW-1:0] a_q;
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      valid_q <= '0;
    end else if (move) begin
      valid_q <= {valid_q[2:0], in_valid_i};
    end
  end
  always_ff @(posedge clk_i) begin
    if (move) begin
      p0_q <= in_p0_i;
      p1_q <= in_p1_i;
      a_q  <= in_a_i;
    end
  end

  for (genvar c = 0; c < 3; c++) begin : g_component
    wide_t m0_q, m1_q, sum_q;
    logic [OW-1:0] p_q;
    always_ff @(posedge clk_i) begin
      if (move) begin
        m0_q  <= ((EW'(1) <<< AF) - widen(64'(a_q), AW, AS != 0))
                 * widen(64'(p0_q[c*PW+:PW]), PW, PS != 0);
        m1_q  <= widen(64'(a_q), AW, AS != 0) * widen(64'(p1_q[c*PW+:PW]), PW, PS != 0);
        sum_q <= m0_q + m1_q;
        p_q   <= requantize(sum_q);
      end
    end
    assign out_p_o[c*OW+:OW] = p_q;
  end

endmodule
