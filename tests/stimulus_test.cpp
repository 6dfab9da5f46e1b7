// The random stimulus' building blocks: Rng::fill gives next()'s sequence, and FieldRandom gives
// exactly the values of its definition (field i: below(8) == 0 picks one of the format's
// corner_values() by a second draw, otherwise the second draw is uniform over the range), so a
// failing vector still regenerates from (configuration, seed, vector index); its batch and
// Stimulus::vectors give what one vector at a time gives.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "base/rng.h"
#include "model/plan.h"
#include "sim/cosim/stimulus.h"
#include "tests/fixed_helpers.h"

namespace phongsim {
namespace {

using testing::S;
using testing::U;

TEST(RngTest, FillIsTheSequenceOfNext) {
  for (const std::size_t n : {0, 1, 2, 7, 14, 96}) {
    Rng a(5, kStimulusStream, n), b(5, kStimulusStream, n);
    std::vector<std::uint64_t> z(n);
    a.fill(z);
    for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(z[k], b.next()) << "output " << k << " of " << n;
    EXPECT_EQ(a.next(), b.next()) << "the state after fill(" << n << ")";
    EXPECT_EQ(Rng::scaled(a.next(), 1000), b.below(1000));
  }
}

// Formats from one bit to 63, signed and unsigned: their ranges' spans reach 2^63, which the
// batch's 32-bit-halves product must scale exactly.
const std::vector<fx::Format> kFormats{S(1, 10), U(1, 10), U(4, 4),  S(0, 7),
                                       S(62, 0), U(63, 0), U(0, 63), S(1, 30)};

std::vector<Field> fields_of(const std::vector<fx::Format>& formats) {
  std::vector<Field> fields;
  for (const fx::Format f : formats) fields.push_back({"f", f});
  return fields;
}

TEST(RngTest, ScaledHalvesIsScaled) {
  Rng rng(3, kStimulusStream, 0);
  std::vector<std::uint64_t> ns{1,
                                2,
                                3,
                                7,
                                8,
                                1000,
                                0xffffffffU,
                                0x100000000U,
                                0x100000001U,
                                ~std::uint64_t{0} >> 1,
                                std::uint64_t{1} << 63,
                                ~std::uint64_t{0}};
  for (int k = 0; k < 1000; ++k) ns.push_back(rng.next() >> rng.below(64));  // every magnitude
  for (const std::uint64_t n : ns) {
    for (const std::uint64_t z : {std::uint64_t{0}, std::uint64_t{1}, ~std::uint64_t{0},
                                  std::uint64_t{0xffffffffU}, std::uint64_t{1} << 32}) {
      ASSERT_EQ(Rng::scaled_halves(z, n), Rng::scaled(z, n)) << z << " x " << n;
      if (n < std::uint64_t{1} << 32) {
        ASSERT_EQ(Rng::scaled_narrow(z, n), Rng::scaled(z, n)) << z << " x " << n;
      }
    }
    for (int k = 0; k < 100; ++k) {
      const std::uint64_t z = rng.next();
      ASSERT_EQ(Rng::scaled_halves(z, n), Rng::scaled(z, n)) << z << " x " << n;
      if (n < std::uint64_t{1} << 32) {
        ASSERT_EQ(Rng::scaled_narrow(z, n), Rng::scaled(z, n)) << z << " x " << n;
      }
    }
  }
}

TEST(FieldRandomTest, ValuesFollowTheDefinition) {
  const std::vector<fx::Format>& formats = kFormats;
  const std::vector<Field> fields = fields_of(formats);
  const FieldRandom random(fields);
  std::vector<std::int64_t> got(fields.size());
  std::uint64_t corners = 0, draws = 0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    for (std::uint64_t index = 0; index < 20000; ++index) {
      random(seed, index, got);
      Rng rng(seed, kStimulusStream, index);
      for (std::size_t i = 0; i < formats.size(); ++i) {
        const fx::Format f = formats[i];
        const std::vector<std::int64_t> c = corner_values(f);
        const bool corner = rng.below(8) == 0;
        const std::int64_t want =
            corner ? c[rng.below(c.size())]
                   : f.min_raw() + static_cast<std::int64_t>(rng.below(
                                       static_cast<std::uint64_t>(f.max_raw() - f.min_raw()) + 1));
        ASSERT_EQ(got[i], want) << "seed " << seed << " index " << index << " field " << i;
        corners += corner ? 1 : 0;
        ++draws;
      }
    }
  }
  // 1 in 8 from the corners: 480,000 draws put the fraction within 0.003 of 0.125 (> 6 sigma).
  EXPECT_NEAR(static_cast<double>(corners) / static_cast<double>(draws), 0.125, 0.003);
}

// fill() and fill_rows() on every instruction set this CPU runs: the vectors of one call per
// vector, for counts that end inside a block and start anywhere; with `skip`, of an Rng that drew
// that many first. fill_rows() puts them in the rows it is given (here every other row, in
// reverse order) and writes no others.
TEST(FieldRandomTest, FillIsOneVectorAtATime) {
  const std::vector<Field> fields = fields_of(kFormats);
  const std::size_t n = fields.size();
  const FieldRandom random(fields);
  const fx::Isa chosen = fx::kernel_isa();
  for (const fx::Isa isa : fx::supported_isas()) {
    fx::set_kernel_isa(isa);
    for (const std::uint64_t seed : {1, 7}) {
      for (const auto& [first, count] : {std::pair<std::uint64_t, std::size_t>{0, 0},
                                         {0, 1},
                                         {3, 63},
                                         {100, 64},
                                         {12345, 65},
                                         {~std::uint64_t{0} - 2000, 2000}}) {
        for (const std::uint64_t skip : {0, 1, 3}) {
          std::vector<std::int64_t> got(count * n), want(n), in_rows(2 * count * n, -99);
          random.fill(seed, first, count, got, skip);
          std::vector<std::uint64_t> starts;
          std::vector<std::uint32_t> rows;
          for (std::size_t v = 0; v < count; ++v) {
            starts.push_back(Rng::start(seed, kStimulusStream, first + v));
            rows.push_back(static_cast<std::uint32_t>(2 * (count - 1 - v)));
          }
          random.fill_rows(starts, rows, in_rows, skip);
          for (std::size_t v = 0; v < count; ++v) {
            Rng rng(seed, kStimulusStream, first + v);
            for (std::uint64_t k = 0; k < skip; ++k) (void)rng.next();
            random(rng, want);
            for (std::size_t i = 0; i < n; ++i) {
              ASSERT_EQ(got[v * n + i], want[i])
                  << fx::isa_name(isa) << " seed " << seed << " skip " << skip << " vector "
                  << first + v << " field " << i;
              ASSERT_EQ(in_rows[rows[v] * n + i], want[i]) << "fill_rows, vector " << first + v;
              ASSERT_EQ(in_rows[(rows[v] + 1) * n + i], -99) << "fill_rows wrote a gap";
            }
          }
        }
      }
    }
  }
  fx::set_kernel_isa(chosen);
}

// Stimulus::vectors across the end of the directed vectors, with FieldRandom and with a
// pipeline's own random function.
TEST(StimulusTest, VectorsAreOneVectorAtATime) {
  class Model final : public PipelineModel {
   public:
    explicit Model(std::vector<Field> in) { inputs_ = std::move(in); }
    std::size_t eval(std::span<const std::int64_t>, std::vector<std::int64_t>&) override {
      return 0;
    }
    [[nodiscard]] std::unique_ptr<PipelineModel> clone() const override {
      return std::make_unique<Model>(*this);
    }
  };
  const Model model(fields_of({S(1, 10), U(0, 12), S(20, 3)}));
  const std::vector<std::vector<std::int64_t>> directed{{1, 2, 3}, {-4, 5, 6}, {7, 8, -9}};
  const Stimulus::RandomFn own = [](std::uint64_t seed, std::uint64_t index,
                                    std::span<std::int64_t> in) {
    for (std::size_t i = 0; i < in.size(); ++i) in[i] = static_cast<std::int64_t>(seed + index + i);
  };
  for (const Stimulus& stimulus : {Stimulus(model, directed), Stimulus(model, directed, own)}) {
    for (const auto& [first, count] :
         {std::pair<std::uint64_t, std::size_t>{0, 2}, {1, 100}, {3, 70}, {50, 0}}) {
      std::vector<std::int64_t> got(3 * count), want(3);
      stimulus.vectors(5, first, count, got);
      for (std::size_t v = 0; v < count; ++v) {
        stimulus.vector(5, first + v, want);
        for (std::size_t i = 0; i < 3; ++i) {
          ASSERT_EQ(got[3 * v + i], want[i]) << "vector " << first + v << " field " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace phongsim
