// quad_walker_core: the quadratic (or linear) colour interpolator of Vlasic §4.3 in hardware: walks
// one triangle per program and emits (x, y, R, G, B) for every covered pixel, one per clock, each
// with its program's tag (side data the walker carries but never reads: the composed pipelines'
// per-triangle values, docs/shade_lyon.md). quad_walker is this core without a tag.
//
// Coverage is by span: for each row the program's three edge DDAs give the row's first and last
// covered pixel exactly (edge functions with the top-left fill rule, divided by the setup, then
// advanced per row with additions only: q <- q + dq + carry, r <- r + dr - carry·d, where carry =
// r + dr >= d; a "lower" edge bounds x from below by -q, an "upper" edge from above by q). The
// colour of each channel is forward differenced (quad_channel). A linear (Gouraud) triangle is
// the same program with a = b = c = 0. State machine (state_e): Idle (no triangle) -> Row (set up
// row y's span) -> Pixels (emit its pixels) -> Row ... -> Idle or, in the cycle the last row
// ends, straight to the next triangle's first Row.
//
// Latency 4 cycles at least from a program to its first pixel (input skid buffer, row set-up,
// output skid buffer). Throughput: one cycle per row of the program's row range plus one per
// covered pixel; a triangle's program is read in the cycle its last row finishes, so triangles
// stream without further gaps; a program with no rows costs one cycle. Specification and fill
// rule: docs/quad.md.
// Parameters:
//   AccFmt   - signed accumulator format word of the channels
//   OutFmt   - colour output format word
//   OutRound - fx_pkg rounding mode of the colour output
//   SubBits  - subpixel bits of the setup (sets the DDA widths QW and RW)
//   TagW     - bits of the tag
// Ports (fields packed from the LSB in the order listed):
//   clk_i, rst_ni            - clock; asynchronous reset, active low
//   in_valid_i, in_ready_o   - program handshake
//   in_bbox_i                - x0, y0, x1, y1 (CoordW bits each): rows y0..y1, columns x0..x1
//   in_edge0_i .. in_edge2_i - per edge: kind (2 bits), q, r, d, dq, dr
//   in_red_i, in_green_i, in_blue_i - per channel: f, gy, gx, a, b, c (AccW bits each)
//   in_tag_i                 - the program's tag
//   out_valid_o, out_ready_i - pixel handshake
//   out_x_o, out_y_o         - the pixel
//   out_rgb_o                - R, G, B (OutW bits each)
//   out_tag_o                - the tag of the pixel's program
//
// Assertions: the handshakes are the skid buffers' (tests/stream_rtl_test.cpp); the co-simulation
// harness checks that a stalled output stays valid and unchanged.
module quad_walker_core #(
  parameter bit [31:0] AccFmt   = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter bit [31:0] OutFmt   = fx_pkg::fx_fmt(1'b0, 0, 8),
  parameter bit [31:0] OutRound = fx_pkg::FxHalfEven,
  parameter bit [31:0] SubBits  = 4,
  parameter bit [31:0] TagW     = 1,
  // Derived, do not override.
  localparam bit [31:0] AccW    = fx_pkg::fx_width(AccFmt),
  localparam bit [31:0] OutW    = fx_pkg::fx_width(OutFmt),
  localparam bit [31:0] CoordW  = 11,                 // screens up to 2048 x 2048
  localparam bit [31:0] QW      = 26 + 2 * SubBits,   // DDA quotient (signed)
  localparam bit [31:0] RW      = 12 + 2 * SubBits,   // DDA remainder and divisor
  localparam bit [31:0] EdgeW   = 2 + 2 * QW + 3 * RW,
  localparam bit [31:0] ChanW   = 6 * AccW
) (
  input  logic              clk_i,
  input  logic              rst_ni,
  input  logic              in_valid_i,
  output logic              in_ready_o,
  input  logic [4*CoordW-1:0] in_bbox_i,
  input  logic [   EdgeW-1:0] in_edge0_i,
  input  logic [   EdgeW-1:0] in_edge1_i,
  input  logic [   EdgeW-1:0] in_edge2_i,
  input  logic [   ChanW-1:0] in_red_i,
  input  logic [   ChanW-1:0] in_green_i,
  input  logic [   ChanW-1:0] in_blue_i,
  input  logic [    TagW-1:0] in_tag_i,
  output logic              out_valid_o,
  input  logic              out_ready_i,
  output logic [  CoordW-1:0] out_x_o,
  output logic [  CoordW-1:0] out_y_o,
  output logic [  3*OutW-1:0] out_rgb_o,
  output logic [    TagW-1:0] out_tag_o
);

  localparam bit [31:0] ProgW = 4 * CoordW + 3 * EdgeW + 3 * ChanW + TagW;
  localparam logic [1:0] KindLower = 2'd1;
  localparam logic [1:0] KindUpper = 2'd2;

  // ---- Program, registered by a skid buffer ----
  logic              head_valid, load;
  logic [ProgW-1:0]  head;
  stream_skid #(.Width(ProgW)) u_in (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .in_data_i  ({
      in_tag_i, in_blue_i, in_green_i, in_red_i, in_edge2_i, in_edge1_i, in_edge0_i, in_bbox_i
    }),
    .out_valid_o(head_valid),
    .out_ready_i(load),
    .out_data_o (head)
  );
  logic [CoordW-1:0] p_x0, p_y0, p_x1, p_y1;
  assign {p_y1, p_x1, p_y0, p_x0} = head[4*CoordW-1:0];

  // ---- State ----
  typedef enum logic [1:0] {
    Idle   = 2'd0,  // no triangle
    Row    = 2'd1,  // setting up the span of row y_q
    Pixels = 2'd2   // emitting pixels x_q .. xr_q of row y_q
  } state_e;
  state_e            state_q, state_d;
  logic [CoordW-1:0] x0_q, x1_q, y1_q, y_q, x_q, xr_q;
  logic [  TagW-1:0] tag_q;

  logic fire, out_ready, row_empty, row_done, tri_done, row_start, row_next;
  logic signed [QW:0] lower, upper;  // the row's span before clamping to the box

  // ---- Edge DDAs: q and kind of every edge, gathered for the span logic ----
  logic [3*QW-1:0] q_bus;
  logic [     5:0] kind_bus;
  for (genvar k = 0; k < 3; k++) begin : g_edge
    logic [1:0] kind, kind_q;
    logic [QW-1:0] q0, dq, q_q, dq_q;
    logic [RW-1:0] r0, d, dr, r_q, d_q, dr_q;
    logic [RW:0] sum;
    logic carry;
    assign {dr, dq, d, r0, q0, kind} = head[4*CoordW+k*EdgeW+:EdgeW];
    assign sum   = {1'b0, r_q} + {1'b0, dr_q};
    assign carry = sum >= {1'b0, d_q};
    always_ff @(posedge clk_i) begin
      if (load) begin
        kind_q <= kind;
        q_q    <= q0;
        r_q    <= r0;
        d_q    <= d;
        dq_q   <= dq;
        dr_q   <= dr;
      end else if (row_next) begin
        q_q <= q_q + dq_q + QW'(carry);
        r_q <= carry ? RW'(sum - {1'b0, d_q}) : RW'(sum);
      end
    end
    assign q_bus[k*QW+:QW] = q_q;
    assign kind_bus[2*k+:2] = kind_q;
  end

  // The row's span: the tightest bounds of the edges, then the box.
  logic signed [QW:0] q_ext[3];
  for (genvar k = 0; k < 3; k++) begin : g_q_ext
    assign q_ext[k] = (QW + 1)'($signed(q_bus[k*QW+:QW]));
  end
  always_comb begin
    lower = $signed({{(QW + 1 - CoordW) {1'b0}}, x0_q});
    upper = $signed({{(QW + 1 - CoordW) {1'b0}}, x1_q});
    for (int k = 0; k < 3; k++) begin
      if (kind_bus[2*k+:2] == KindLower && 0 - q_ext[k] > lower) lower = 0 - q_ext[k];  // phongsim: waive-begin narrow
      if (kind_bus[2*k+:2] == KindUpper && q_ext[k] < upper) upper = q_ext[k];  // phongsim: waive-end narrow
    end
  end
  assign row_empty = lower > upper;

  // ---- Control ----
  logic emitting;  // in Pixels: offering a pixel (a named signal: Icarus 11 mistypes the enum otherwise)
  assign emitting  = state_q == Pixels;
  assign fire      = emitting && out_ready;
  assign row_start = state_q == Row && !row_empty;
  assign row_done  = (state_q == Row && row_empty) || (fire && x_q == xr_q);
  assign tri_done  = row_done && y_q == y1_q;
  assign row_next  = row_done && !tri_done;
  assign load      = head_valid && (state_q == Idle || tri_done);

  always_comb begin
    state_d = state_q;
    if (load) begin
      if (p_y0 <= p_y1) begin
        state_d = Row;
      end else begin
        state_d = Idle;  // a program with no rows leaves nothing to walk
      end
    end else if (tri_done) begin
      state_d = Idle;
    end else if (row_next) begin
      state_d = Row;
    end else if (row_start) begin
      state_d = Pixels;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      state_q <= Idle;
    end else begin
      state_q <= state_d;
    end
  end

  // Data registers need no reset: they are only used while a triangle is walked.
  always_ff @(posedge clk_i) begin
    if (load) begin
      x0_q <= p_x0;
      x1_q <= p_x1;
      y1_q <= p_y1;
      y_q  <= p_y0;
      tag_q <= head[ProgW-1-:TagW];
    end else if (row_next) begin
      y_q <= y_q + 1'b1;
    end
    if (row_start) begin
      x_q  <= lower[CoordW-1:0];
      xr_q <= upper[CoordW-1:0];
    end else if (fire) begin
      x_q <= x_q + 1'b1;
    end
  end

  // ---- Channels ----
  logic [3*OutW-1:0] rgb;
  logic [CoordW-1:0] i0;  // the row's first pixel, as an offset from the box's left column
  assign i0 = lower[CoordW-1:0] - x0_q;
  for (genvar ch = 0; ch < 3; ch++) begin : g_channel
    logic [ChanW-1:0] word;
    assign word = head[4*CoordW+3*EdgeW+ch*ChanW+:ChanW];
    quad_channel #(
      .AccFmt  (AccFmt),
      .OutFmt  (OutFmt),
      .OutRound(OutRound),
      .I0Bits  (CoordW)
    ) u_channel (
      .clk_i,
      .load_i     (load),
      .f00_i      (word[0*AccW+:AccW]),
      .gy0_i      (word[1*AccW+:AccW]),
      .gx0_i      (word[2*AccW+:AccW]),
      .a_i        (word[3*AccW+:AccW]),
      .b_i        (word[4*AccW+:AccW]),
      .c_i        (word[5*AccW+:AccW]),
      .row_start_i(row_start),
      .i0_i       (i0),
      .pixel_i    (fire),
      .row_next_i (row_next),
      .value_o    (rgb[ch*OutW+:OutW])
    );
  end

  // ---- Output skid buffer ----
  stream_skid #(.Width(TagW + 2 * CoordW + 3 * OutW)) u_out (
    .clk_i,
    .rst_ni,
    .in_valid_i (emitting),
    .in_ready_o (out_ready),
    .in_data_i  ({tag_q, rgb, y_q, x_q}),
    .out_valid_o,
    .out_ready_i,
    .out_data_o ({out_tag_o, out_rgb_o, out_y_o, out_x_o})
  );

endmodule
