// shade_kb_top: Kuijk–Blake shading of whole scanline spans in colour (CWI CS-R8909, section 2:
// "two additions per pixel" per colour channel): span programs for R, G and B in, pixels
// (x, y, R, G, B) out, one per clock on long spans. The span setup (model/kb_setup) runs on the
// host; each channel's program is what one kb_engine takes (docs/kb.md).
//
// Input: a stream of words, each three kb_engine words side by side (sharing n and reload) plus
// the span's x0 and y. A span is a header word followed by count_r + count_g + count_b event
// words, the red channel's events first, then green's, then blue's:
//   header: n = last pixel index (the span's length - 1, the same for every channel), x, y = the
//           span's first pixel, per channel count, f, d1, d2 (kb_engine's header)
//   event:  for the first channel with events still due: n = pixel index, that channel's d1, d2,
//           reload (kb_engine's event); every other field is ignored
// Stages: input skid buffer -> demux (the parse above: a header goes to all three channels and
// the span queue, an event to one channel) -> per channel a FIFO of 2^EventBits words (a whole
// program: no channel waits for words held behind another's) and a kb_engine -> join (one pixel
// when all three engines have one: x = x0 + i, y from the span queue) -> output skid buffer.
// Specification: docs/shade_kb.md.
//
// Latency 5 cycles from a header to its first pixel (kb_engine alone: 2); throughput 1 pixel per
// clock on spans whose program words arrive ahead of their pixels.
// Parameters:
//   AccFmt    - format word of f, d1, d2 (signed), every channel
//   OutFmt    - output format word of a colour channel
//   OutRound  - fx_pkg rounding mode of the outputs
//   EventBits - width of each channel's count (up to 2^EventBits - 1 events per channel and span)
// Ports (fields packed from the LSB in the order listed):
//   clk_i, rst_ni            - clock; asynchronous reset, active low
//   in_valid_i, in_ready_o   - word handshake
//   in_n_i, in_x_i, in_y_i   - n, the span's x0 and y (CoordW bits each)
//   in_count_i               - count_r, count_g, count_b (EventBits each)
//   in_f_i, in_d1_i, in_d2_i - per channel r, g, b (AccW each)
//   in_reload_i              - an event's reload
//   out_valid_o, out_ready_i - pixel handshake
//   out_x_o, out_y_o         - the pixel
//   out_rgb_o                - R, G, B (OutW bits each)
//
// Assertions: the handshakes are the skid buffers' and FIFOs' (stream_check); the co-simulation
// harness checks that a stalled output stays valid and unchanged.
module shade_kb_top #(
  parameter bit [31:0] AccFmt    = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter bit [31:0] OutFmt    = fx_pkg::fx_fmt(1'b0, 0, 8),
  parameter bit [31:0] OutRound  = fx_pkg::FxHalfEven,
  parameter bit [31:0] EventBits = 5,
  // Derived, do not override.
  localparam bit [31:0] AccW     = fx_pkg::fx_width(AccFmt),
  localparam bit [31:0] OutW     = fx_pkg::fx_width(OutFmt),
  localparam bit [31:0] IdxBits  = 12,
  localparam bit [31:0] CoordW   = 11,  // screens up to 2048 x 2048, as quad_walker
  localparam bit [31:0] SpanBits = 3    // the span queue holds 8 spans
) (
  input  logic                   clk_i,
  input  logic                   rst_ni,
  input  logic                   in_valid_i,
  output logic                   in_ready_o,
  input  logic [    IdxBits-1:0] in_n_i,
  input  logic [     CoordW-1:0] in_x_i,
  input  logic [     CoordW-1:0] in_y_i,
  input  logic [3*EventBits-1:0] in_count_i,
  input  logic [     3*AccW-1:0] in_f_i,
  input  logic [     3*AccW-1:0] in_d1_i,
  input  logic [     3*AccW-1:0] in_d2_i,
  input  logic                   in_reload_i,
  output logic                   out_valid_o,
  input  logic                   out_ready_i,
  output logic [     CoordW-1:0] out_x_o,
  output logic [     CoordW-1:0] out_y_o,
  output logic [     3*OutW-1:0] out_rgb_o
);

  localparam bit [31:0] InW    = IdxBits + 2 * CoordW + 3 * EventBits + 9 * AccW + 1;
  localparam bit [31:0] EngineW = IdxBits + EventBits + 3 * AccW + 1;  // one kb_engine word

  // ---- Input word, registered by a skid buffer ----
  logic                   head_valid, pop;
  logic [    IdxBits-1:0] head_n;
  logic [     CoordW-1:0] head_x, head_y;
  logic [3*EventBits-1:0] head_count;
  logic [     3*AccW-1:0] head_f, head_d1, head_d2;
  logic                   head_reload;
  stream_skid #(.Width(InW)) u_in (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .in_data_i  ({in_n_i, in_x_i, in_y_i, in_count_i, in_f_i, in_d1_i, in_d2_i, in_reload_i}),
    .out_valid_o(head_valid),
    .out_ready_i(pop),
    .out_data_o ({head_n, head_x, head_y, head_count, head_f, head_d1, head_d2, head_reload})
  );

  // ---- Demux: the parse. left_q: each channel's event words still due in the current span ----
  logic [EventBits-1:0] left_q[3];
  logic                 is_header, span_ready;
  logic [2:0]           target, fifo_ready;
  assign is_header = left_q[0] == '0 && left_q[1] == '0 && left_q[2] == '0;
  // A header goes to every channel; an event to the first channel with events still due.
  assign target[0] = is_header | (left_q[0] != '0);
  assign target[1] = is_header | (left_q[0] == '0 && left_q[1] != '0);
  assign target[2] = is_header | (left_q[0] == '0 && left_q[1] == '0);
  assign pop = head_valid & ((fifo_ready & target) == target) & (span_ready | ~is_header);

  for (genvar ch = 0; ch < 3; ch++) begin : g_left
    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) begin
        left_q[ch] <= '0;
      end else if (pop && is_header) begin
        left_q[ch] <= head_count[ch*EventBits+:EventBits];
      end else if (pop && target[ch]) begin
        left_q[ch] <= left_q[ch] - 1'b1;
      end
    end
  end

  // ---- Span queue: x0 and y of every span whose header was read and whose pixels are not all
  // out ----
  logic              span_valid, join_fire, join_last;
  logic [CoordW-1:0] span_x, span_y;
  shade_kb_fifo #(.Width(2 * CoordW), .AddrBits(SpanBits)) u_spans (
    .clk_i,
    .rst_ni,
    .in_valid_i (head_valid & is_header & ((fifo_ready & target) == target)),
    .in_ready_o (span_ready),
    .in_data_i  ({head_y, head_x}),
    .out_valid_o(span_valid),
    .out_ready_i(join_fire & join_last),
    .out_data_o ({span_y, span_x})
  );

  // ---- Channels: a FIFO of one whole program, then the engine ----
  logic [     2:0] pixel_valid, pixel_last;
  logic [3*OutW-1:0] rgb;
  for (genvar ch = 0; ch < 3; ch++) begin : g_channel
    logic               word_valid, word_ready;
    logic [EngineW-1:0] word;
    logic [IdxBits-1:0] word_n;
    logic [EventBits-1:0] word_count;
    logic [AccW-1:0]      word_f, word_d1, word_d2;
    logic                 word_reload;
    shade_kb_fifo #(.Width(EngineW), .AddrBits(EventBits)) u_fifo (
      .clk_i,
      .rst_ni,
      .in_valid_i (head_valid & target[ch] & ((fifo_ready & target) == target) &
                   (span_ready | ~is_header)),
      .in_ready_o (fifo_ready[ch]),
      .in_data_i  ({head_n, head_count[ch*EventBits+:EventBits], head_f[ch*AccW+:AccW],
                    head_d1[ch*AccW+:AccW], head_d2[ch*AccW+:AccW], head_reload}),
      .out_valid_o(word_valid),
      .out_ready_i(word_ready),
      .out_data_o (word)
    );
    assign {word_n, word_count, word_f, word_d1, word_d2, word_reload} = word;
    kb_engine #(
      .AccFmt   (AccFmt),
      .OutFmt   (OutFmt),
      .OutRound (OutRound),
      .EventBits(EventBits)
    ) u_engine (
      .clk_i,
      .rst_ni,
      .in_valid_i (word_valid),
      .in_ready_o (word_ready),
      .in_n_i     (word_n),
      .in_count_i (word_count),
      .in_f_i     (word_f),
      .in_d1_i    (word_d1),
      .in_d2_i    (word_d2),
      .in_reload_i(word_reload),
      .out_valid_o(pixel_valid[ch]),
      .out_ready_i(join_fire),
      .out_value_o(rgb[ch*OutW+:OutW]),
      .out_last_o (pixel_last[ch])
    );
  end

  // ---- Join: a pixel when every channel has one; x = x0 + i ----
  logic              out_ready;
  logic [CoordW-1:0] i_q;
  assign join_fire = (&pixel_valid) & span_valid & out_ready;
  // Every channel's span has the header's length: the channels' last flags agree.
  assign join_last = pixel_last[0];

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      i_q <= '0;
    end else if (join_fire) begin
      i_q <= join_last ? '0 : i_q + 1'b1;
    end
  end

  logic unused_last;
  assign unused_last = ^pixel_last[2:1];

  // ---- Output skid buffer ----
  stream_skid #(.Width(2 * CoordW + 3 * OutW)) u_out (
    .clk_i,
    .rst_ni,
    .in_valid_i ((&pixel_valid) & span_valid),
    .in_ready_o (out_ready),
    .in_data_i  ({rgb, span_y, span_x + i_q}),
    .out_valid_o,
    .out_ready_i,
    .out_data_o ({out_rgb_o, out_y_o, out_x_o})
  );

endmodule
