// Randomized power-up (`--x-init random --x-seed N`): the seed really sets the state the RTL
// starts in. For every pipeline's default configuration, the XInit::random plugin (built into
// the build's cache on first use) is made with several seeds and its outputs read before any
// reset: two seeds give different values, the same seed the same values, and the default (zero)
// plugin gives zeros. That the co-simulation still passes from such a state, after reset, is the
// xinit ctests' part (tests/CMakeLists.txt). Without a reset, rst_ni itself powers up at a drawn
// value, so an RTL assertion may fire here (lirp_unit's, when it draws 1 for rst_ni and a stall);
// it prints an %Error and is not this test's concern.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "base/paths.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

// Every output port's bits and the handshake outputs of a fresh DUT, inputs idle, no reset.
std::vector<std::int64_t> power_up_state(RtlLibrary& library, const PipelineModel& model,
                                         std::uint32_t seed) {
  auto dut = library.create(model, seed);
  dut->set_in_valid(false);
  dut->set_out_ready(false);
  dut->settle();
  std::vector<std::int64_t> state(model.outputs().size());
  dut->output(state);
  state.push_back(dut->out_valid() ? 1 : 0);
  state.push_back(dut->in_ready() ? 1 : 0);
  return state;
}

class PowerUp : public ::testing::TestWithParam<const PipelineInfo*> {};

TEST_P(PowerUp, TheSeedSetsThePowerUpState) {
  const PipelineInfo& p = *GetParam();
  const Config cfg = Config::load(data_root() / "configs" / p.name / "default.toml");
  const auto model = make_model(p, cfg);
  RtlDesign design = rtl_design(p, cfg);
  design.x_init = XInit::random;
  const auto random = RtlLibrary::open(locate_rtl(design, *model, RtlBuild::if_missing, stderr));
  ASSERT_TRUE(random->x_random());
  const auto one = power_up_state(*random, *model, 1);
  EXPECT_EQ(one, power_up_state(*random, *model, 1)) << "the same seed, another state";
  EXPECT_NE(one, power_up_state(*random, *model, 2)) << "seeds 1 and 2, the same state";
  EXPECT_NE(one, power_up_state(*random, *model, 1234567)) << "seeds 1 and 1234567";

  design.x_init = XInit::zero;
  const auto zero = RtlLibrary::open(locate_rtl(design, *model, RtlBuild::if_missing, stderr));
  EXPECT_FALSE(zero->x_random());
  auto zeros = power_up_state(*zero, *model, 1);
  EXPECT_EQ(zeros, power_up_state(*zero, *model, 2)) << "the zero plugin ignores the seed";
  zeros.pop_back();  // in_ready_o: combinational, 1 while nothing is valid
  EXPECT_EQ(zeros, std::vector<std::int64_t>(zeros.size(), 0)) << "the zero plugin";
}

std::vector<const PipelineInfo*> All() {
  std::vector<const PipelineInfo*> all;
  for (const PipelineInfo& p : pipelines()) all.push_back(&p);
  return all;
}

INSTANTIATE_TEST_SUITE_P(Default, PowerUp, ::testing::ValuesIn(All()),
                         [](const auto& info) { return std::string(info.param->name); });

}  // namespace
}  // namespace phongsim
