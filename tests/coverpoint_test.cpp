// Functional coverpoints (docs/verification.md): every built-in configuration's co-simulation
// stimulus — its directed vectors and the default number of random ones from seed 1, what
// `phongsim cosim --config C` runs — hits every coverpoint its registry entry declares, on the
// model alone. A failure names the configuration and the points never hit.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/file_util.h"
#include "sim/cosim/coverage.h"
#include "sim/cosim/coverpoints.h"
#include "sim/cosim/stall.h"
#include "sim/pipelines/registry.h"
#include "tests/config_items.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

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
  const testing::TempDir tmp;
  const auto file = tmp.path() / "coverpoints.txt";
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

// The line of the tree's rtl/common/fx_resize.sv holding `text` (its saturation compares are
// found by their code, never by a line number), and a point of it as Verilator keys it: an if
// arm at line `at` with statements S `at`-`at + 1`, in instance `hier`.
int fx_resize_line(const std::string& text) {
  std::istringstream in(
      read_file(std::filesystem::path(PHONGSIM_SOURCE_DIR) / "rtl/common/fx_resize.sv"));
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.find(text) != std::string::npos) return n;
  }
  ADD_FAILURE() << "no line of fx_resize.sv holds " << text;
  return 0;
}

std::string fx_resize_key(int at, const std::string& hier) {  // "\x01" "f": \x01f is one escape
  return fmt::format(
      "\x01page\x02v_line/fx_resize\x01"
      "f\x02{}/rtl/common/fx_resize.sv\x01l\x02{}"
      "\x01S\x02{}-{}\x01h\x02{}",
      PHONGSIM_SOURCE_DIR, at, at, at + 1, hier);
}

// A line waiver leaves out the points it matches (file, the lines its RTL marker marks,
// hierarchy) while they are unreached, and makes a reached one an error naming its reason.
TEST(LineWaivers, LeaveOutUnreachedPointsAndFireWhenReached) {
  const int high = fx_resize_line("if (wide > MaxV)"), low = fx_resize_line("if (wide < MinV)");
  const std::vector<LineWaiver> waivers{
      fx_resize_saturation_waiver(R"(\.u_value\.)", "low", "value.low: never negative")};
  std::map<std::string, std::uint64_t> points{
      {fx_resize_key(low, "top.q.g_channel[0].u_value.u"), 0},
      {fx_resize_key(high, "top.q.g_channel[0].u_value.u"), 4},
      {fx_resize_key(low, "top.q.u_other.u"), 0}};
  const CoverageSummary s = count_coverage_points(points, waivers);
  EXPECT_EQ(s.line_waived, 1U);  // the u_value low arm; not the high one, not another instance
  EXPECT_EQ(s.line_points, 2U);
  EXPECT_EQ(s.line_hit, 1U);
  points[fx_resize_key(low, "top.q.g_channel[0].u_value.u")] = 1;
  const std::string e = testing::ErrorOf([&] { (void)count_coverage_points(points, waivers); });
  EXPECT_NE(e.find("is waived (value.low: never negative) but was reached"), std::string::npos)
      << e;
}

// Lyon's halfway configuration gives H's normalization N's parameters: Verilator makes one module
// of u_norm_n and u_norm_h and counts its lines once, under "u_core.*": such a point is waived
// only where the arm is waived in both (halfway: the g arms), and not in a configuration with one
// normalization.
TEST(LineWaivers, LyonSharedNormalizationPoint) {
  const auto waivers_of = [](const char* config) {
    const Config cfg = Config::load(std::filesystem::path(PHONGSIM_SOURCE_DIR) / config);
    const auto model = make_model(find_pipeline("lyon"), cfg);
    return find_pipeline("lyon").coverpoints(*model, cfg).line_waivers;
  };
  const int high = fx_resize_line("if (wide > MaxV)");
  const std::string shared = "top.lyon_top.u_core.*.g_approximate.u_g.u_resize";
  const std::map<std::string, std::uint64_t> points{{fx_resize_key(high, shared), 0}};
  const auto halfway = waivers_of("configs/lyon/halfway.toml");
  EXPECT_EQ(count_coverage_points(points, halfway).line_waived, 1U);
  EXPECT_EQ(count_coverage_points(points, waivers_of("configs/lyon/default.toml")).line_waived, 0U);
  // One instance's point (not shared) is not waived by the shared waiver alone.
  const std::map<std::string, std::uint64_t> other{
      {fx_resize_key(high, "top.lyon_top.u_core.*.g_approximate.u_q.u_resize"), 0}};
  EXPECT_EQ(count_coverage_points(other, halfway).line_waived, 0U);
}

// A stall-pattern class counts a run only where the pattern acted: an always-active periodic
// source withheld nothing.
TEST(StallClasses, CountOnlyPatternsThatActed) {
  Coverpoints p;
  declare_stall_classes(p);
  stall_class_hit(p, StallPattern::parse("periodic:1"), StallPattern::parse("random:0.5"), 0, 7);
  stall_class_hit(p, StallPattern{}, StallPattern::parse("long:10:20"), 0, 0);
  EXPECT_EQ(p.holes(), (std::vector<std::string>{"stall.source.periodic", "stall.source.random",
                                                 "stall.source.long", "stall.sink.none",
                                                 "stall.sink.periodic", "stall.sink.long"}));
  stall_class_hit(p, StallPattern::parse("periodic:10"), StallPattern{}, 3, 0);
  EXPECT_EQ(p.holes(), (std::vector<std::string>{"stall.source.random", "stall.source.long",
                                                 "stall.sink.periodic", "stall.sink.long"}));
}

}  // namespace
}  // namespace phongsim
