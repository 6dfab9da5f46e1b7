// shade_kb's model (model/shade_kb.h) against its parts: every channel of every pixel is what a
// kb engine (KbModel) gives for that channel's program alone, x = x0 + i and y the span's, on
// random colour spans of every configuration's setup (a failure names configuration and span);
// the word layout shade_kb_span_words writes; and the input contract: setup programs on the
// screen are inside it, each clause broken in one channel is counted against that clause.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "base/error.h"
#include "base/rng.h"
#include "model/config.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "model/shade_kb.h"
#include "sim/pipelines/kb.h"
#include "sim/pipelines/registry.h"
#include "sim/pipelines/shade_kb.h"
#include "tests/config_items.h"

namespace phongsim {
namespace {

using Words = std::vector<std::vector<std::int64_t>>;
using M = ShadeKbModel;

struct Loaded {
  explicit Loaded(const std::string& name)
      : cfg(Config::load(pipeline_configs(find_pipeline("shade_kb"))[0].parent_path() /
                         (name + ".toml"))),
        model(make_model(find_pipeline("shade_kb"), cfg)),
        f(dynamic_cast<const ShadeKbModel&>(*model).formats()),
        setup(KbSetupOptions::from_config(cfg)) {}
  Config cfg;
  std::unique_ptr<PipelineModel> model;
  KbFormats f;
  KbSetupOptions setup;
};

// Three programs of one length: each channel half a setup program, half kb's random words.
std::array<Words, 3> RandomPrograms(Rng& rng, const Loaded& l, int length) {
  std::array<Words, 3> p;
  const std::uint64_t max_events = (std::uint64_t{1} << l.f.event_bits) - 1;
  for (Words& w : p) {
    if (rng.below(2) == 0) {
      w = kb_random_words(rng, l.f, max_events, length);
    } else {
      KbSpan span = kb_random_span(rng, l.setup, length);
      w = kb_fitting_program(span, l.f, l.setup);
    }
  }
  return p;
}

TEST(ShadeKb, EveryChannelIsItsEngineAlone) {
  for (const char* name : {"default", "narrow", "wide"}) {
    const Loaded l(name);
    ShadeKbModel model(l.f);
    for (std::uint64_t s = 0; s < 300; ++s) {
      Rng rng(3, kStimulusStream, s);
      const int length = 1 + static_cast<int>(rng.below(s % 10 == 0 ? 4096 : 64));
      const auto programs = RandomPrograms(rng, l, length);
      const auto x = static_cast<std::int64_t>(rng.below(2048));
      const auto y = static_cast<std::int64_t>(rng.below(2048));
      std::vector<std::int64_t> got;
      for (const auto& w : shade_kb_span_words(programs, x, y, 12345)) (void)model.eval(w, got);
      ASSERT_EQ(got.size(), 5U * static_cast<std::size_t>(length)) << name << " span " << s;
      for (std::size_t c = 0; c < 3; ++c) {
        KbModel engine(l.f);
        std::vector<std::int64_t> want;
        for (const auto& w : programs[c]) (void)engine.eval(w, want);
        ASSERT_EQ(want.size(), 2U * static_cast<std::size_t>(length));
        for (int i = 0; i < length; ++i) {
          const auto p = static_cast<std::size_t>(i);
          ASSERT_EQ(got[5 * p], (x + i) % 2048) << name << " span " << s << " pixel " << i;
          ASSERT_EQ(got[5 * p + 1], y) << name << " span " << s << " pixel " << i;
          ASSERT_EQ(got[5 * p + 2 + c], want[2 * p])
              << name << " span " << s << " channel " << c << " pixel " << i;
        }
      }
    }
  }
}

TEST(ShadeKb, SpanWordsLayout) {
  const Words r{{4, 1, 10, 11, 12, 0}, {2, 0, 0, 21, 22, 1}};
  const Words g{{4, 0, 30, 31, 32, 0}};
  const Words b{{4, 2, 40, 41, 42, 0}, {1, 0, 0, 51, 52, 0}, {3, 0, 0, 61, 62, 1}};
  const Words w = shade_kb_span_words({r, g, b}, 7, 9, 99);
  ASSERT_EQ(w.size(), 4U);
  EXPECT_EQ(w[0],
            (std::vector<std::int64_t>{4, 7, 9, 1, 0, 2, 10, 30, 40, 11, 31, 41, 12, 32, 42, 0}));
  EXPECT_EQ(w[1][M::kN], 2);
  EXPECT_EQ(w[1][M::kD1], 21);
  EXPECT_EQ(w[1][M::kD2], 22);
  EXPECT_EQ(w[1][M::kReload], 1);
  EXPECT_EQ(w[1][M::kD1 + 2], 99);  // fields its channel does not read
  EXPECT_EQ(w[3][M::kD1 + 2], 61);
  EXPECT_EQ(w[3][M::kD2 + 2], 62);
  ShadeKbModel m(KbFormats::from_config(Loaded("default").cfg));
  for (std::size_t k = 0; k < w.size(); ++k) {
    const ShadeKbModel::Route route = m.route();
    EXPECT_EQ(route.header, k == 0);
    EXPECT_EQ(route.targets, k == 0 ? 0b111U : k == 1 ? 0b001U : 0b100U) << k;
    std::vector<std::int64_t> out;
    (void)m.eval(w[k], out);
  }
}

// Each word's first broken clause, from reset.
std::vector<int> Clauses(const Loaded& l, const Words& words) {
  InputContract c = find_pipeline("shade_kb").contract(*l.model, l.cfg);
  std::vector<int> r;
  for (const auto& w : words) r.push_back(c.check(w));
  return r;
}

TEST(ShadeKb, ContractFollowsTheDemux) {
  const Loaded l("default");
  const std::int64_t one = std::int64_t{1} << l.f.acc.frac_bits;
  const InputContract c = find_pipeline("shade_kb").contract(*l.model, l.cfg);
  EXPECT_EQ(c.clauses().back(), "span on the screen: x0 + n < 2048");
  // Setup programs on the screen: inside.
  for (std::uint64_t s = 0; s < 100; ++s) {
    Rng rng(5, kStimulusStream, s);
    const int length = 1 + static_cast<int>(rng.below(2000));
    std::array<Words, 3> p;
    for (Words& w : p) {
      KbSpan span = kb_random_span(rng, l.setup, length);
      w = kb_fitting_program(span, l.f, l.setup);
    }
    for (const int b : Clauses(l, shade_kb_span_words(p, 2047 - length, 5))) {
      EXPECT_EQ(b, InputContract::kIn) << "span " << s;
    }
  }
  // Green's events out of order while red's and blue's are in order: clause 3 on green's second
  // event word only (a checker that routed a word to two channels would see it elsewhere).
  const Words r{{9, 1, one / 2, 0, 0, 0}, {8, 0, 0, 0, 0, 1}};
  const Words g{{9, 2, one / 2, 0, 0, 0}, {6, 0, 0, 0, 0, 1}, {5, 0, 0, 0, 0, 1}};
  const Words b{{9, 1, one / 2, 0, 0, 0}, {2, 0, 0, 0, 0, 1}};
  const int in = InputContract::kIn;
  EXPECT_EQ(Clauses(l, shade_kb_span_words({r, g, b}, 0, 0)),
            (std::vector<int>{in, in, in, 3, in}));
  // A header's f out of range in blue only; Δf too large in a reloading event of red; off screen.
  const Words bad_f{{9, 0, 2 * one, 0, 0, 0}};
  EXPECT_EQ(Clauses(l, shade_kb_span_words({b, r, bad_f}, 0, 0)), (std::vector<int>{0, in, in}));
  const Words bad_d1{{9, 1, 0, 0, 0, 0}, {3, 0, 0, 2 * one, 0, 1}};
  EXPECT_EQ(Clauses(l, shade_kb_span_words({bad_d1, r, r}, 0, 0)),
            (std::vector<int>{in, 1, in, in}));
  EXPECT_EQ(Clauses(l, shade_kb_span_words({r, r, r}, 2038, 0))[0], in);  // x0 + n = 2047
  EXPECT_EQ(Clauses(l, shade_kb_span_words({r, r, r}, 2039, 0))[0], 4);
}

}  // namespace
}  // namespace phongsim
