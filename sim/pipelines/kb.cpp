// Stimulus for the Kuijk–Blake engine. Its input is a stream of span programs (a header word
// then its event words), so random vectors come in chunks of kChunkWords words: each chunk is
// one span program followed by one-pixel filler spans, derived from (seed, chunk), so vector i
// is still a pure function of (seed, i). Half the chunks are programs the setup writes for
// random angular spans (the configuration's policy), half are random well-formed programs
// (events before the last pixel, increasing indices) with arbitrary values. Directed vectors
// cover what well-formed programs never do: late events, events at or after the last pixel,
// left-over event words, accumulator wrap-around and every clamp corner.
#include "sim/pipelines/kb.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <numeric>

#include "base/error.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "sim/pipelines/guard_tables.h"

namespace phongsim {
namespace {

using Word = std::vector<std::int64_t>;  // n, count, f, d1, d2, reload

Word header(std::int64_t last, std::int64_t count, std::int64_t f, std::int64_t d1,
            std::int64_t d2) {
  return {last, count, f, d1, d2, 0};
}
Word event(std::int64_t at, std::int64_t d1, std::int64_t d2, bool reload) {
  return {at, 0, 0, d1, d2, reload ? 1 : 0};
}

}  // namespace

std::vector<std::vector<std::int64_t>> kb_random_words(Rng& rng, const KbFormats& f,
                                                       std::uint64_t max_events, int pixels) {
  const auto length = pixels > 0
                          ? std::int64_t{pixels}
                          : static_cast<std::int64_t>(std::min(
                                4096.0, std::floor(std::exp(rng.uniform() * std::log(4097.0)))));
  const std::int64_t last = std::max<std::int64_t>(length, 1) - 1;
  const auto q = [&f](double x) {
    return fx::quantize(x, f.acc, fx::Round::half_even, fx::Overflow::saturate);
  };
  const auto bits = [&f, &rng]() {
    return f.acc.min_raw() +
           static_cast<std::int64_t>(
               rng.below(static_cast<std::uint64_t>(f.acc.max_raw() - f.acc.min_raw()) + 1));
  };
  const double scale = 1.0 / static_cast<double>(last + 1);
  const auto value = [&](double magnitude) {
    return rng.below(4) == 0 ? bits() : q((2 * rng.uniform() - 1) * magnitude);
  };
  const std::uint64_t events =
      rng.below(std::min<std::uint64_t>(static_cast<std::uint64_t>(last), max_events) + 1);
  // Distinct indices in [0, last - 1], increasing.
  std::vector<std::int64_t> at;
  while (at.size() < events) {
    const auto i = static_cast<std::int64_t>(rng.below(static_cast<std::uint64_t>(last)));
    if (std::find(at.begin(), at.end(), i) == at.end()) at.push_back(i);
  }
  std::sort(at.begin(), at.end());
  std::vector<Word> words{header(last, static_cast<std::int64_t>(events),
                                 rng.below(4) == 0 ? bits() : q(1.4 * rng.uniform() - 0.2),
                                 value(scale), value(scale * scale))};
  for (const std::int64_t i : at) {
    words.push_back(event(i, value(scale), value(scale * scale), rng.below(2) == 0));
  }
  return words;
}

KbSpan kb_random_span(Rng& rng, const KbSetupOptions& setup, int length) {
  KbSpan span;
  span.length =
      static_cast<int>(std::min(4096.0, std::floor(std::exp(rng.uniform() * std::log(4097.0)))));
  span.length = length > 0 ? length : std::max(span.length, 1);
  const auto terms = static_cast<int>(rng.below(static_cast<std::uint64_t>(setup.max_terms))) + 1;
  double budget = 1.0;
  for (int t = 0; t < terms; ++t) {
    KbTerm term;
    term.ab = kb_params(static_cast<double>(rng.below(125) + 1), setup.ab);
    const double start = (3 * rng.uniform() - 1.5) * term.ab.b;
    const double end = (3 * rng.uniform() - 1.5) * term.ab.b;
    term.theta0 = start;
    term.dtheta = (end - start) / span.length;
    term.scale = budget * (t + 1 == terms ? 1.0 : rng.uniform());
    budget -= term.scale;
    span.terms.push_back(term);
  }
  return span;
}

std::vector<std::vector<std::int64_t>> kb_fitting_program(KbSpan& span, const KbFormats& formats,
                                                          const KbSetupOptions& setup) {
  while (true) {
    try {
      return kb_program(span, setup.policy, formats);
    } catch (const Error&) {
      // Too many events for the header: fewer terms first, then a narrower sweep (fewer
      // crossings; a sweep that stays in one section needs none).
      if (span.terms.size() > 1) {
        span.terms.resize(1);
        span.terms[0].scale = 1;
      } else {
        span.terms[0].dtheta /= 2;
      }
    }
  }
}

std::vector<std::vector<std::int64_t>> kb_random_program(Rng& rng, const KbFormats& formats,
                                                         const KbSetupOptions& setup) {
  KbSpan span = kb_random_span(rng, setup);
  return kb_fitting_program(span, formats, setup);
}

std::vector<std::vector<std::int64_t>> kb_directed_words(const KbFormats& f) {
  const std::uint64_t max_events = (std::uint64_t{1} << f.event_bits) - 1;
  const std::int64_t one = std::int64_t{1} << f.acc.frac_bits;
  const std::int64_t lsb = 1;

  // Directed: clamp corners and wrap-around (one-pixel spans), then malformed programs.
  std::vector<Word> d;
  for (const std::int64_t v : {std::int64_t{0}, one, one - lsb, one + lsb, -lsb, f.acc.min_raw(),
                               f.acc.max_raw(), one / 2, one / 2 + lsb}) {
    d.push_back(header(0, 0, v, 0, 0));
  }
  d.push_back(header(3, 0, f.acc.max_raw(), f.acc.max_raw(), f.acc.max_raw()));  // wraps
  d.push_back(header(4095, 0, 0, 1, 0));                                         // 4096 pixels
  d.push_back(header(4095, 0, one, -(one >> 11), 0));
  // Events at the first pixels, consecutive indices, with and without reload.
  d.push_back(header(9, 3, one / 4, one / 16, 0));
  d.push_back(event(0, one / 32, -(one >> 8), true));
  d.push_back(event(1, 0, one >> 7, false));
  d.push_back(event(2, -(one / 64), 0, true));
  // A late event (index below the current pixel) is applied at once.
  d.push_back(header(7, 2, one / 2, 0, 0));
  d.push_back(event(5, one / 8, 0, true));
  d.push_back(event(3, -(one / 8), 0, true));
  // Events at and after the last pixel: the later ones are dropped after the span.
  d.push_back(header(2, 3, one / 2, one / 16, 0));
  d.push_back(event(2, one, one, true));
  d.push_back(event(3, one, one, true));
  d.push_back(event(4095, one, one, true));
  // An event word past the span's last pixel while the span runs: the span ends without it and
  // the word is dropped.
  d.push_back(header(2, 1, one / 2, one / 16, 0));
  d.push_back(event(5, one, one, true));
  // The span's last event on its last pixel: the next header is read a cycle later.
  d.push_back(header(3, 1, one / 4, one / 32, 0));
  d.push_back(event(3, -(one / 8), 0, true));
  // A one-pixel span with more event words than pixels, then back-to-back one-pixel spans.
  d.push_back(header(0, 2, one, 0, 0));
  d.push_back(event(0, 0, 0, false));
  d.push_back(event(0, 0, 0, false));
  for (int k = 0; k < 5; ++k) d.push_back(header(0, 0, k * one / 5, 0, 0));
  // The largest event count the header can hold.
  d.push_back(header(static_cast<std::int64_t>(max_events) + 3,
                     static_cast<std::int64_t>(max_events), one / 2, 0, 0));
  for (std::uint64_t e = 0; e < max_events; ++e) {
    d.push_back(event(static_cast<std::int64_t>(e), one >> 6, -(one >> 10), e % 2 == 0));
  }
  return d;
}

Stimulus make_kb_stimulus(const PipelineModel& model, const KbSetupOptions& setup) {
  const KbFormats& f = dynamic_cast<const KbModel&>(model).formats();
  const std::uint64_t max_events = (std::uint64_t{1} << f.event_bits) - 1;
  std::vector<Word> d = kb_directed_words(f);

  // One program (at most 1 + max_events words) and at least one filler word per chunk.
  return span_stimulus(
      model, std::move(d), max_events + 2,
      [f, setup, max_events](Rng& rng) {
        return rng.below(2) == 0 ? kb_random_words(rng, f, max_events)
                                 : kb_random_program(rng, f, setup);
      },
      header(0, 0, 0, 0, 0));  // filler: one-pixel spans
}

Stimulus span_stimulus(const PipelineModel& model, std::vector<std::vector<std::int64_t>> directed,
                       std::uint64_t chunk_words,
                       std::function<std::vector<std::vector<std::int64_t>>(Rng&)> chunk,
                       std::vector<std::int64_t> filler) {
  // Random: chunk c of chunk_words words, cached (consecutive indices share a chunk). The cache
  // is part of the function object: a copy of the stimulus (one per co-simulation worker) has its
  // own.
  struct Cache {
    std::uint64_t seed = 0;
    std::uint64_t chunk = UINT64_MAX;
    std::vector<Word> words;
  };
  const std::uint64_t first = directed.size();
  auto random = [first, cache = Cache{}, chunk_words, chunk = std::move(chunk),
                 filler = std::move(filler)](std::uint64_t seed, std::uint64_t index,
                                             std::span<std::int64_t> in) mutable {
    const std::uint64_t r = index - first;
    const std::uint64_t c = r / chunk_words;
    if (cache.chunk != c || cache.seed != seed) {
      Rng rng(seed, kStimulusStream, c);
      cache.words = chunk(rng);
      cache.chunk = c;
      cache.seed = seed;
    }
    // The padding is served from `filler`, not copied into the chunk: most of a chunk is
    // padding, and a copy per word was an allocation per word.
    const std::uint64_t k = r % chunk_words;
    const Word& w = k < cache.words.size() ? cache.words[k] : filler;
    std::copy(w.begin(), w.end(), in.begin());
  };
  Stimulus stimulus(model, std::move(directed), random);
  // Programs start at vector 0, after the directed ones, and at every chunk: each chunk ends in
  // filler (one-pixel spans), so the pipeline is idle there. (Directed programs may include
  // malformed ones with left-over event words: they are one group.)
  stimulus.set_groups([first, chunk_words](std::uint64_t index) -> std::uint64_t {
    if (index == 0) return 0;
    if (index <= first) return first;
    return first + (index - first + chunk_words - 1) / chunk_words * chunk_words;
  });
  return stimulus;
}

// ---- analysis ----

std::vector<KbFitRow> kb_fit_table() {
  std::vector<KbFitRow> rows;
  // The paper's range 1..125, then the renderer's halfway exponents 4n for shininess 32..1024.
  std::vector<int> ns(125);
  std::iota(ns.begin(), ns.end(), 1);
  ns.insert(ns.end(), {128, 256, 512, 1024, 4096});
  for (const int n : ns) {
    KbFitRow r;
    r.n = n;
    r.closed = kb::closed_form(n);
    r.lsq = kb::least_squares(n);
    r.closed_max = kb::max_error(r.closed, n);
    r.closed_rms = kb::rms_error(r.closed, n);
    r.lsq_max = kb::max_error(r.lsq, n);
    r.lsq_rms = kb::rms_error(r.lsq, n);
    rows.push_back(r);
  }
  return rows;
}

double kb_drift(int length, int guard_bits, KbPolicy policy, fx::Format out, int spans,
                std::uint64_t seed) {
  KbFormats f;
  f.acc = fx::Format{true, 2, out.frac_bits + guard_bits};
  f.out = out;
  f.event_bits = 6;
  KbModel engine(f);
  std::vector<std::int64_t> trace;
  std::vector<std::int64_t> outputs;
  engine.trace_accumulator(&trace);
  const KbSetupOptions options{policy, KbAbSource::least_squares, 2};
  const double out_lsb = std::ldexp(1.0, -out.frac_bits);
  double worst = 0;
  for (int s = 0; s < spans; ++s) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(s));
    const KbSpan span = kb_random_span(rng, options, length);
    trace.clear();
    engine.reset();
    for (const auto& word : kb_program(span, policy, f)) engine.eval(word, outputs);
    // What reaches the output: both sides clamped to [0, 1] (before the output rounding).
    const auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
    for (int i = 0; i < length; ++i) {
      const double drift =
          std::abs(clamp01(fx::to_real(trace[i], f.acc)) - clamp01(kb_exact(span, i))) / out_lsb;
      worst = std::max(worst, drift);
    }
  }
  return worst;
}

int kb_guard_bits_needed(int length) {
  const double l = length;
  return static_cast<int>(std::ceil(std::log2((l * l - l + 2) / 2)));
}

namespace {

// The longest span whose accumulated rounding stays within half an output LSB with the
// configuration's guard bits (the contract's length clause), at most 4096.
std::int64_t longest_span(const KbFormats& f) {
  const int guard = f.acc.frac_bits - f.out.frac_bits;
  std::int64_t longest = 0;
  while (longest < 4096 && guard >= 0 &&
         kb_guard_bits_needed(static_cast<int>(longest + 1)) <= guard) {
    ++longest;
  }
  return longest;
}

// The first clause a program breaks, checked from reset, or InputContract::kIn.
int broken_clause(const InputContract& contract, const std::vector<Word>& program) {
  InputContract c = contract;
  for (const Word& w : program) {
    const int b = c.check(w);
    if (b != InputContract::kIn) return b;
  }
  return InputContract::kIn;
}

// Every pixel value the engine outputs for `program` (run from reset).
std::vector<double> run_engine(const KbFormats& f, const std::vector<Word>& program) {
  KbModel m(f);
  std::vector<std::int64_t> out;
  for (const Word& w : program) (void)m.eval(w, out);
  std::vector<double> values;
  for (std::size_t i = 0; i < out.size() / 2; ++i) values.push_back(fx::to_real(out[2 * i], f.out));
  return values;
}

// The program's own values accumulated without wrapping: the engine with an accumulator of 20
// integer bits (the same fraction bits, so the same raw words), before clamping.
std::vector<double> unwrapped(const KbFormats& f, const std::vector<Word>& program) {
  KbFormats wide = f;
  wide.acc = fx::Format{true, 20, f.acc.frac_bits};
  KbModel m(wide);
  std::vector<std::int64_t> trace, out;
  m.trace_accumulator(&trace);
  for (const Word& w : program) (void)m.eval(w, out);
  std::vector<double> values;
  for (const std::int64_t v : trace) values.push_back(fx::to_real(v, wide.acc));
  return values;
}

}  // namespace

KbOutputError kb_output_error(const KbFormats& f, const KbSetupOptions& setup,
                              const InputContract& contract, int programs, std::uint64_t seed) {
  const double top = fx::to_real(f.out.max_raw(), f.out);
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  KbOutputError e;
  double sum = 0;
  for (int n = 0; n < programs; ++n) {
    Rng rng(seed, kStimulusStream, static_cast<std::uint64_t>(n));
    KbSpan span = kb_random_span(rng, setup);
    const std::vector<Word> program = kb_fitting_program(span, f, setup);
    if (broken_clause(contract, program) != InputContract::kIn) {
      ++e.out_of_contract;
      continue;
    }
    ++e.programs;
    const std::vector<double> got = run_engine(f, program);
    for (std::size_t i = 0; i < got.size(); ++i) {
      const double d =
          std::abs(got[i] - std::clamp(kb_exact(span, static_cast<int>(i)), 0.0, top)) / lsb;
      e.max = std::max(e.max, d);
      sum += d;
      ++e.pixels;
    }
  }
  e.mean = e.pixels == 0 ? 0 : sum / static_cast<double>(e.pixels);
  return e;
}

std::vector<KbContractRow> kb_out_of_contract(const KbFormats& f, const KbSetupOptions& setup,
                                              const InputContract& contract, std::uint64_t samples,
                                              std::uint64_t seed) {
  const std::size_t clauses = contract.clauses().size();
  std::vector<KbContractRow> rows(clauses + 1);
  for (std::size_t c = 0; c < clauses; ++c) rows[c].clause = contract.clauses()[c];
  rows[clauses].clause = "any (arbitrary values)";
  const double top = fx::to_real(f.out.max_raw(), f.out);
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  const double acc_max = fx::to_real(f.acc.max_raw(), f.acc);
  const std::int64_t longest = longest_span(f);
  const std::uint64_t max_events = (std::uint64_t{1} << f.event_bits) - 1;
  const auto q = [&f](double x) {
    return fx::quantize(x, f.acc, fx::Round::half_even, fx::Overflow::saturate);
  };
  const auto record = [&](KbContractRow& r, const std::vector<double>& got,
                          const std::vector<double>& want) {
    ++r.programs;
    for (std::size_t i = 0; i < got.size() && i < want.size(); ++i) {
      const double w = std::clamp(want[i], 0.0, top);
      const double d = std::abs(got[i] - w);
      if (d > r.max_error || r.pixels == 0) {
        r.max_error = d;
        r.worst = got[i];
        r.worst_want = w;
      }
      if (d > lsb) ++r.off;
      ++r.pixels;
    }
  };
  const std::uint64_t per_clause = std::max<std::uint64_t>(samples / (clauses + 1), 1);
  for (std::size_t c = 0; c <= clauses; ++c) {
    if (c == 2 && longest >= 4096) {
      rows[c].note = "cannot be broken: the header's n holds at most 4096 pixels";
      continue;
    }
    for (std::uint64_t tries = 0; rows[c].programs < per_clause && tries < 20 * per_clause;
         ++tries) {
      Rng rng(seed, kStimulusStream, (std::uint64_t{c} << 40) + tries);
      KbSpan span;
      std::vector<Word> program;
      bool against_span = c == 2 || c == 3;  // else: the program's own values, unwrapped
      if (c == clauses) {
        program = kb_random_words(rng, f, max_events);
      } else if (c == 2) {  // a span longer than the guard bits cover
        span = kb_random_span(rng, setup,
                              static_cast<int>(longest + 1 +
                                               static_cast<std::int64_t>(rng.below(
                                                   static_cast<std::uint64_t>(4096 - longest)))));
        program = kb_fitting_program(span, f, setup);
      } else {
        span = kb_random_span(rng, setup);
        program = kb_fitting_program(span, f, setup);
        if (broken_clause(contract, program) != InputContract::kIn) continue;
        const double u = rng.uniform();
        const bool low = rng.below(2) == 0;
        switch (c) {
          case 0:  // f below 0 or above 1
            program[0][2] = q(low ? -u * acc_max : 1 + lsb + u * (acc_max - 1));
            break;
          case 1: {  // Δf beyond 1 or Δ²f beyond 2, in the header or a reloading event
            std::vector<std::size_t> reloads{0};
            for (std::size_t k = 1; k < program.size(); ++k) {
              if (program[k][5] != 0) reloads.push_back(k);
            }
            Word& w = program[reloads[rng.below(reloads.size())]];
            const double sign = rng.below(2) == 0 ? -1 : 1;
            if (low) {
              w[3] = q(sign * (1 + lsb + u * (acc_max - 1)));
            } else {
              w[4] = q(sign * (2 + lsb + u * (acc_max - 2)));
            }
            break;
          }
          default: {  // an event after the last pixel, or before the one before it
            if (program.size() < 2) continue;
            const std::size_t k = 1 + rng.below(program.size() - 1);
            const std::int64_t last = program[0][0];
            if (low || k == 1) {
              program[k][0] = last + static_cast<std::int64_t>(
                                         rng.below(static_cast<std::uint64_t>(4096 - last)));
            } else {
              program[k][0] = static_cast<std::int64_t>(
                  rng.below(static_cast<std::uint64_t>(program[k - 1][0] + 1)));
            }
            break;
          }
        }
      }
      const int broken = broken_clause(contract, program);
      if (broken == InputContract::kIn) continue;
      if (c < clauses && static_cast<std::size_t>(broken) != c) continue;
      std::vector<double> want;
      if (against_span) {
        for (int i = 0; i < span.length; ++i) want.push_back(kb_exact(span, i));
      } else {
        want = unwrapped(f, program);
      }
      record(rows[c], run_engine(f, program), want);
    }
  }
  return rows;
}

KbCoverpoints::KbCoverpoints(CoverpointSampler& sampler, const KbFormats& f)
    : output_(sampler, f.acc, f.out, f.out_round),
      max_events_((std::int64_t{1} << f.event_bits) - 1),
      max_last_((std::int64_t{1} << KbFormats::kIndexBits) - 1) {
  Coverpoints& p = sampler.points;
  events_ = p.declare("program.no_events");
  p.declare("program.max_events");
  span_ = p.declare("span.length_1");
  p.declare("span.length_max");
  ev_ = p.declare("event.section");
  for (const char* e :
       {"event.reload", "event.late", "event.last_pixel", "event.beyond_span", "event.dropped"}) {
    p.declare(e);
  }
}

void KbCoverpoints::word(std::span<const std::int64_t> in, Coverpoints& cp) {
  if (!st_.running && st_.remaining == 0) {  // a header
    st_ = {true, in[1], 0, in[0]};
    if (in[1] == 0) cp.hit(events_);
    if (in[1] == max_events_) cp.hit(events_ + 1);
    if (in[0] == 0) cp.hit(span_);
    if (in[0] == max_last_) cp.hit(span_ + 1);
  } else if (!st_.running) {
    cp.hit(ev_ + 5);  // dropped after its span
    --st_.remaining;
  } else {
    if (in[0] > st_.last) {
      cp.hit(ev_ + 4);
    } else {
      cp.hit(ev_ + (in[5] != 0 ? 1 : 0));
      if (in[0] < st_.i) cp.hit(ev_ + 2);
      if (in[0] == st_.last) cp.hit(ev_ + 3);
    }
    --st_.remaining;
  }
}

void KbCoverpoints::pixels(std::span<const std::int64_t> acc, Coverpoints& cp) {
  for (const std::int64_t f : acc) {
    output_.hit(cp, f);
    if (st_.i == st_.last) st_.running = false;
    ++st_.i;
  }
}

// ---- registry entry ----
namespace {

std::unique_ptr<PipelineModel> make_model(const Config& cfg) {
  const KbFormats formats = KbFormats::from_config(cfg);
  (void)KbSetupOptions::from_config(cfg);  // the stimulus reads it; check it here
  cfg.check_all_used();
  try {
    return std::make_unique<KbModel>(formats);
  } catch (const Error& e) {
    cfg.fail(e.what());
  }
}

Stimulus make_stimulus(const PipelineModel& model, const Config& cfg) {
  return make_kb_stimulus(model, KbSetupOptions::from_config(cfg));
}

}  // namespace

// The domain of the accuracy claims (docs/kb.md, "Input contract"), word by word: the checker
// follows the engine's parse (a header, then `count` event words) from reset.
InputContract kb_input_contract(const KbFormats& f) {
  const std::int64_t one = std::int64_t{1} << f.acc.frac_bits;
  const std::int64_t longest = longest_span(f);
  struct Parse {
    std::int64_t remaining = 0;  // event words still due for the current span
    std::int64_t last = 0;       // its last pixel
    std::int64_t previous = -1;  // its previous event's pixel
  };
  return InputContract(
      {"f in [0, 1]", "|d1| <= 1, |d2| <= 2", fmt::format("length <= {}", longest),
       "events ordered, before the last pixel"},
      [one, longest, s = Parse{}](std::span<const std::int64_t> in) mutable {
        // Fields: n, count, f, d1, d2, reload.
        const bool header = s.remaining == 0;
        if (header) {
          s = Parse{in[1], in[0], -1};
        } else {
          --s.remaining;
        }
        const bool uses_d1 = header || in[5] != 0;
        if (header && (in[2] < 0 || in[2] > one)) return 0;
        if ((uses_d1 && (in[3] < -one || in[3] > one)) || in[4] < -2 * one || in[4] > 2 * one) {
          return 1;
        }
        if (header) return in[0] + 1 <= longest ? InputContract::kIn : 2;
        const bool ordered = in[0] > s.previous && in[0] < s.last;
        s.previous = in[0];
        return ordered ? InputContract::kIn : 3;
      });
}

namespace {

InputContract contract(const PipelineModel& model, const Config&) {
  return kb_input_contract(dynamic_cast<const KbModel&>(model).formats());
}

int latency(const Config&) { return 2; }  // header word to its first pixel (docs/kb.md)

// kb_engine's control, cycle by cycle (its signal names), with the source offering a word every
// cycle and the sink always ready: the word accepted in cycle 0 is the head from cycle 1; a pixel
// leaves through the output register the cycle after it fires.
FrameCycles cycles(const Config&, std::span<const std::int64_t> in, std::span<const std::int64_t>,
                   std::span<const std::uint32_t> counts, std::vector<FrameCycles>* per_vector) {
  const std::size_t words = counts.size(), fields = words == 0 ? 0 : in.size() / words;
  if (per_vector != nullptr) per_vector->assign(words, {});
  std::size_t span = 0;  // the header word of the span the cycle belongs to
  const auto field = [&](std::size_t w, std::size_t k) { return in[w * fields + k]; };
  FrameCycles now, at_last;  // at_last: as of the last pixel so far
  std::uint64_t last_fire = 0;
  bool running = false;
  std::int64_t remaining = 0, i = 0, last = 0;
  std::size_t head = 0;
  for (std::uint64_t t = 1;; ++t) {
    const bool head_valid = head < words;
    if (!head_valid && (!running || remaining != 0)) break;  // nothing left to do
    const bool fire = running && (remaining == 0 || head_valid);
    const bool apply = fire && remaining != 0 && field(head, 0) <= i;
    const bool is_last = i == last;
    const std::int64_t remaining_after = remaining - (apply ? 1 : 0);
    const bool take =
        head_valid && !apply && remaining_after == 0 && (!running || (fire && is_last));
    const bool drain = head_valid && !running && remaining != 0;
    if (fire) {
      ++now.outputs;
      last_fire = t;
      at_last = now;
    } else {
      ++now.setup_cycles;  // a header read or a left-over event word dropped
    }
    if (per_vector != nullptr) {  // a dropped word's cycle is its own; the rest its span's
      FrameCycles& own = (*per_vector)[fire ? span : head];
      ++own.cycles;
      ++(fire ? own.outputs : own.setup_cycles);
    }
    if (take) span = head;
    if (take) {
      running = true;
      remaining = field(head, 1);
      i = 0;
      last = field(head, 0);
    } else if (fire) {
      running = !is_last;
      remaining = remaining_after;
      ++i;
    } else if (drain) {
      --remaining;
    }
    if (apply || take || drain) ++head;
  }
  if (at_last.outputs == 0) return {};
  at_last.fill_cycles = 2;  // the input and output registers
  at_last.cycles = last_fire + 2;
  return at_last;
}

// configs/kb/default.toml's engine by hand: acc S2.32 (35-bit adders, wrapping), out 0.8 rounded
// half_even from the accumulator clamped to [0, 1]. The control is KbModel's; runs of 16 pixels
// or more without an event in closed form on the kernel instruction set, as the model's plan
// does them (KbPlan::run), so the two are compared on equal terms.
std::size_t native(std::span<const std::int64_t> in, std::vector<std::int64_t>& out) {
  const auto wrap = [](std::uint64_t v) { return static_cast<std::int64_t>(v << 29) >> 29; };
  const auto value = [](std::int64_t f) {
    f = std::clamp<std::int64_t>(f, 0, std::int64_t{1} << 32);
    return std::min<std::int64_t>((f + (1 << 23) - 1 + ((f >> 24) & 1)) >> 24, 255);
  };
  const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
  bool running = false;
  std::int64_t remaining = 0, i = 0, last = 0, f = 0, d1 = 0, d2 = 0;
  const auto pixel = [&](std::int64_t d1_step, std::int64_t d2_step) {
    out.push_back(value(f));
    out.push_back(i == last ? 1 : 0);
    f = wrap(u(f) + u(d1_step));
    d1 = wrap(u(d1_step) + u(d2_step));
    d2 = d2_step;
    if (i == last) {
      running = false;
    } else {
      ++i;
    }
  };
  // Pixels i .. stop - 1 (at most to the span's end) with the span's own steps.
  const auto steady = [&](std::int64_t stop) {
    const std::int64_t end = std::min(stop, last + 1);
    if (!running || i >= end) return;
    const auto count = static_cast<std::size_t>(end - i);
    if (count < 16) {
      while (running && i < end) pixel(d1, d2);
      return;
    }
    const std::size_t base = out.size();
    out.resize(base + 2 * count);
    std::int64_t* const o = out.data() + base;
    const std::uint64_t f0 = u(f), g = u(d1), a = u(d2);
    for (std::size_t k = 0; k < count; ++k) {  // f + k·d1 + d2·k(k - 1)/2
      o[2 * k] = value(wrap(f0 + k * g + a * (k * (k - 1) / 2)));
      o[2 * k + 1] = 0;
    }
    f = wrap(f0 + count * g + a * (count * (count - 1) / 2));
    d1 = wrap(g + count * a);
    if (end == last + 1) {
      o[2 * count - 1] = 1;
      i = last;
      running = false;
    } else {
      i = end;
    }
  };
  const std::size_t before = out.size();
  fx::on_kernel_isa([&] {
    for (std::size_t at = 0; at + 6 <= in.size(); at += 6) {
      const std::int64_t* w = in.data() + at;
      if (!running && remaining == 0) {
        running = true;
        remaining = w[1];
        i = 0;
        last = w[0];
        f = w[2];
        d1 = w[3];
        d2 = w[4];
      } else if (!running) {
        --remaining;
      } else {
        steady(w[0]);
        if (running) pixel(w[5] != 0 ? w[3] : d1, w[4]);
        --remaining;
      }
      if (running && remaining == 0) steady(last + 1);  // the rest of the span
    }
  });
  return (out.size() - before) / 2;
}

// A word's stages: the accumulator f of every pixel it emits (before clamping and rounding),
// then that pixel's output value.
std::vector<StageValue> stages(PipelineModel& model, std::span<const std::int64_t> in) {
  auto& m = dynamic_cast<KbModel&>(model);
  std::vector<std::int64_t> acc, out;
  m.trace_accumulator(&acc);
  (void)m.eval(in, out);
  m.trace_accumulator(nullptr);
  std::vector<StageValue> s;
  for (std::size_t i = 0; i < acc.size(); ++i) {
    s.push_back({fmt::format("pixel{}.f", i), fx::Fixed{acc[i], m.formats().acc}});
    s.push_back({fmt::format("pixel{}.value", i), fx::Fixed{out[2 * i], m.formats().out}});
  }
  return s;
}

CoverpointSampler coverpoints(const PipelineModel& model, const Config&) {
  const KbFormats f = dynamic_cast<const KbModel&>(model).formats();
  CoverpointSampler c;
  KbCoverpoints points(c, f);
  c.sample = [points](PipelineModel& model, std::span<const std::int64_t> in,
                      Coverpoints& cp) mutable {
    auto& m = dynamic_cast<KbModel&>(model);
    points.word(in, cp);
    std::vector<std::int64_t> acc, out;
    m.trace_accumulator(&acc);
    (void)m.eval(in, out);
    m.trace_accumulator(nullptr);
    points.pixels(acc, cp);
  };
  return c;
}

// Random spans of the configuration's setup through the model, against the exact span.
ModelError float_error(const Config& cfg, std::uint64_t samples, std::uint64_t seed) {
  const KbFormats f = KbFormats::from_config(cfg);
  const KbSetupOptions so = KbSetupOptions::from_config(cfg);
  KbModel model(f);
  const double top = fx::to_real(f.out.max_raw(), f.out);
  const double lsb = std::ldexp(1.0, -f.out.frac_bits);
  ErrorTally tally;
  for (std::uint64_t n = 0; tally.samples() < samples && n < 100000; ++n) {
    Rng rng(seed, kStimulusStream, n);
    const KbSpan span = kb_random_span(rng, so, 0);
    std::vector<std::vector<std::int64_t>> program;
    try {
      program = kb_program(span, so.policy, f);
    } catch (const Error&) {
      continue;  // more events than the header counts: not a span this configuration takes
    }
    model.reset();
    std::vector<std::int64_t> out;
    for (const auto& w : program) (void)model.eval(w, out);
    for (std::size_t i = 0; i < out.size() / 2; ++i) {
      const double d = std::abs(fx::to_real(out[2 * i], f.out) -
                                std::clamp(kb_exact(span, static_cast<int>(i)), 0.0, top));
      tally.add(d, lsb);
    }
  }
  return tally.result();
}

void analyze(std::span<const Config> configs, std::uint64_t samples, std::uint64_t seed,
             AnalysisReport& out) {
  out.print(
      "Three-piece quadratic against cos^n theta (0 beyond pi/2): max and rms over theta in "
      "[0, pi] (kb::max_error, rms_error)\n");
  out.print("  {:>4}  {:>8} {:>8} {:>9} {:>9}   {:>8} {:>8} {:>9} {:>9}\n", "n", "a closed",
            "b closed", "max", "rms", "a lsq", "b lsq", "max", "rms");
  out.table("Three-piece quadratic against cos^n theta over [0, pi]",
            {"n", "a_closed", "b_closed", "max_closed", "rms_closed", "a_lsq", "b_lsq", "max_lsq",
             "rms_lsq"});
  for (const KbFitRow& r : kb_fit_table()) {
    out.print(
        "  {:>4}  {:>8.5f} {:>8.5f} {:>9.6f} {:>9.6f}   {:>8.5f} {:>8.5f} {:>9.6f} "
        "{:>9.6f}\n",
        r.n, r.closed.a, r.closed.b, r.closed_max, r.closed_rms, r.lsq.a, r.lsq.b, r.lsq_max,
        r.lsq_rms);
    out.row({static_cast<std::int64_t>(r.n), r.closed.a, r.closed.b, r.closed_max, r.closed_rms,
             r.lsq.a, r.lsq.b, r.lsq_max, r.lsq_rms});
  }
  const int spans = static_cast<int>(std::max<std::uint64_t>(1, samples / 2000));
  const fx::Format out_fmt{false, 0, 8};
  const int lengths[] = {16, 64, 256, 1024, 4096};
  const int guards[] = {0, 4, 8, 12, 16, 20, 24, 40};
  for (const KbPolicy policy : {KbPolicy::exact_reload, KbPolicy::d2_only}) {
    out.print(
        "\nDrift: max |accumulator - exact span|, both clamped to [0, 1], in LSBs of an "
        "8-bit output; {} random spans per cell (1-2 terms, n 1..125), seed {}, policy {}\n",
        spans, seed, policy == KbPolicy::d2_only ? "d2_only" : "exact_reload");
    drift_table(out,
                fmt::format("Drift in LSBs of an 8-bit output, policy {}, by span length and "
                            "guard bits",
                            policy == KbPolicy::d2_only ? "d2_only" : "exact_reload"),
                "length", 6, lengths, guards, [&](int length, int g) {
                  return kb_drift(length, g, policy, out_fmt, spans, seed);
                });
  }
  out.print(
      "\nGuard bits for a drift of at most 1/2 output LSB (exact_reload): analytic bound "
      "G >= log2((L^2 - L + 2)/2), and the smallest G that met it on the spans above\n");
  guard_bits_table(
      out, "Guard bits for a drift of at most 1/2 output LSB (exact_reload)", "length", 6, lengths,
      [](int length) { return kb_guard_bits_needed(length); },
      [&](int length, int g) {
        return kb_drift(length, g, KbPolicy::exact_reload, out_fmt, spans, seed);
      });

  // Per configuration: inside the input contract, then each clause broken alone.
  const int programs = static_cast<int>(std::max<std::uint64_t>(1, samples / 50));
  out.print(
      "\nOutput against the exact span (kb_exact clamped to the output range), per "
      "configuration, in output LSBs: the programs of {} random spans of the configuration's "
      "setup, those inside the input contract (docs/kb.md), seed {}\n",
      programs, seed);
  out.print("  {:<14} {:>12} {:>9} {:>10} {:>9} {:>9} {:>9}\n", "config", "policy", "programs",
            "pixels", "max", "mean", "left out");
  out.table("Output against the exact span inside the input contract, in output LSBs",
            {"config", "policy", "programs", "pixels", "max_lsb", "mean_lsb", "out_of_contract"});
  std::vector<KbModel> models;
  for (const Config& cfg : configs) {
    const KbFormats f = KbFormats::from_config(cfg);
    const KbSetupOptions so = KbSetupOptions::from_config(cfg);
    models.emplace_back(f);
    const KbOutputError e = kb_output_error(f, so, contract(models.back(), cfg), programs, seed);
    const std::string policy = so.policy == KbPolicy::d2_only ? "d2_only" : "exact_reload";
    out.print("  {:<14} {:>12} {:>9} {:>10} {:>9.4f} {:>9.4f} {:>9}\n", cfg.name(), policy,
              e.programs, e.pixels, e.max, e.mean, e.out_of_contract);
    out.row({cfg.name(), policy, static_cast<std::int64_t>(e.programs),
             static_cast<std::int64_t>(e.pixels), e.max, e.mean,
             static_cast<std::int64_t>(e.out_of_contract)});
  }
  out.print(
      "\nOutside the input contract: every pixel against what the program was written for "
      "(the exact span for the length and event clauses, the program's values accumulated "
      "without wrapping for the others), both clamped to the output range, absolute; each "
      "clause broken alone in setup programs, then random programs with arbitrary values; {} "
      "programs per row, seed {}\n",
      std::max<std::uint64_t>(programs / 5, 1), seed);
  out.table("Outside the input contract: output against the intended values, absolute",
            {"config", "clause", "programs", "pixels", "max_error", "worst", "worst_want",
             "pixels_off", "note"});
  for (std::size_t i = 0; i < configs.size(); ++i) {
    const KbFormats& f = models[i].formats();
    const auto rows = kb_out_of_contract(f, KbSetupOptions::from_config(configs[i]),
                                         contract(models[i], configs[i]),
                                         static_cast<std::uint64_t>(programs), seed);
    out.print("  {}\n  {:<38} {:>8} {:>9} {:>9} {:>17} {:>12}\n", configs[i].name(),
              "clause broken first", "programs", "pixels", "max err", "worst: out/want",
              "> 1 LSB off");
    for (const KbContractRow& r : rows) {
      if (!r.note.empty()) {
        out.print("  {:<38} {}\n", r.clause, r.note);
      } else {
        out.print("  {:<38} {:>8} {:>9} {:>9.4f} {:>8.4f}/{:<8.4f} {:>12}\n", r.clause, r.programs,
                  r.pixels, r.max_error, r.worst, r.worst_want, r.off);
      }
      out.row({configs[i].name(), r.clause, static_cast<std::int64_t>(r.programs),
               static_cast<std::int64_t>(r.pixels), r.max_error, r.worst, r.worst_want,
               static_cast<std::int64_t>(r.off), r.note});
    }
  }
}

}  // namespace

const PipelineInfo& kb_pipeline() {
  static const PipelineInfo info{
      .name = "kb",
      .summary = "Kuijk-Blake forward-differencing engine: piecewise-quadratic cos^n along spans",
      .top = "kb_engine",
      .rtl_files = {"rtl/common", "rtl/kb/kb_engine.sv"},
      .ports = {{"in_n_i", true, {"n"}},
                {"in_count_i", true, {"count"}},
                {"in_f_i", true, {"f"}},
                {"in_d1_i", true, {"d1"}},
                {"in_d2_i", true, {"d2"}},
                {"in_reload_i", true, {"reload"}},
                {"out_value_o", false, {"value"}},
                {"out_last_o", false, {"last"}}},
      .make_model = make_model,
      .make_stimulus = make_stimulus,
      .independent_vectors = false,
      // Vectors are span-program words, about 15 pixels each on average.
      .default_vectors = 100000,
      .latency = latency,
      .one_per_clock = true,
      .cycles = cycles,
      .stages = stages,
      .coverpoints = coverpoints,
      .native = native,
      .contract = contract,
      .float_error = float_error,
      .analyze = analyze,
      .mutants = {{"kb-event-late", "default", "rtl/kb/kb_engine.sv", "(head_n <= i_q)",
                   "(head_n < i_q)", "events applied one pixel late"},
                  {"kb-reload", "default", "rtl/kb/kb_engine.sv",
                   "assign d1_step = apply_event & head_reload ? head_d1 : d1;",
                   "assign d1_step = d1;", "reload of the first difference ignored"},
                  {"kb-d2-hold", "d2_only", "rtl/kb/kb_engine.sv", "      d2_q <= d2_step;",
                   "      d2_q <= d2_q;", "an event's second difference lasts one step only"},
                  {"kb-drain", "default", "rtl/kb/kb_engine.sv",
                   "      remaining_q <= remaining_q - 1'b1;", "      remaining_q <= remaining_q;",
                   "left-over event words never dropped"}},
  };
  return info;
}

}  // namespace phongsim
