// The random stimulus' building blocks: Rng::fill gives next()'s sequence, and FieldRandom gives
// exactly the values of its definition (field i: below(8) == 0 picks one of the format's
// corner_values() by a second draw, otherwise the second draw is uniform over the range), so a
// failing vector still regenerates from (configuration, seed, vector index).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "base/rng.h"
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

TEST(FieldRandomTest, ValuesFollowTheDefinition) {
  const std::vector<fx::Format> formats{S(1, 10), U(1, 10), U(4, 4),  S(0, 7),
                                        S(62, 0), U(63, 0), U(0, 63), S(1, 30)};
  std::vector<Field> fields;
  for (const fx::Format f : formats) fields.push_back({"f", f});
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

}  // namespace
}  // namespace phongsim
