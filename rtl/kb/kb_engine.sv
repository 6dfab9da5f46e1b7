// kb_engine: the Kuijk–Blake forward-differencing engine (CWI CS-R8909, section 2: a piecewise
// quadratic evaluated "by forward differencing ... two additions per pixel", the second
// difference "changed where the curve changes section"). One engine serves one term or several
// summed terms: the span's program says where the second difference changes.
//
// Input: a stream of words. A span is a header word followed by `count` event words:
//   header:  n = index of the last pixel (span length n + 1, 1..4096), count, f = f(0),
//            d1 = Δf(0), d2 = Δ²f(0)                       (f, d1, d2 in AccFmt)
//   event:   n = pixel index; at that pixel d2 <- d2 of the event, and d1 <- d1 of the event
//            when reload is set; they take effect for the step to the next pixel.
// Per pixel i:  out = rq(clamp01(f), OutFmt) (fx_rq: OutRound, saturating);
//               then f <- f + d1, d1 <- d1 + d2 (fdiff_acc, wrap).
// An event is applied at the first pixel whose index reaches its n; a pixel that may still need
// an event waits until the next event word has arrived. Event words left over when the span has
// ended are read and dropped before the next header. Spans whose events lie before their last
// pixel (what the setup writes) stream back to back without bubbles.
// Specification: docs/kb.md.
//
// Latency 2 cycles from a header to its first pixel; throughput 1 pixel per clock.
// Parameters:
//   AccFmt    - format word of f, d1, d2 (signed)
//   OutFmt    - output format word
//   OutRound  - fx_pkg rounding mode of the output
//   EventBits - width of count (up to 2^EventBits - 1 events per span)
// Ports:
//   clk_i, rst_ni            - clock; asynchronous reset, active low
//   in_valid_i, in_ready_o   - word handshake
//   in_n_i, in_count_i, in_f_i, in_d1_i, in_d2_i, in_reload_i - the word's fields (above)
//   out_valid_o, out_ready_i - pixel handshake
//   out_value_o              - the pixel's value
//   out_last_o               - the pixel is its span's last
//
// Assertions: AccFmt must be signed (elaboration check at the end); the handshakes are the skid
// buffers' (tests/stream_rtl_test.cpp) and the co-simulation harness checks the output's.
module kb_engine #(
  parameter int unsigned AccFmt    = fx_pkg::fx_fmt(1'b1, 2, 32),
  parameter int unsigned OutFmt    = fx_pkg::fx_fmt(1'b0, 0, 8),
  parameter int unsigned OutRound  = fx_pkg::FxHalfEven,
  parameter int unsigned EventBits = 5,
  // Derived, do not override.
  localparam int unsigned AccW     = fx_pkg::fx_width(AccFmt),
  localparam int unsigned OutW     = fx_pkg::fx_width(OutFmt),
  localparam int unsigned IdxBits  = 12
) (
  input  logic                 clk_i,
  input  logic                 rst_ni,
  input  logic                 in_valid_i,
  output logic                 in_ready_o,
  input  logic [  IdxBits-1:0] in_n_i,
  input  logic [EventBits-1:0] in_count_i,
  input  logic [     AccW-1:0] in_f_i,
  input  logic [     AccW-1:0] in_d1_i,
  input  logic [     AccW-1:0] in_d2_i,
  input  logic                 in_reload_i,
  output logic                 out_valid_o,
  input  logic                 out_ready_i,
  output logic [     OutW-1:0] out_value_o,
  output logic                 out_last_o
);

  localparam int unsigned WordW = IdxBits + EventBits + 3 * AccW + 1;

  // ---- Input word, registered by a skid buffer ----
  logic                 head_valid, pop;
  logic [IdxBits-1:0]   head_n;
  logic [EventBits-1:0] head_count;
  logic [AccW-1:0]      head_f, head_d1, head_d2;
  logic                 head_reload;
  stream_skid #(.Width(WordW)) u_in (
    .clk_i,
    .rst_ni,
    .in_valid_i,
    .in_ready_o,
    .in_data_i  ({in_n_i, in_count_i, in_f_i, in_d1_i, in_d2_i, in_reload_i}),
    .out_valid_o(head_valid),
    .out_ready_i(pop),
    .out_data_o ({head_n, head_count, head_f, head_d1, head_d2, head_reload})
  );

  // ---- Span state ----
  logic                 running_q;
  logic [EventBits-1:0] remaining_q;
  logic [IdxBits-1:0]   i_q, last_q;
  logic [AccW-1:0]      d2_q, f, d1;

  logic pixel_ready, out_ready, fire, apply_event, is_last, take_header, drain;
  logic [EventBits-1:0] remaining_after;
  logic [AccW-1:0] d1_step, d2_step;

  // A pixel can go out unless an event may still be due and its word has not arrived.
  assign pixel_ready = running_q & ((remaining_q == '0) | head_valid);
  assign fire        = pixel_ready & out_ready;
  assign apply_event = fire & (remaining_q != '0) & (head_n <= i_q);
  assign is_last     = i_q == last_q;
  assign remaining_after = remaining_q - EventBits'(apply_event);
  // The next header is read when idle, or in the cycle the last pixel leaves (no bubble).
  assign take_header = head_valid & ~apply_event & (remaining_after == '0) &
                       (~running_q | (fire & is_last));
  // Event words left over after the span: read and dropped.
  assign drain       = head_valid & ~running_q & (remaining_q != '0);
  assign pop         = apply_event | take_header | drain;

  assign d1_step = apply_event & head_reload ? head_d1 : d1;
  assign d2_step = apply_event ? head_d2 : d2_q;

  fdiff_acc #(.Width(AccW)) u_acc (
    .clk_i,
    .load_i   (take_header),
    .f_i      (head_f),
    .d1_i     (head_d1),
    .step_i   (fire),
    .d1_step_i(d1_step),
    .d2_step_i(d2_step),
    .f_o      (f),
    .d1_o     (d1)
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      running_q   <= 1'b0;
      remaining_q <= '0;
    end else if (take_header) begin
      running_q   <= 1'b1;
      remaining_q <= head_count;
    end else if (fire) begin
      running_q   <= ~is_last;
      remaining_q <= remaining_after;
    end else if (drain) begin
      remaining_q <= remaining_q - 1'b1;
    end
  end

  // Data registers need no reset: they are only used while a span runs.
  always_ff @(posedge clk_i) begin
    if (take_header) begin
      i_q    <= '0;
      last_q <= head_n;
      d2_q   <= head_d2;
    end else if (fire) begin
      i_q  <= i_q + 1'b1;
      d2_q <= d2_step;
    end
  end

  // ---- Output: clamp to [0, 1], round, skid buffer ----
  logic [AccW-1:0] clamped;
  fx_clamp01 #(.AFmt(AccFmt)) u_clamp (
    .a_i      (f),
    .clamped_o(clamped)
  );
  logic [OutW-1:0] value;
  fx_rq #(.InFmt(AccFmt), .OutFmt(OutFmt), .Round(OutRound))
      u_value (.in_i(clamped), .out_o(value));

  stream_skid #(.Width(OutW + 1)) u_out (
    .clk_i,
    .rst_ni,
    .in_valid_i (pixel_ready),
    .in_ready_o (out_ready),
    .in_data_i  ({value, is_last}),
    .out_valid_o,
    .out_ready_i,
    .out_data_o ({out_value_o, out_last_o})
  );

  // Assertions: elaboration-time parameter checks.
  if (!fx_pkg::fx_signed(AccFmt)) begin : g_bad_acc
    $error("kb_engine: AccFmt must be signed (differences are negative)");
  end

endmodule
