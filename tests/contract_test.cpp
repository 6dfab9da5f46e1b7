// Input contracts (sim/cosim/contract.h, each pipeline's registry entry and docs/<pipeline>.md
// "Input contract"): per pipeline, a vector known to be inside the contract is, and one vector per
// clause that breaks exactly that clause is counted against it; the kb checker follows the
// engine's parse of span programs; and outside Lyon's, Kuijk-Blake's and the quadratic
// interpolator's contracts the units give the wrong answers the contracts warn of.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/rng.h"
#include "model/kb.h"
#include "model/kb_setup.h"
#include "model/lyon.h"
#include "model/plan.h"
#include "model/quad.h"
#include "model/quad_setup.h"
#include "ref/kb_float.h"
#include "sim/pipelines/kb.h"
#include "sim/pipelines/lyon.h"
#include "sim/pipelines/quad.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

using Vector = std::vector<std::int64_t>;

struct Loaded {
  Config cfg;
  const PipelineInfo& pipeline;
  std::unique_ptr<PipelineModel> model;
  InputContract contract;

  Loaded(const std::string& pipeline_name, const std::string& config)
      : cfg(Config::load(PHONGSIM_SOURCE_DIR "/configs/" + pipeline_name + "/" + config + ".toml")),
        pipeline(find_pipeline(pipeline_name)),
        model(make_model(pipeline, cfg)),
        contract(pipeline.contract(*model, cfg)) {}

  // Each word through a fresh checker, in order: the clause of each.
  std::vector<int> clauses(const std::vector<Vector>& words) const {
    InputContract c = contract;
    std::vector<int> out;
    for (const Vector& w : words) out.push_back(c.check(w));
    return out;
  }
  int clause(const Vector& v) const { return clauses({v})[0]; }
};

// Counting `vectors` gives `in` inside and, per clause, `by_clause`.
void ExpectCounts(const Loaded& l, const std::vector<Vector>& vectors, std::uint64_t in,
                  const std::vector<std::uint64_t>& by_clause) {
  InputContract c = l.contract;
  ContractCounts counts;
  for (const Vector& v : vectors) c.count(v, v.size(), counts);
  EXPECT_EQ(counts.in, in);
  EXPECT_EQ(counts.by_clause, by_clause);
  EXPECT_EQ(counts.out(), vectors.size() - in);
}

// ---- Lyon ----

Vector LyonPixelRaw(const LyonFormats& f, Vec3 n0, Vec3 n1, double a, Vec3 v, Vec3 l, double shin) {
  return quantize_lyon_pixel(LyonPixel{n0, n1, a, v, l, shin}, f);
}

TEST(Contract, LyonOnePerClause) {
  const Loaded l("lyon", "default");
  ASSERT_EQ(l.contract.clauses(),
            (std::vector<std::string>{"a in [0, 1]", "|N'| in [1/sqrt 2, 1]", "|V| = 1", "|L| = 1",
                                      "shininess >= 1"}));
  const LyonFormats& f = dynamic_cast<const LyonModel&>(*l.model).formats();
  const Vec3 up{0, 0, 1}, side{1, 0, 0}, l_in{0, 0.6, 0.8};
  const Vector in = LyonPixelRaw(f, up, up, 0, up, l_in, 10);
  // Normals 90 degrees apart, halfway: |N'| = cos 45 degrees, the contract's lower end.
  const Vector at_edge = LyonPixelRaw(f, up, side, 0.5, up, l_in, 10);
  const std::vector<Vector> out{
      LyonPixelRaw(f, up, up, 1.5, up, l_in, 10),             // a > 1
      LyonPixelRaw(f, 1.2 * up, 1.2 * up, 0, up, l_in, 10),   // |N'| = 1.2
      LyonPixelRaw(f, side, -1.0 * side, 0.5, up, l_in, 10),  // |N'| = 0
      LyonPixelRaw(f, up, up, 0, 0.5 * up, l_in, 10),         // |V| = 1/2
      LyonPixelRaw(f, up, up, 0, up, 1.9 * l_in, 10),         // |L| = 1.9
      LyonPixelRaw(f, up, up, 0, up, l_in, 0),                // shininess 0
  };
  EXPECT_EQ(l.clause(in), InputContract::kIn);
  EXPECT_EQ(l.clause(at_edge), InputContract::kIn);
  EXPECT_EQ(l.clauses(out), (std::vector<int>{0, 1, 1, 2, 3, 4}));
  std::vector<Vector> all = out;
  all.push_back(in);
  ExpectCounts(l, all, 1, {1, 2, 1, 1, 1});
}

// random_lyon_pixel, what analyze measures, stays inside the contract for every configuration.
TEST(Contract, LyonAnalysisPixelsAreInside) {
  for (const auto& path : pipeline_configs(find_pipeline("lyon"))) {
    const Loaded l("lyon", path.stem().string());
    const LyonFormats& f = dynamic_cast<const LyonModel&>(*l.model).formats();
    const LyonOutputError e = lyon_output_error(dynamic_cast<const LyonModel&>(*l.model), 2000, 1);
    EXPECT_EQ(e.out_of_contract, 0U) << path;
    EXPECT_EQ(e.samples, 2000U) << path;
    (void)f;
  }
}

// The finding: outside the contract the unit saturates into answers the float datapath
// does not give — a full highlight where there is none, a diffuse term above 1.
TEST(Contract, LyonOutsideGivesWrongAnswers) {
  const Loaded l("lyon", "default");
  const auto rows = lyon_out_of_contract(dynamic_cast<const LyonModel&>(*l.model), 6000, 1);
  ASSERT_EQ(rows.size(), l.contract.clauses().size() + 1);
  double spec_worst = 0;
  for (const auto& r : rows) {
    EXPECT_GT(r.samples, 0U) << r.clause;
    spec_worst = std::max(spec_worst, r.spec_max_error);
    for (std::size_t c = 0; c + 1 < rows.size(); ++c) {
      if (r.clause == rows[c].clause) {
        InputContract check = l.contract;
        EXPECT_EQ(check.check(r.worst), static_cast<int>(c)) << r.clause;
      }
    }
  }
  EXPECT_GT(spec_worst, 0.5);        // a highlight where the float datapath has none
  EXPECT_GT(rows[1].diff_max, 1.0);  // a long N' is not normalized back
  EXPECT_GT(rows[1].diff_above_one, 0U);
}

// ---- LIRP ----

TEST(Contract, LirpOnePerClause) {
  const Loaded l("lirp", "default");  // p S1.10, a 1.10, out S1.10
  const std::int64_t one = 1024;
  const Vector in{one, -one, 0, -one, one, 512, 300};
  EXPECT_EQ(l.clause(in), InputContract::kIn);
  const std::vector<Vector> out{
      {0, 0, 0, 0, 0, 0, one + 1},   // a > 1
      {-one - 1, 0, 0, 0, 0, 0, 0},  // p0_x < -1
      {0, 0, 0, 0, 0, 2047, one},    // p1_z > 1
  };
  EXPECT_EQ(l.clauses(out), (std::vector<int>{0, 1, 1}));
  // The narrow configuration's output S0.5 stops below 1: p = 1 leaves it.
  const Loaded narrow("lirp", "narrow");  // p S1.6, a 1.4
  EXPECT_EQ(narrow.clause({64, 0, 0, 64, 0, 0, 8}), 2);
  EXPECT_EQ(narrow.clause({32, 0, 0, 32, 0, 0, 8}), InputContract::kIn);
  // Its ends exactly: 31/32 (62/64) is in, 63/64 out; -1 is in.
  EXPECT_EQ(narrow.clause({62, 0, 0, 62, 0, 0, 8}), InputContract::kIn);
  EXPECT_EQ(narrow.clause({63, 0, 0, 63, 0, 0, 8}), 2);
  EXPECT_EQ(narrow.clause({-64, 0, 0, -64, 0, 0, 8}), InputContract::kIn);
  // Unsigned channels: [0, 1].
  const Loaded colour("lirp", "colour8");
  EXPECT_EQ(colour.contract.clauses()[1], "p0, p1 in [0, 1]");
  EXPECT_EQ(colour.clause({256, 0, 0, 0, 0, 0, 256}), InputContract::kIn);
  EXPECT_EQ(colour.clause({257, 0, 0, 0, 0, 0, 256}), 1);
  ExpectCounts(l, {in, out[0], out[1], out[2]}, 1, {1, 2, 0});
}

// ---- Kuijk–Blake ----

Vector Header(std::int64_t last, std::int64_t count, std::int64_t f, std::int64_t d1,
              std::int64_t d2) {
  return {last, count, f, d1, d2, 0};
}
Vector Event(std::int64_t at, std::int64_t d1, std::int64_t d2, bool reload) {
  return {at, 0, 0, d1, d2, reload ? 1 : 0};
}

TEST(Contract, KbSetupProgramsAreInside) {
  for (const auto& config : {"default", "d2_only"}) {
    const Loaded l("kb", config);
    const KbFormats& f = dynamic_cast<const KbModel&>(*l.model).formats();
    const KbSetupOptions setup = KbSetupOptions::from_config(l.cfg);
    for (std::uint64_t s = 0; s < 200; ++s) {
      Rng rng(7, 0, s);
      KbSpan span = kb_random_span(rng, setup, 64 + static_cast<int>(rng.below(4000)));
      std::vector<Vector> words;
      try {
        words = kb_program(span, setup.policy, f);
      } catch (const Error&) {
        continue;  // too many events for the header
      }
      for (const int c : l.clauses(words)) EXPECT_EQ(c, InputContract::kIn) << config << " " << s;
    }
  }
}

TEST(Contract, KbOnePerClause) {
  const Loaded l("kb", "default");  // acc S2.32: 1.0 is 2^32
  const std::int64_t one = std::int64_t{1} << 32;
  EXPECT_EQ(l.contract.clauses(),
            (std::vector<std::string>{"f in [0, 1]", "|d1| <= 1, |d2| <= 2", "length <= 4096",
                                      "events ordered, before the last pixel"}));
  // A span with two events in order, then a header of the next span.
  EXPECT_EQ(l.clauses({Header(9, 2, one / 2, one / 16, 0), Event(3, one / 8, 0, true),
                       Event(5, 0, -one, false), Header(0, 0, one, 0, 0)}),
            (std::vector<int>{InputContract::kIn, InputContract::kIn, InputContract::kIn,
                              InputContract::kIn}));
  EXPECT_EQ(l.clause(Header(0, 0, -1, 0, 0)), 0);            // f < 0
  EXPECT_EQ(l.clause(Header(0, 0, one + 1, 0, 0)), 0);       // f > 1
  EXPECT_EQ(l.clause(Header(3, 0, 0, one + 1, 0)), 1);       // d1 > 1
  EXPECT_EQ(l.clause(Header(3, 0, 0, 0, -2 * one - 1)), 1);  // d2 < -2
  // An event's d1 counts only when it reloads.
  EXPECT_EQ(l.clauses({Header(9, 1, 0, 0, 0), Event(3, 3 * one, 0, false)})[1], InputContract::kIn);
  EXPECT_EQ(l.clauses({Header(9, 1, 0, 0, 0), Event(3, 3 * one, 0, true)})[1], 1);
  // Events out of order, at the last pixel, and after it (left over).
  EXPECT_EQ(l.clauses({Header(7, 2, 0, 0, 0), Event(5, 0, 0, true), Event(3, 0, 0, true)}),
            (std::vector<int>{InputContract::kIn, InputContract::kIn, 3}));
  EXPECT_EQ(l.clauses({Header(2, 2, 0, 0, 0), Event(2, 0, 0, true), Event(4095, 0, 0, true)}),
            (std::vector<int>{InputContract::kIn, 3, 3}));
  // 8 guard bits hold spans up to 23 pixels within half an LSB.
  const Loaded narrow("kb", "narrow_d2");
  EXPECT_EQ(narrow.contract.clauses()[2], "length <= 23");
  EXPECT_EQ(narrow.clause(Header(22, 0, 0, 0, 0)), InputContract::kIn);
  EXPECT_EQ(narrow.clause(Header(23, 0, 0, 0, 0)), 2);
  ExpectCounts(l,
               {Header(0, 0, -1, 0, 0), Header(3, 0, 0, one + 1, 0), Header(7, 1, 0, 0, 0),
                Event(7, 0, 0, true), Header(0, 0, 0, 0, 0)},
               2, {1, 1, 0, 1});
}

// `phongsim analyze kb`: the setup's programs are inside the contract and there within the
// output's half LSB plus the drift bound the guard bits give (half an LSB); outside it the engine
// wraps or mis-steps into values far from what the program was written for.
TEST(Contract, KbAnalysisInsideAndOutside) {
  const Loaded l("kb", "default");
  const KbFormats& f = dynamic_cast<const KbModel&>(*l.model).formats();
  const KbSetupOptions setup = KbSetupOptions::from_config(l.cfg);
  const KbOutputError in = kb_output_error(f, setup, l.contract, 100, 1);
  EXPECT_EQ(in.out_of_contract, 0U);
  EXPECT_EQ(in.programs, 100U);
  EXPECT_GT(in.pixels, 1000U);
  EXPECT_LE(in.max, 1.0);
  const auto rows = kb_out_of_contract(f, setup, l.contract, 500, 1);
  ASSERT_EQ(rows.size(), l.contract.clauses().size() + 1);
  EXPECT_FALSE(rows[2].note.empty());  // 24 guard bits cover every length n can express
  EXPECT_EQ(rows[2].programs, 0U);
  for (const std::size_t c : {0, 1, 3, 4}) EXPECT_GT(rows[c].programs, 0U) << rows[c].clause;
  EXPECT_GT(rows[1].max_error, 0.5);  // a difference beyond the range wraps the accumulator
  EXPECT_GT(rows[3].max_error, 0.1);  // a misplaced event leaves the span's curve
  EXPECT_GT(rows[4].off, 0U);
  // With 8 guard bits a span longer than 23 pixels drifts by more than an output LSB.
  const Loaded narrow("kb", "narrow_reload");
  const KbFormats& nf = dynamic_cast<const KbModel&>(*narrow.model).formats();
  const auto nrows =
      kb_out_of_contract(nf, KbSetupOptions::from_config(narrow.cfg), narrow.contract, 500, 1);
  EXPECT_TRUE(nrows[2].note.empty());
  EXPECT_GT(nrows[2].programs, 0U);
  EXPECT_GT(nrows[2].max_error, 1.0 / 256);
}

// ---- quadratic interpolator ----

TEST(Contract, QuadOnePerClause) {
  const Loaded l("quad", "default");
  const QuadFormats& f = dynamic_cast<const QuadModel&>(*l.model).formats();
  const auto program = [&f](double size) {
    const auto tri = quad::quantize({10, 10}, {10 + size, 10.5}, {10.25, 10 + size}, f.sub_bits);
    const quad::Coeffs c = quad::linear_coefficients(0.2, 0.5, 0.9);
    return QuadModel::words(quad_program(tri, {c, c, c}, f));
  };
  const Vector in = program(100);
  EXPECT_EQ(l.clause(in), InputContract::kIn);
  EXPECT_EQ(l.clause(program(2000)), InputContract::kIn);  // 24 guard bits: any box
  // Edge words the setup never writes: kind 3, a remainder not below its divisor, a divisor
  // that is not a whole number of subpixel rows.
  int used = -1;
  for (int k = 0; k < 3 && used < 0; ++k) {
    if (in[4 + 6 * k] != 0) used = k;
  }
  ASSERT_GE(used, 0);
  const std::size_t e = 4 + 6 * static_cast<std::size_t>(used);
  Vector kind = in, rem = in, div = in;
  kind[e] = 3;
  rem[e + 1 + 1] = rem[e + 3];
  div[e + 3] += 1;
  EXPECT_EQ(l.clauses({kind, rem, div}), (std::vector<int>{0, 0, 0}));
  // 8 guard bits: the box must stay small (1 + 3·9² = 244 <= 256 for 10 x 10; 11 x 11 is not).
  const Loaded narrow("quad", "narrow_quad");
  const QuadFormats& nf = dynamic_cast<const QuadModel&>(*narrow.model).formats();
  Vector box = QuadModel::words(QuadProgram{});  // no edges, no rows
  EXPECT_EQ(narrow.clause(box), InputContract::kIn);
  box[0] = 100, box[1] = 100, box[2] = 109, box[3] = 109;
  EXPECT_EQ(narrow.clause(box), InputContract::kIn);
  box[2] = 110, box[3] = 110;
  EXPECT_EQ(narrow.clause(box), 1);
  (void)nf;
  ExpectCounts(l, {in, kind, rem}, 1, {2, 0});
}

// `phongsim analyze quad`: inside the contract the narrow configuration stays within its
// truncation's LSB plus the guard bits' half LSB of direct evaluation (its larger triangles,
// outside, do not: QuadAnalysis.DriftBoundAndOutputError); outside, edge words the setup never
// writes cover the wrong pixels, and colour samples too large for the accumulator wrap.
TEST(Contract, QuadAnalysisInsideAndOutside) {
  const Loaded narrow("quad", "narrow_quad");
  const QuadFormats& nf = dynamic_cast<const QuadModel&>(*narrow.model).formats();
  const QuadOutputError in = quad_output_error(nf, QuadMode::quadratic, 100, 1, &narrow.contract);
  EXPECT_GT(in.out_of_contract, 0U);
  EXPECT_GT(in.pixels, 100U);
  EXPECT_LE(in.max, 1.5);  // it truncates: up to 1 LSB, plus the drift's half
  const auto nrows = quad_out_of_contract(nf, QuadMode::quadratic, narrow.contract, 300, 1);
  ASSERT_EQ(nrows.size(), narrow.contract.clauses().size() + 1);
  EXPECT_GT(nrows[1].programs, 0U);
  EXPECT_GT(nrows[1].max_error, 2.0 / 256);  // boxes beyond 10 x 10 drift past that

  const Loaded l("quad", "default");
  const QuadFormats& f = dynamic_cast<const QuadModel&>(*l.model).formats();
  const auto rows = quad_out_of_contract(f, QuadMode::quadratic, l.contract, 300, 1);
  EXPECT_GT(rows[0].programs, 0U);
  EXPECT_GT(rows[0].extra + rows[0].missing, 0U);  // wrong coverage
  EXPECT_FALSE(rows[1].note.empty());              // 24 guard bits: any box
  EXPECT_GT(rows[2].programs, 0U);
  EXPECT_GT(rows[2].max_error, 0.5);  // wrapped colours
}

// Co-simulation's random stimulus covers the whole format range on purpose: every pipeline's
// default configuration draws vectors both inside and outside its contract.
TEST(Contract, RandomStimulusIsOnBothSides) {
  for (const auto& name : {"lirp", "lyon", "kb", "quad", "shade_kb"}) {
    const Loaded l(name, "default");
    const Stimulus s = l.pipeline.make_stimulus(*l.model, l.cfg);
    InputContract c = l.contract;
    ContractCounts counts;
    Vector v(l.model->inputs().size());
    for (std::uint64_t i = 0; i < s.directed_count() + 2000; ++i) {
      s.vector(1, i, v);
      c.count(v, v.size(), counts);
    }
    EXPECT_GT(counts.in, 0U) << name;
    EXPECT_GT(counts.out(), 0U) << name;
  }
}

// The checks that run a batch on the kernel instruction set (LIRP's and Lyon's): a batch of
// stimulus vectors checked in one call, and in calls of 37, on every instruction set, gives the
// clauses of one vector at a time on the baseline.
TEST(Contract, BatchesAreOneAtATimeOnEveryIsa) {
  const fx::Isa chosen = fx::kernel_isa();
  for (const auto& name : {"lirp", "lyon"}) {
    const Loaded l(name, "default");
    const Stimulus s = l.pipeline.make_stimulus(*l.model, l.cfg);
    const std::size_t width = l.model->inputs().size();
    const std::size_t count = s.directed_count() + 3000;
    Vector vectors(count * width);
    s.vectors(1, 0, count, vectors);
    fx::set_kernel_isa(fx::Isa::baseline);
    std::vector<int> want;
    for (std::size_t i = 0; i < count; ++i) {
      want.push_back(
          l.clause(Vector(vectors.begin() + static_cast<std::ptrdiff_t>(i * width),
                          vectors.begin() + static_cast<std::ptrdiff_t>((i + 1) * width))));
    }
    for (const fx::Isa isa : fx::supported_isas()) {
      fx::set_kernel_isa(isa);
      for (const std::size_t batch : {count, std::size_t{37}}) {
        InputContract c = l.contract;
        std::vector<std::int16_t> got(count);
        for (std::size_t b = 0; b < count; b += batch) {
          const std::size_t m = std::min(batch, count - b);
          c.check(std::span(vectors).subspan(b * width, m * width), width,
                  std::span(got).subspan(b, m));
        }
        for (std::size_t i = 0; i < count; ++i) {
          ASSERT_EQ(got[i], want[i])
              << name << " " << fx::isa_name(isa) << " batch " << batch << " vector " << i;
        }
      }
    }
  }
  fx::set_kernel_isa(chosen);
}

}  // namespace
}  // namespace phongsim
