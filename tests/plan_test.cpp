// The compiled plans (model/plan.h and each model's plan) against the stage-by-stage path they
// replace on the hot path: bit-identical in every configuration in configs/. The requantization
// step exhaustively against fx::resize_raw (every value of every format up to 10 bits into many
// formats, every mode); LIRP exhaustively over every (p0, p1, a) where the three together are at
// most 25 bits, random otherwise; Lyon, kb, quad and shade_kb on their co-simulation stimulus
// (directed corners and seeded random vectors, half of them arbitrary bit patterns) plus, for Lyon,
// vectors of uniformly random raw fields. A failure names configuration, seed and vector index.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/rng.h"
#include "model/config.h"
#include "model/kb.h"
#include "model/lirp.h"
#include "model/lyon.h"
#include "model/plan.h"
#include "model/quad.h"
#include "model/shade_kb.h"
#include "model/shade_lyon.h"
#include "model/shade_quad.h"
#include "sim/pipelines/registry.h"
#include "tests/config_items.h"

namespace phongsim {
namespace {

// ---- the requantization step ----

std::vector<fx::Format> SmallFormats(int max_width) {
  std::vector<fx::Format> f;
  for (int w = 1; w <= max_width; ++w) {
    for (int s = 0; s <= 1; ++s) {
      for (int frac = 0; frac <= w - s; frac += std::max(1, (w - s) / 3)) {
        f.push_back({s == 1, w - s - frac, frac});
      }
    }
  }
  return f;
}

TEST(Requant, EveryValueEveryModeMatchesResizeRaw) {
  const auto from_formats = SmallFormats(10);
  const auto to_formats = SmallFormats(9);
  std::uint64_t checked = 0;
  for (const fx::Format from : from_formats) {
    for (const fx::Format to : to_formats) {
      for (const auto round : {fx::Round::truncate, fx::Round::half_up, fx::Round::half_even}) {
        for (const auto overflow : {fx::Overflow::wrap, fx::Overflow::saturate}) {
          const fx::Requant step(from, to, round, overflow);
          const fx::Saturate clamp(from, to, round);  // the saturating step without the wrap
          ASSERT_TRUE(step.fits_int64());
          ASSERT_EQ(step.saturates(), overflow == fx::Overflow::saturate);
          for (std::int64_t x = from.min_raw(); x <= from.max_raw(); ++x) {
            const std::int64_t want = fx::resize_raw(x, from, to, round, overflow);
            ASSERT_EQ(step(x), want)
                << from.str() << " -> " << to.str() << " " << fx::to_string(round) << " "
                << fx::to_string(overflow) << " x = " << x;
            if (step.saturates()) {
              ASSERT_EQ(clamp(x), want) << from.str() << " -> " << to.str() << " x = " << x;
            }
            ++checked;
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 1'000'000U);
}

// Wide formats: range ends, neighbours and random values, up to the int64 limit of the step.
TEST(Requant, WideFormatsMatchResizeRawWhereTheyFit) {
  const fx::Format wide[] = {{true, 20, 40}, {false, 30, 30}, {true, 0, 55}, {false, 61, 0},
                             {true, 2, 32},  {false, 0, 8},   {true, 30, 0}, {false, 10, 50}};
  Rng rng(1, kStimulusStream, 0);
  for (const fx::Format from : wide) {
    for (const fx::Format to : wide) {
      for (const auto round : {fx::Round::truncate, fx::Round::half_up, fx::Round::half_even}) {
        for (const auto overflow : {fx::Overflow::wrap, fx::Overflow::saturate}) {
          const fx::Requant step(from, to, round, overflow);
          if (!step.fits_int64()) continue;
          std::vector<std::int64_t> xs{from.min_raw(),     from.min_raw() + 1, -1, 0, 1,
                                       from.max_raw() - 1, from.max_raw()};
          for (int i = 0; i < 2000; ++i) {
            xs.push_back(from.min_raw() +
                         static_cast<std::int64_t>(rng.below(
                             static_cast<std::uint64_t>(from.max_raw() - from.min_raw()) + 1)));
          }
          for (const std::int64_t x : xs) {
            if (x < from.min_raw() || x > from.max_raw()) continue;
            ASSERT_EQ(step(x), fx::resize_raw(x, from, to, round, overflow))
                << from.str() << " -> " << to.str() << " x = " << x;
          }
        }
      }
    }
  }
}

// ---- every configuration ----

class PlanTest : public ::testing::TestWithParam<Item> {
 protected:
  Config cfg_ = Config::load(GetParam().config);
  std::unique_ptr<PipelineModel> model_ = make_model(*GetParam().pipeline, cfg_);
  std::string name_ = fmt::format("{}/{}", GetParam().pipeline->name, cfg_.name());
};

constexpr std::uint64_t kSeed = 1;
constexpr std::uint64_t kRandomVectors = 20000;

// The pipeline's co-simulation vectors: directed corners then kRandomVectors random ones.
std::vector<std::int64_t> StimulusVectors(const PipelineInfo& p, const PipelineModel& m,
                                          const Config& cfg) {
  const Stimulus stimulus = p.make_stimulus(m, cfg);
  const std::size_t n_in = m.inputs().size();
  const std::uint64_t count = stimulus.directed_count() + kRandomVectors;
  std::vector<std::int64_t> v(count * n_in);
  for (std::uint64_t i = 0; i < count; ++i) {
    stimulus.vector(kSeed, i, std::span(v).subspan(i * n_in, n_in));
  }
  return v;
}

TEST_P(PlanTest, PlanIsUsed) {
  // Every built-in configuration runs the plan (none falls back to the stage path).
  if (const auto* m = dynamic_cast<const LirpModel*>(model_.get())) {
    EXPECT_TRUE(m->plan().usable()) << name_;
  } else if (const auto* m = dynamic_cast<const LyonModel*>(model_.get())) {
    EXPECT_TRUE(m->plan().usable()) << name_;
  } else if (const auto* m = dynamic_cast<const QuadModel*>(model_.get())) {
    EXPECT_TRUE(m->plan().usable()) << name_;
  } else if (const auto* m = dynamic_cast<const KbModel*>(model_.get())) {
    EXPECT_TRUE(KbPlan(m->formats()).usable()) << name_;
  } else if (const auto* m = dynamic_cast<const ShadeKbModel*>(model_.get())) {
    EXPECT_TRUE(KbPlan(m->formats()).usable()) << name_;
  }
}

TEST_P(PlanTest, PlanEqualsStagePath) {
  const PipelineInfo& p = *GetParam().pipeline;
  const std::size_t n_in = model_->inputs().size();
  const std::size_t n_out = model_->outputs().size();

  if (const auto* lirp = dynamic_cast<const LirpModel*>(model_.get())) {
    // One component: exhaustive over (p0, p1, a) when they fit 25 bits, else random.
    const LirpFormats& f = lirp->formats();
    const int bits = 2 * f.p.width() + f.a.width();
    const LirpPlan& plan = lirp->plan();
    std::uint64_t checked = 0;
    const auto one = [&](std::int64_t p0, std::int64_t p1, std::int64_t a) {
      ASSERT_EQ(plan.component(p0, p1, a), lirp->component(p0, p1, a).p.raw)
          << name_ << ": p0 " << p0 << " p1 " << p1 << " a " << a;
      ++checked;
    };
    if (bits <= 25) {
      for (std::int64_t p0 = f.p.min_raw(); p0 <= f.p.max_raw(); ++p0) {
        for (std::int64_t p1 = f.p.min_raw(); p1 <= f.p.max_raw(); ++p1) {
          for (std::int64_t a = f.a.min_raw(); a <= f.a.max_raw(); ++a) one(p0, p1, a);
        }
      }
      EXPECT_EQ(checked, std::uint64_t{1} << bits) << name_;
    } else {
      Rng rng(kSeed, kStimulusStream, 0);
      const auto draw = [&](fx::Format fmt) {
        return fmt.min_raw() + static_cast<std::int64_t>(rng.below(
                                   static_cast<std::uint64_t>(fmt.max_raw() - fmt.min_raw()) + 1));
      };
      for (int i = 0; i < 2'000'000; ++i) one(draw(f.p), draw(f.p), draw(f.a));
    }
  }

  // Whole transactions: eval_batch (the plan, blocks of structure of arrays) against the stage
  // path, transaction by transaction, in order.
  std::vector<std::int64_t> vectors = StimulusVectors(p, *model_, cfg_);
  if (dynamic_cast<const LyonModel*>(model_.get()) != nullptr) {  // plus uniform raw fields
    Rng rng(kSeed, kStimulusStream, 1);
    for (int i = 0; i < 20000; ++i) {
      for (const Field& f : model_->inputs()) {
        vectors.push_back(f.fmt.min_raw() +
                          static_cast<std::int64_t>(rng.below(
                              static_cast<std::uint64_t>(f.fmt.max_raw() - f.fmt.min_raw()) + 1)));
      }
    }
  }
  std::vector<std::int64_t> got;
  std::vector<std::uint32_t> counts;
  model_->reset();
  (void)model_->eval_batch(vectors, got, &counts);
  ASSERT_EQ(counts.size(), vectors.size() / n_in);

  std::vector<std::int64_t> want;
  std::unique_ptr<KbModel> kb_stages;
  if (const auto* kb = dynamic_cast<const KbModel*>(model_.get())) {
    kb_stages = std::make_unique<KbModel>(kb->formats(), true);
  }
  std::unique_ptr<ShadeKbModel> shade_kb_stages;
  if (const auto* m = dynamic_cast<const ShadeKbModel*>(model_.get())) {
    shade_kb_stages = std::make_unique<ShadeKbModel>(m->formats(), true);
  }
  std::size_t at = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const auto in = std::span<const std::int64_t>(vectors).subspan(i * n_in, n_in);
    const std::size_t before = want.size();
    if (const auto* lirp = dynamic_cast<const LirpModel*>(model_.get())) {
      for (int c = 0; c < 3; ++c) want.push_back(lirp->component(in[c], in[3 + c], in[6]).p.raw);
    } else if (const auto* lyon = dynamic_cast<const LyonModel*>(model_.get())) {
      const LyonStages s = lyon->stages({in[0], in[1], in[2]}, {in[3], in[4], in[5]}, in[6],
                                        {in[7], in[8], in[9]}, {in[10], in[11], in[12]}, in[13]);
      want.insert(want.end(), {s.spec.raw, s.diff.raw});
    } else if (kb_stages) {
      (void)kb_stages->eval(in, want);
    } else if (shade_kb_stages) {
      (void)shade_kb_stages->eval(in, want);
    } else if (const auto* quad = dynamic_cast<const QuadModel*>(model_.get())) {
      (void)quad->walk(QuadModel::program(in), want);
    } else if (const auto* sq = dynamic_cast<const ShadeQuadModel*>(model_.get())) {
      // The walker's stage path, the triangle's number after x and y.
      std::vector<std::int64_t> px;
      const std::size_t n = sq->walker().walk(QuadModel::program(in.first(40)), px);
      for (std::size_t j = 0; j < 5 * n; j += 5) {
        want.insert(want.end(), {px[j], px[j + 1], in[40], px[j + 2], px[j + 3], px[j + 4]});
      }
    } else if (const auto* sl = dynamic_cast<const ShadeLyonModel*>(model_.get())) {
      // The walker's stage path, N' = C - 2^F, Lyon's stage path with N0 = N1 = N', a = 0.
      std::vector<std::int64_t> px;
      const std::size_t n = sl->walker().walk(QuadModel::program(in.first(40)), px);
      const std::int64_t half = std::int64_t{1} << sl->formats().lyon.vec.frac_bits;
      for (std::size_t j = 0; j < 5 * n; j += 5) {
        const std::array<std::int64_t, 3> np{px[j + 2] - half, px[j + 3] - half, px[j + 4] - half};
        const LyonStages st = sl->lyon().stages(np, np, 0, {in[40], in[41], in[42]},
                                                {in[43], in[44], in[45]}, in[46]);
        want.insert(want.end(), {px[j], px[j + 1], in[47], st.spec.raw, st.diff.raw});
      }
    }
    const std::size_t k = (want.size() - before) / n_out;
    ASSERT_EQ(counts[i], k) << name_ << ": seed " << kSeed << " vector " << i;
    ASSERT_TRUE(std::equal(want.begin() + static_cast<std::ptrdiff_t>(before), want.end(),
                           got.begin() + static_cast<std::ptrdiff_t>(at)))
        << name_ << ": seed " << kSeed << " vector " << i;
    at += k * n_out;
  }
  EXPECT_EQ(got, want) << name_;

  // eval() of one transaction at a time is the plan too.
  std::vector<std::int64_t> single;
  model_->reset();
  for (std::size_t i = 0; i < counts.size(); ++i) {
    (void)model_->eval(std::span<const std::int64_t>(vectors).subspan(i * n_in, n_in), single);
  }
  EXPECT_EQ(single, want) << name_;

  // The batch kernels compiled for every instruction set this CPU runs (model/plan.h), not
  // only the one it picks.
  const fx::Isa chosen = fx::kernel_isa();
  for (const fx::Isa isa : fx::supported_isas()) {
    fx::set_kernel_isa(isa);
    std::vector<std::int64_t> on_isa;
    model_->reset();
    (void)model_->eval_batch(vectors, on_isa);
    EXPECT_EQ(on_isa, want) << name_ << " on " << fx::isa_name(isa);
  }
  fx::set_kernel_isa(chosen);
}

// The block transposes (fx::to_fields, fx::from_fields) against their definition on every
// instruction set: every field count up to 17 (one, two and three groups of eight, full and
// partial) and every block length, writing nothing outside the transactions and fields named.
TEST(Transpose, FieldsAreTheDefinitionOnEveryIsa) {
  constexpr std::int64_t kGuard = 0x5a5a5a5a5a5a5a5a;
  constexpr std::size_t kMaxFields = 17, kPad = 9;
  Rng rng(7, kStimulusStream, 0);
  const fx::Isa chosen = fx::kernel_isa();
  for (const fx::Isa isa : fx::supported_isas()) {
    fx::set_kernel_isa(isa);
    for (std::size_t n = 1; n <= kMaxFields; ++n) {
      for (std::size_t m = 0; m <= fx::kBlock; ++m) {
        const std::string at =
            fmt::format("{} fields, {} transactions, {}", n, m, fx::isa_name(isa));
        std::vector<std::int64_t> src(kPad + n * m + kPad);
        for (auto& x : src) x = static_cast<std::int64_t>(rng.next());
        alignas(64) std::int64_t soa[kMaxFields + 1][fx::kBlock];
        std::fill(&soa[0][0], &soa[0][0] + (kMaxFields + 1) * fx::kBlock, kGuard);
        fx::to_fields(src.data() + kPad, n, m, soa);
        for (std::size_t f = 0; f <= kMaxFields; ++f) {
          for (std::size_t k = 0; k < fx::kBlock; ++k) {
            const std::int64_t want = f < n && k < m ? src[kPad + k * n + f] : kGuard;
            ASSERT_EQ(soa[f][k], want) << at << ": to_fields, field " << f << ", row " << k;
          }
        }
        std::vector<std::int64_t> dst(src.size(), kGuard);
        fx::from_fields(soa, n, m, dst.data() + kPad);
        for (std::size_t i = 0; i < dst.size(); ++i) {
          const bool inside = i >= kPad && i < kPad + n * m;
          ASSERT_EQ(dst[i], inside ? src[i] : kGuard) << at << ": from_fields, value " << i;
        }
      }
    }
  }
  fx::set_kernel_isa(chosen);
}

TEST(KernelIsa, TheWidestSupportedByDefaultAndOnlySupportedOnesChosen) {
  const std::vector<fx::Isa> isas = fx::supported_isas();
  ASSERT_FALSE(isas.empty());
  EXPECT_EQ(isas.front(), fx::Isa::baseline);
  if (std::getenv("PHONGSIM_ISA") == nullptr) {
    EXPECT_EQ(fx::kernel_isa(), isas.back());
  }
  const fx::Isa chosen = fx::kernel_isa();
  for (const fx::Isa isa : {fx::Isa::baseline, fx::Isa::avx2, fx::Isa::avx512}) {
    if (std::find(isas.begin(), isas.end(), isa) == isas.end()) {
      EXPECT_THROW(fx::set_kernel_isa(isa), Error) << fx::isa_name(isa);
      EXPECT_EQ(fx::kernel_isa(), chosen);
    }
  }
}

std::string Name(const ::testing::TestParamInfo<Item>& info) {
  return fmt::format("{}_{}", info.param.pipeline->name, info.param.config.stem().string());
}

INSTANTIATE_TEST_SUITE_P(Configs, PlanTest, ::testing::ValuesIn(ConfigItems()), Name);

}  // namespace
}  // namespace phongsim
