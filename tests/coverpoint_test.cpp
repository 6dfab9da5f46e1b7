// Functional coverpoints (docs/verification.md): every built-in configuration's co-simulation
// stimulus — its directed vectors and the default number of random ones from seed 1, what
// `phongsim cosim --config C` runs — hits every coverpoint its registry entry declares, on the
// model alone. A failure names the configuration and the points never hit.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

#include "base/error.h"
#include "sim/cosim/coverpoints.h"
#include "sim/pipelines/registry.h"
#include "tests/config_items.h"

namespace phongsim {
namespace {

class Coverpoint : public ::testing::TestWithParam<Item> {};

TEST_P(Coverpoint, StimulusHitsEveryPoint) {
  const Item& it = GetParam();
  const Config cfg = Config::load(it.config);
  const auto model = make_model(*it.pipeline, cfg);
  const Stimulus stimulus = it.pipeline->make_stimulus(*model, cfg);
  CoverpointSampler c = it.pipeline->coverpoints(*model, cfg);
  ASSERT_GT(c.points.size(), 0U);
  count_coverpoints(c, *model, stimulus, 1, true, it.pipeline->default_vectors, std::nullopt);
  for (const std::string& w : c.points.waivers()) std::cout << "waived " << w << "\n";
  EXPECT_EQ(c.points.hit_points(), c.points.size())
      << it.config.string()
      << " seed 1: never hit: " << fmt::format("{}", fmt::join(c.points.holes(), ", "));
}

INSTANTIATE_TEST_SUITE_P(Configs, Coverpoint, ::testing::ValuesIn(ConfigItems()),
                         [](const ::testing::TestParamInfo<Item>& info) {
                           std::string name(info.param.pipeline->name);
                           name += "_" + info.param.config.stem().string();
                           return name;
                         });

// The mechanism: sides, merge by name, the file round trip, holes in order, and a malformed file.
TEST(Coverpoints, CountMergeAndFile) {
  const fx::Format s3{true, 3, 2}, s1{true, 1, 2}, u1{false, 1, 2};
  Coverpoints a;
  const auto p = a.declare_sides("p", s3, s1, fx::Round::half_even);
  const std::size_t z = a.declare("zero.set");
  a.hit_side(p, 1);
  a.hit_side(p, 1);
  a.hit(z);
  EXPECT_EQ(a.names(), (std::vector<std::string>{"p.low", "p.inside", "p.high", "zero.set"}));
  EXPECT_EQ(a.counts(), (std::vector<std::uint64_t>{0, 0, 2, 1}));
  EXPECT_EQ(a.holes(), (std::vector<std::string>{"p.low", "p.inside"}));
  EXPECT_THROW(a.declare("p.low"), Error);
  // Only the outcomes a value can reach: unsigned never saturates low, a fitting format never.
  Coverpoints b;
  const auto u = b.declare_sides("u", u1, s3, fx::Round::truncate);
  EXPECT_EQ(b.names(), (std::vector<std::string>{"u.inside"}));
  EXPECT_THROW(b.hit_side(u, 1), Error);
  b.hit_side(b.declare_sides("q", s3, u1, fx::Round::half_up), -1);
  b.hit(0);
  a.merge(b);
  EXPECT_EQ(a.size(), 8U);
  EXPECT_EQ(a.hit_points(), 4U);
  const auto file = std::filesystem::temp_directory_path() / "phongsim-coverpoint-test.txt";
  a.prefixed("x/y:").write(file);
  const Coverpoints r = Coverpoints::read(file);
  EXPECT_EQ(r.names().front(), "x/y:p.low");
  EXPECT_EQ(r.counts(), a.counts());
  std::FILE* f = std::fopen(file.c_str(), "w");
  std::fputs("3 ok\nnot a count\n", f);
  std::fclose(f);
  EXPECT_THROW((void)Coverpoints::read(file), Error);
  std::filesystem::remove(file);
  EXPECT_EQ(Coverpoints::read(file).size(), 0U);  // none yet
}

}  // namespace
}  // namespace phongsim
