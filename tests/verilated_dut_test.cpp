// Verilated DUTs that live side by side on one thread: Verilator reports $error to, and tears a
// model's scopes down through, the thread's current context (the last one constructed on the
// thread), so VerilatedDut makes it its own at each entry point (sim/cosim/verilated_dut.h).
// Without that, an older DUT's assertion went to a newer DUT's context (missed: a false PASS),
// and destroying an older DUT after a newer one could hang on the newer one's freed mutex.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "base/paths.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

TEST(VerilatedDut, AnAssertionReachesItsOwnDutWhileAnotherLives) {
  const PipelineInfo& p = find_pipeline("lyon");
  const Config cfg = Config::load(data_root() / "configs" / "lyon" / "default.toml");
  const auto model = make_model(p, cfg);
  const auto library =
      RtlLibrary::open(locate_rtl(rtl_design(p, cfg), *model, RtlBuild::if_missing, stderr));
  DutPtr older = library->create(*model);
  DutPtr newer = library->create(*model);  // the thread's current context from here
  older->reset();
  // The sink stalls until the input stalls too; then the source withdraws its offer, which
  // lyon_core's input stream_check reports ($error "valid dropped while stalled").
  older->set_input(std::vector<std::int64_t>(model->inputs().size(), 0));
  older->set_out_ready(false);
  older->set_in_valid(true);
  bool stalled = false;
  for (int c = 0; c < 1000 && !stalled; ++c) {
    older->settle();
    stalled = !older->in_ready();
    older->clock();
  }
  ASSERT_TRUE(stalled) << "the input never stalled";
  EXPECT_FALSE(older->assertion_failed());
  older->set_in_valid(false);
  older->settle();
  older->clock();
  EXPECT_TRUE(older->assertion_failed()) << "the older DUT's $error was not seen";
  EXPECT_FALSE(newer->assertion_failed()) << "the older DUT's $error reached the newer one";
  // Destroyed newest first: the older one's teardown must not use the newer one's context.
  newer.reset();
  older.reset();
}

}  // namespace
}  // namespace phongsim
