// Kuijk–Blake shading of scanline spans in colour: the registry entry (docs/shade_kb.md). Its
// input is a stream of span words (a header, then each channel's event words), so random vectors
// come in chunks of kChunkWords words, like kb's: each chunk is one span (the three channels'
// programs for one length: each channel half a setup program of a random angular span, half a
// random well-formed program with arbitrary values, sim/pipelines/kb.h) followed by one-pixel
// filler spans, derived from (seed, chunk). Directed vectors are kb's directed programs, each in
// every channel in turn (the other two channels flat), and the spans that only colour has: an
// x that wraps, every channel with the most events at once, the screen's corners.
#include "sim/pipelines/shade_kb.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>

#include "base/error.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "model/shade_kb.h"
#include "sim/pipelines/kb.h"

namespace phongsim {
namespace {

using Word = std::vector<std::int64_t>;  // ShadeKbModel's inputs
using Program = std::vector<Word>;       // kb words: n, count, f, d1, d2, reload
using M = ShadeKbModel;
constexpr const char* kChannelNames[] = {"r", "g", "b"};
constexpr std::int64_t kScreen = std::int64_t{1} << M::kCoordBits;

// The kb programs of `words` (a header, then `count` words each).
std::vector<Program> split_programs(const std::vector<Word>& words) {
  std::vector<Program> programs;
  for (std::size_t k = 0; k < words.size();) {
    const auto count = static_cast<std::size_t>(words[k][1]);
    programs.emplace_back(
        words.begin() + static_cast<std::ptrdiff_t>(k),
        words.begin() + static_cast<std::ptrdiff_t>(std::min(words.size(), k + 1 + count)));
    k += 1 + count;
  }
  return programs;
}

// A program of `last` + 1 pixels at `value` without events.
Program flat(std::int64_t last, std::int64_t value) { return {{last, 0, value, 0, 0, 0}}; }

}  // namespace

std::vector<std::vector<std::int64_t>> shade_kb_span_words(
    const std::array<std::vector<std::vector<std::int64_t>>, 3>& programs, std::int64_t x,
    std::int64_t y, std::int64_t filler) {
  std::vector<Word> words;
  Word h(M::kInputs, 0);
  h[M::kN] = programs[0][0][0];
  h[M::kX] = x;
  h[M::kY] = y;
  for (std::size_t c = 0; c < 3; ++c) {
    const Word& ph = programs[c][0];
    h[M::kCount + c] = ph[1];
    h[M::kF + c] = ph[2];
    h[M::kD1 + c] = ph[3];
    h[M::kD2 + c] = ph[4];
  }
  words.push_back(h);
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t k = 1; k < programs[c].size(); ++k) {
      const Word& e = programs[c][k];
      Word w(M::kInputs, filler);
      w[M::kN] = e[0];
      w[M::kX] = filler & (kScreen - 1);
      w[M::kY] = filler & (kScreen - 1);
      for (std::size_t o = 0; o < 3; ++o) w[M::kCount + o] = 0;
      w[M::kD1 + c] = e[3];
      w[M::kD2 + c] = e[4];
      w[M::kReload] = e[5];
      words.push_back(w);
    }
  }
  return words;
}

namespace {

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const KbFormats formats = KbFormats::from_config(cfg);
  (void)KbSetupOptions::from_config(cfg);  // the stimulus reads it; check it here
  cfg.check_all_used();
  if (formats.event_bits > 8) {
    cfg.fail(fmt::format(
        "[param] event_bits = {}: each channel's FIFO holds 2^event_bits words; at most 8",
        formats.event_bits));
  }
  try {
    return std::make_unique<ShadeKbModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

Stimulus make_stimulus(const PipelineModel& model, const Config& cfg) {
  const KbSetupOptions setup = KbSetupOptions::from_config(cfg);
  const KbFormats f = dynamic_cast<const ShadeKbModel&>(model).formats();
  const std::uint64_t max_events = (std::uint64_t{1} << f.event_bits) - 1;
  const std::int64_t one = std::int64_t{1} << f.acc.frac_bits;
  const std::int64_t garbage = f.acc.max_raw();  // in fields a word's channel does not read

  // Directed: each of kb's directed programs in every channel in turn, the others flat, at
  // spans along the screen; then what only colour has.
  std::vector<Word> d;
  const auto add = [&d](const std::vector<Word>& words) {
    d.insert(d.end(), words.begin(), words.end());
  };
  std::int64_t k = 0;
  for (const Program& p : split_programs(kb_directed_words(f))) {
    const std::int64_t last = p[0][0];
    for (std::size_t c = 0; c < 3; ++c) {
      std::array<Program, 3> programs{flat(last, one / 4), flat(last, one / 2), flat(last, one)};
      programs[c] = p;
      add(shade_kb_span_words(programs, (37 * k) % (kScreen - last > 0 ? kScreen - last : 1),
                              (k * 13) % kScreen, garbage));
      ++k;
    }
  }
  // An x that wraps past the screen's right edge; the screen's corners.
  add(shade_kb_span_words({flat(15, one / 3), flat(15, one / 5), flat(15, one / 7)}, kScreen - 4,
                          kScreen - 1, garbage));
  add(shade_kb_span_words({flat(0, 0), flat(0, one), flat(0, one / 2)}, 0, 0));
  add(shade_kb_span_words({flat(0, one), flat(0, 0), flat(0, one / 2)}, kScreen - 1, kScreen - 1));
  // Every channel with the most events at once (each channel's FIFO holds the whole program),
  // red's spread over a long span so that green and blue wait behind it.
  {
    const auto last = static_cast<std::int64_t>(40 * max_events + 3);
    std::array<Program, 3> programs{flat(last, one / 2), flat(last, one / 3), flat(last, one / 4)};
    for (std::uint64_t e = 0; e < max_events; ++e) {
      const auto at = static_cast<std::int64_t>(e);
      programs[0].push_back({40 * at, 0, 0, one >> 9, -(one >> 16), e % 2 == 0 ? 1 : 0});
      programs[1].push_back({at, 0, 0, -(one >> 10), one >> 14, e % 3 == 0 ? 1 : 0});
      programs[2].push_back(
          {last - static_cast<std::int64_t>(max_events) + at, 0, 0, one >> 8, 0, 1});
      for (auto& p : programs) p[0][1] = static_cast<std::int64_t>(max_events);
    }
    add(shade_kb_span_words(programs, 100, 200, garbage));
  }
  for (int s = 0; s < 4; ++s) {  // back-to-back one-pixel spans
    add(shade_kb_span_words({flat(0, s * one / 4), flat(0, one - s * one / 4), flat(0, one / 2)}, s,
                            7));
  }

  // Random: one span (at most 1 + 3 max_events words) and at least one filler word per chunk.
  return span_stimulus(
      model, std::move(d), 3 * max_events + 2,
      [f, setup, max_events](Rng& rng) {
        const auto length = static_cast<int>(std::max(
            1.0, std::min(4096.0, std::floor(std::exp(rng.uniform() * std::log(4097.0))))));
        std::array<Program, 3> programs;
        for (Program& p : programs) {
          if (rng.below(2) == 0) {
            p = kb_random_words(rng, f, max_events, length);
          } else {
            KbSpan span = kb_random_span(rng, setup, length);
            p = kb_fitting_program(span, f, setup);
          }
        }
        // x0 on the screen with the span (one time in eight anywhere: x wraps), any y.
        const auto room =
            static_cast<std::uint64_t>(std::max<std::int64_t>(kScreen - length, 0) + 1);
        const auto x = static_cast<std::int64_t>(
            rng.below(8) == 0 ? rng.below(std::uint64_t{kScreen}) : rng.below(room));
        const auto y = static_cast<std::int64_t>(rng.below(std::uint64_t{kScreen}));
        return shade_kb_span_words(programs, x, y,
                                   static_cast<std::int64_t>(rng.below(std::uint64_t{1} << 30)));
      },
      Word(M::kInputs, 0));  // filler: one-pixel spans without events
}

// kb's contract for each channel's program (its clauses in its order), then the span on the
// screen: x0 + n < 2048 (x wraps otherwise). A header is checked in every channel.
InputContract contract(const PipelineModel& model, const Config&) {
  const KbFormats f = dynamic_cast<const ShadeKbModel&>(model).formats();
  InputContract kb = kb_input_contract(f);
  std::vector<std::string> clauses = kb.clauses();
  const int screen = static_cast<int>(clauses.size());
  clauses.push_back("span on the screen: x0 + n < 2048");
  struct Parse {
    std::array<InputContract, 3> channels;
    std::array<std::int64_t, 3> left{};
  };
  return InputContract(std::move(clauses), [screen, s = Parse{{kb, kb, kb}, {}}](
                                               std::span<const std::int64_t> in) mutable {
    // The demux's route (ShadeKbModel::route): a header to every channel, an event to the first
    // channel with events still due.
    const bool header = s.left[0] == 0 && s.left[1] == 0 && s.left[2] == 0;
    const std::size_t first = s.left[0] != 0 ? 0 : s.left[1] != 0 ? 1 : 2;
    int broken = InputContract::kIn;
    for (std::size_t c = 0; c < 3; ++c) {
      if (!header && c != first) continue;
      const int b = s.channels[c].check(M::channel_word(in, static_cast<int>(c)));
      if (b != InputContract::kIn && (broken == InputContract::kIn || b < broken)) broken = b;
    }
    if (!header) --s.left[first];
    if (header) {
      for (std::size_t c = 0; c < 3; ++c) s.left[c] = in[M::kCount + c];
      if (broken == InputContract::kIn && in[M::kX] + in[M::kN] >= kScreen) broken = screen;
    }
    return broken;
  });
}

int latency(const Config&) { return 5; }  // header word to its first pixel (docs/shade_kb.md)

// ---- the cycle model: shade_kb_top's control, clock by clock ----

// stream_skid: a main and a spare slot, each holding what it carries (`T`).
template <class T>
struct Skid {
  bool main = false, spare = false;
  T main_d{}, spare_d{};
  [[nodiscard]] bool ready() const { return !spare; }
  void clock(bool in_valid, const T& in, bool out_ready) {
    const bool in_fire = in_valid && !spare;
    if (!main || out_ready) {
      if (spare) {
        main_d = spare_d;
        spare = false;
      } else {
        main = in_fire;
        main_d = in;
      }
    } else if (in_fire) {
      spare = true;
      spare_d = in;
    }
  }
};

// shade_kb_top's control (its signal names), with the source offering a word every cycle and the
// sink always ready, from reset: the word accepted in cycle 0 is the demux's from cycle 1. Words
// are carried as their indices; a pixel as the header word of its span and its last flag.
FrameCycles cycles(const Config& cfg, std::span<const std::int64_t> in,
                   std::span<const std::int64_t> out, std::span<const std::uint32_t> counts,
                   std::vector<FrameCycles>* per_vector) {
  const std::size_t words = counts.size(), fields = words == 0 ? 0 : in.size() / words;
  if (per_vector != nullptr) per_vector->assign(words, {});
  const std::uint64_t expected = out.size() / 5;
  if (expected == 0) return {};
  const int event_bits = static_cast<int>(cfg.param("event_bits", 1, 16));
  const std::size_t fifo_depth = std::size_t{1} << event_bits, span_depth = 8;
  const auto field = [&](std::size_t w, std::size_t k) { return in[w * fields + k]; };

  struct Pixel {
    std::size_t span = 0;
    bool last = false;
  };
  struct Engine {
    Skid<std::size_t> in;  // kb_engine's input skid buffer (word indices)
    Skid<Pixel> out;       // its output skid buffer
    std::deque<std::size_t> fifo;
    bool running = false;
    std::int64_t remaining = 0, i = 0, last = 0;
    std::size_t span = 0;  // the header word of the span it runs
  };
  std::array<Engine, 3> eng;
  Skid<std::size_t> u_in;
  Skid<std::size_t> u_out;  // the header word of the pixel's span
  std::deque<std::size_t> spans;
  std::array<std::int64_t, 3> left{};
  std::size_t next = 0;
  FrameCycles total;
  std::uint64_t taken = 0, gap = 0;
  const std::uint64_t fill = static_cast<std::uint64_t>(latency(cfg));
  for (std::uint64_t t = 0;; ++t) {
    if (t > 64 * (words + expected) + 10000) {
      throw Error("shade_kb cycle model: the stream does not finish (a bug in the model)");
    }
    // ---- output ----
    if (u_out.main) {
      ++taken;
      if (per_vector != nullptr) {
        FrameCycles& own = (*per_vector)[u_out.main_d];
        ++own.outputs;
        own.cycles += 1 + gap;
        own.setup_cycles += gap;
      }
      total.outputs = taken;
      total.cycles = t + 1;
      gap = 0;
      if (taken == expected) break;
    } else if (t >= fill) {
      ++gap;
    }
    // ---- combinational ----
    bool pixels = !spans.empty();
    for (const Engine& e : eng) pixels = pixels && e.out.main;
    const bool join_fire = pixels && u_out.ready();
    const bool join_last = eng[0].out.main_d.last;
    std::array<bool, 3> pixel_ready{}, fire{}, is_last{}, take{}, drain{}, apply{}, pop_e{};
    for (std::size_t c = 0; c < 3; ++c) {
      Engine& e = eng[c];
      const bool head_valid = e.in.main;
      const std::int64_t head_n = head_valid ? field(e.in.main_d, M::kN) : 0;
      pixel_ready[c] = e.running && (e.remaining == 0 || head_valid);
      fire[c] = pixel_ready[c] && e.out.ready();
      apply[c] = fire[c] && e.remaining != 0 && head_n <= e.i;
      is_last[c] = e.i == e.last;
      const std::int64_t remaining_after = e.remaining - (apply[c] ? 1 : 0);
      take[c] = head_valid && !apply[c] && remaining_after == 0 &&
                (!e.running || (fire[c] && is_last[c]));
      drain[c] = head_valid && !e.running && e.remaining != 0;
      pop_e[c] = apply[c] || take[c] || drain[c];
    }
    const bool head_valid = u_in.main;
    const bool is_header = left[0] == 0 && left[1] == 0 && left[2] == 0;
    std::array<bool, 3> target{is_header || left[0] != 0,
                               is_header || (left[0] == 0 && left[1] != 0),
                               is_header || (left[0] == 0 && left[1] == 0)};
    bool room = !is_header || spans.size() < span_depth;
    for (std::size_t c = 0; c < 3; ++c)
      room = room && (!target[c] || eng[c].fifo.size() < fifo_depth);
    const bool pop = head_valid && room;
    const std::size_t w = u_in.main_d;
    // ---- clock ----
    u_out.clock(pixels, spans.empty() ? 0 : spans.front(), true);
    for (std::size_t c = 0; c < 3; ++c) {
      Engine& e = eng[c];
      const std::size_t head = e.in.main_d;
      e.out.clock(pixel_ready[c], {e.span, is_last[c]}, join_fire);
      const bool fifo_pop = !e.fifo.empty() && e.in.ready();
      e.in.clock(!e.fifo.empty(), e.fifo.empty() ? 0 : e.fifo.front(), pop_e[c]);
      if (take[c]) {
        e.running = true;
        e.remaining = field(head, M::kCount + c);
        e.i = 0;
        e.last = field(head, M::kN);
        e.span = head;
      } else if (fire[c]) {
        e.running = !is_last[c];
        e.remaining -= apply[c] ? 1 : 0;
        ++e.i;
      } else if (drain[c]) {
        --e.remaining;
      }
      if (fifo_pop) e.fifo.pop_front();
      if (pop && target[c]) e.fifo.push_back(w);
    }
    if (join_fire && join_last) spans.pop_front();
    if (pop && is_header) spans.push_back(w);
    if (pop) {
      for (std::size_t c = 0; c < 3; ++c) {
        if (is_header) {
          left[c] = field(w, M::kCount + c);
        } else if (target[c]) {
          --left[c];
        }
      }
    }
    const bool offered = next < words;
    const bool accepted = offered && u_in.ready();
    u_in.clock(offered, next, pop);
    if (accepted) ++next;
  }
  total.fill_cycles = fill;
  total.setup_cycles = total.cycles - fill - total.outputs;
  return total;
}

// A word's stages: for each channel that takes it, the accumulator f of every pixel its engine
// emits (before clamping and rounding) and that pixel's value; then every pixel the join emits.
std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  auto& m = dynamic_cast<ShadeKbModel&>(model);
  std::array<std::vector<std::int64_t>, 3> acc;
  for (int c = 0; c < 3; ++c) m.engine(c).trace_accumulator(&acc[static_cast<std::size_t>(c)]);
  std::vector<std::int64_t> out;
  (void)m.eval(in, out);
  for (int c = 0; c < 3; ++c) m.engine(c).trace_accumulator(nullptr);
  const KbFormats& f = m.formats();
  std::vector<StageValue> s;
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t k = 0; k < acc[c].size(); ++k) {
      s.push_back(
          {fmt::format("engine_{}.pixel{}.f", kChannelNames[c], k), fx::Fixed{acc[c][k], f.acc}});
      s.push_back({fmt::format("engine_{}.pixel{}.value", kChannelNames[c], k),
                   fx::Fixed{m.engine(static_cast<int>(c)).output(acc[c][k]), f.out}});
    }
  }
  const auto& outs = m.outputs();
  for (std::size_t p = 0; p < out.size() / outs.size(); ++p) {
    for (std::size_t o = 0; o < outs.size(); ++o) {
      s.push_back({fmt::format("join.pixel{}.{}", p, outs[o].name),
                   fx::Fixed{out[p * outs.size() + o], outs[o].fmt}});
    }
  }
  return s;
}

// kb's coverpoints (sim/pipelines/kb.h, KbCoverpoints), counted over the three channels' word
// streams, and the span's own: an x that wraps past the screen's edge, events in every channel
// of one span.
CoverpointSampler coverpoints(const PipelineModel& model, const Config&) {
  const KbFormats f = dynamic_cast<const ShadeKbModel&>(model).formats();
  CoverpointSampler c;
  const KbCoverpoints kb(c, f);
  const std::size_t wraps = c.points.declare("span.x_wraps");
  const std::size_t every = c.points.declare("span.events_every_channel");
  c.sample = [channels = std::array<KbCoverpoints, 3>{kb, kb, kb}, wraps, every](
                 PipelineModel& model, std::span<const std::int64_t> in, Coverpoints& cp) mutable {
    auto& m = dynamic_cast<ShadeKbModel&>(model);
    const ShadeKbModel::Route r = m.route();
    if (r.header) {
      if (in[M::kX] + in[M::kN] >= kScreen) cp.hit(wraps);
      if (in[M::kCount] != 0 && in[M::kCount + 1] != 0 && in[M::kCount + 2] != 0) cp.hit(every);
    }
    std::array<std::vector<std::int64_t>, 3> acc;
    for (int ch = 0; ch < 3; ++ch) {
      if ((r.targets >> ch & 1U) == 0) continue;
      const auto word = M::channel_word(in, ch);
      channels[static_cast<std::size_t>(ch)].word(word, cp);
      m.engine(ch).trace_accumulator(&acc[static_cast<std::size_t>(ch)]);
    }
    std::vector<std::int64_t> out;
    (void)m.eval(in, out);
    for (int ch = 0; ch < 3; ++ch) {
      if ((r.targets >> ch & 1U) == 0) continue;
      m.engine(ch).trace_accumulator(nullptr);
      channels[static_cast<std::size_t>(ch)].pixels(acc[static_cast<std::size_t>(ch)], cp);
    }
  };
  return c;
}

// A random colour span: one length (log-uniform in 1..4096, or `length`), each channel a random
// angular span of it (kb_random_span under the configuration's setup) and its program; false
// when a program would need more events than the header counts.
bool random_colour_span(Rng& rng, const KbFormats& f, const KbSetupOptions& setup, int length,
                        std::array<KbSpan, 3>& spans, std::array<Program, 3>& programs) {
  if (length == 0) {
    length = static_cast<int>(
        std::max(1.0, std::min(4096.0, std::floor(std::exp(rng.uniform() * std::log(4097.0))))));
  }
  bool fits = true;
  for (std::size_t c = 0; c < 3; ++c) {
    spans[c] = kb_random_span(rng, setup, length);
    try {
      programs[c] = kb_program(spans[c], setup.policy, f);
    } catch (const Error&) {
      fits = false;  // more events than the header counts: not a span this configuration takes
    }
  }
  return fits;
}

// Every channel of every pixel of random colour spans (at x0 = 0) against the exact spans,
// clamped to the output range, in output LSBs; with `contract`, spans with a word outside it are
// left out and counted in `left_out`.
ModelError colour_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed,
                        InputContract* contract, std::uint64_t* spans_run,
                        std::uint64_t* left_out) {
  const KbFormats f = KbFormats::from_config(cfg);
  const KbSetupOptions so = KbSetupOptions::from_config(cfg);
  ShadeKbModel model(f);
  const double top = fx::to_real(f.out.max_raw(), f.out);
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  ErrorTally tally;
  for (std::uint64_t n = 0; tally.samples() < samples && n < 100000; ++n) {
    Rng rng(seed, kStimulusStream, n);
    std::array<KbSpan, 3> spans;
    std::array<Program, 3> programs;
    if (!random_colour_span(rng, f, so, 0, spans, programs)) continue;
    const std::vector<Word> words = shade_kb_span_words(programs, 0, 0);
    if (contract != nullptr) {
      InputContract c = *contract;  // from reset: a span starts the parse
      bool in = true;
      for (const Word& w : words) in = c.check(w) == InputContract::kIn && in;
      if (!in) {
        if (left_out != nullptr) ++*left_out;
        continue;
      }
    }
    if (spans_run != nullptr) ++*spans_run;
    model.reset();
    std::vector<std::int64_t> out;
    for (const Word& w : words) (void)model.eval(w, out);
    for (std::size_t p = 0; p < out.size() / 5; ++p) {
      for (std::size_t c = 0; c < 3; ++c) {
        const double want = std::clamp(kb_exact(spans[c], static_cast<int>(p)), 0.0, top);
        tally.add(std::abs(fx::to_real(out[5 * p + 2 + c], f.out) - want), lsb);
      }
    }
  }
  return tally.result();
}

// Random colour spans of the configuration's setup through the model, against the exact spans.
ModelError float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  return colour_error(cfg, samples, seed, nullptr, nullptr, nullptr);
}

// Pixels per clock of `spans` random colour spans of `length` pixels back to back, stall-free:
// through shade_kb (its cycle model) and through one kb engine running the three channels'
// programs in turn (kb's cycle model), as the renderer's kb methods do.
std::pair<double, double> pixels_per_clock(const Config& cfg, int length, int spans,
                                           std::uint64_t seed) {
  const KbFormats f = KbFormats::from_config(cfg);
  const KbSetupOptions so = KbSetupOptions::from_config(cfg);
  std::vector<std::int64_t> shade_in, kb_in;
  std::uint64_t pixels = 0;
  for (int s = 0, n = 0; s < spans && n < 100 * spans; ++n) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(n));
    std::array<KbSpan, 3> colour;
    std::array<Program, 3> programs;
    if (!random_colour_span(rng, f, so, length, colour, programs)) continue;
    for (const Word& w : shade_kb_span_words(programs, 0, 0)) {
      shade_in.insert(shade_in.end(), w.begin(), w.end());
    }
    for (const Program& p : programs) {
      for (const Word& w : p) kb_in.insert(kb_in.end(), w.begin(), w.end());
    }
    pixels += static_cast<std::uint64_t>(length);
    ++s;
  }
  const auto run = [&cfg](const PipelineInfo& p, PipelineModel& m,
                          const std::vector<std::int64_t>& in) {
    std::vector<std::int64_t> out;
    std::vector<std::uint32_t> counts;
    (void)m.eval_batch(in, out, &counts);
    return p.cycles(cfg, in, out, counts, nullptr).cycles;
  };
  ShadeKbModel shade(f);
  KbModel kb(f);
  const double px = static_cast<double>(pixels);
  return {px / static_cast<double>(run(shade_kb_pipeline(), shade, shade_in)),
          px / static_cast<double>(run(kb_pipeline(), kb, kb_in))};
}

// configs/shade_kb/default.toml by hand: the demux (a header to the three channels and its x0, y
// to the span queue; an event word to the first channel with events still due), kb/default's
// native engine on each channel's words, and the join (a pixel when all three have one; x = x0 +
// i, wrapping at 2048; the span done at red's last pixel).
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  // Scratch kept between calls (one set per thread), as the model keeps its queues.
  thread_local std::array<std::vector<std::int64_t>, 3> words, pixels;
  thread_local std::vector<std::int64_t> spans;  // x0, y of each header
  for (std::size_t c = 0; c < 3; ++c) {
    words[c].clear();
    pixels[c].clear();
  }
  spans.clear();
  std::array<std::int64_t, 3> left{};
  for (std::size_t at = 0; at + M::kInputs <= in.size(); at += M::kInputs) {
    const std::int64_t* w = in.data() + at;
    const int target = left[0] != 0 ? 0 : left[1] != 0 ? 1 : left[2] != 0 ? 2 : -1;
    if (target < 0) {
      spans.insert(spans.end(), {w[M::kX], w[M::kY]});
      for (std::size_t c = 0; c < 3; ++c) left[c] = w[M::kCount + c];
    } else {
      --left[static_cast<std::size_t>(target)];
    }
    for (int c = 0; c < 3; ++c) {
      if (target >= 0 && c != target) continue;
      const auto word = M::channel_word(in.subspan(at, M::kInputs), c);
      auto& to = words[static_cast<std::size_t>(c)];
      to.insert(to.end(), word.begin(), word.end());
    }
  }
  for (std::size_t c = 0; c < 3; ++c) (void)kb_pipeline().native(words[c], pixels[c]);
  const std::size_t n =
      std::min({pixels[0].size(), pixels[1].size(), pixels[2].size()}) / 2;  // (value, last)
  const std::size_t base = out.size();
  out.resize(base + 5 * n);
  std::size_t span = 0;
  std::int64_t i = 0;
  for (std::size_t p = 0; p < n; ++p) {
    std::int64_t* o = out.data() + base + 5 * p;
    o[0] = (spans[2 * span] + i) & (kScreen - 1);
    o[1] = spans[2 * span + 1];
    for (std::size_t c = 0; c < 3; ++c) o[2 + c] = pixels[c][2 * p];
    if (pixels[0][2 * p + 1] != 0) {
      ++span;
      i = 0;
    } else {
      i = (i + 1) & (kScreen - 1);
    }
  }
  return n;
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  out.print(
      "Colour spans against the exact spans (kb_exact per channel, clamped to the output range), "
      "in output LSBs: {} channel values of random spans of each configuration's setup (x0 = 0), "
      "those inside the input contract (docs/shade_kb.md), seed {}\n",
      samples, seed);
  out.print("  {:<10} {:>12} {:>7} {:>10} {:>9} {:>9} {:>9}\n", "config", "policy", "spans",
            "values", "max", "mean", "left out");
  out.table("Colour spans against the exact spans inside the input contract, in output LSBs",
            {"config", "policy", "spans", "values", "max_lsb", "mean_lsb", "out_of_contract"});
  for (const Config& cfg : configs) {
    const auto model = make_model(cfg);
    InputContract c = contract(*model, cfg);
    std::uint64_t spans = 0, left_out = 0;
    const ModelError e = colour_error(cfg, samples, seed, &c, &spans, &left_out);
    const std::string policy =
        KbSetupOptions::from_config(cfg).policy == KbPolicy::d2_only ? "d2_only" : "exact_reload";
    out.print("  {:<10} {:>12} {:>7} {:>10} {:>9.4f} {:>9.4f} {:>9}\n", cfg.name(), policy, spans,
              e.samples, e.max_lsb, e.mean_lsb, left_out);
    out.row({cfg.name(), policy, static_cast<std::int64_t>(spans),
             static_cast<std::int64_t>(e.samples), e.max_lsb, e.mean_lsb,
             static_cast<std::int64_t>(left_out)});
  }
  const int spans = static_cast<int>(std::clamp<std::uint64_t>(samples / 5000, 1, 50));
  out.print(
      "\nPixels per clock, stall-free (the cycle models), {} random colour spans of each length "
      "back to back, seed {}: shade_kb (an engine per channel) against one kb engine running the "
      "three channels' programs in turn\n",
      spans, seed);
  out.print("  {:<10} {:>7} {:>10} {:>10}\n", "config", "length", "shade_kb", "one engine");
  out.table("Pixels per clock by span length: shade_kb against one engine for three channels",
            {"config", "length", "shade_kb", "one_engine"});
  for (const Config& cfg : configs) {
    for (const int length : {1, 2, 4, 16, 64, 256, 1024, 4096}) {
      const auto [shade, one] = pixels_per_clock(cfg, length, spans, seed);
      out.print("  {:<10} {:>7} {:>10.3f} {:>10.3f}\n", cfg.name(), length, shade, one);
      out.row({cfg.name(), static_cast<std::int64_t>(length), shade, one});
    }
  }
}

}  // namespace

const PipelineInfo& shade_kb_pipeline() {
  static const PipelineInfo info{
      .name = "shade_kb",
      .summary = "Kuijk-Blake spans in colour: three engines, span words in, (x, y, R, G, B) out",
      .top = "shade_kb_top",
      .rtl_files = {"rtl/common", "rtl/kb/kb_engine.sv", "rtl/shade_kb/shade_kb_fifo.sv",
                    "rtl/shade_kb/shade_kb_top.sv"},
      .ports = {{"in_n_i", true, {"n"}},
                {"in_x_i", true, {"x0"}},
                {"in_y_i", true, {"y0"}},
                {"in_count_i", true, {"count_r", "count_g", "count_b"}},
                {"in_f_i", true, {"f_r", "f_g", "f_b"}},
                {"in_d1_i", true, {"d1_r", "d1_g", "d1_b"}},
                {"in_d2_i", true, {"d2_r", "d2_g", "d2_b"}},
                {"in_reload_i", true, {"reload"}},
                {"out_x_o", false, {"x"}},
                {"out_y_o", false, {"y"}},
                {"out_rgb_o", false, {"r", "g", "b"}}},
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = false,
      // Vectors are span words, about six pixels each on average.
      .default_vectors = 100000,
      .latency = latency,
      .one_per_clock = false,
      .cycles = cycles,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract = contract,
      .float_error = float_error,
      .analyze = analyze,
      .mutants = {{"shade-kb-x", "default", "rtl/shade_kb/shade_kb_top.sv",
                   "{rgb, span_y, span_x + i_q}", "{rgb, span_y, span_x - i_q}",
                   "x counts down from x0"},
                  {"shade-kb-route", "default", "rtl/shade_kb/shade_kb_top.sv",
                   "assign target[2] = is_header | (left_q[0] == '0 && left_q[1] == '0);",
                   "assign target[2] = is_header | (left_q[1] == '0);",
                   "blue takes event words while red's are still due"},
                  {"shade-kb-valid", "narrow", "rtl/shade_kb/shade_kb_top.sv",
                   ".in_valid_i ((&pixel_valid) & span_valid),",
                   ".in_valid_i ((&pixel_valid[1:0]) & span_valid),",
                   "a pixel leaves without waiting for blue"}},
  };
  return info;
}

}  // namespace phongsim
