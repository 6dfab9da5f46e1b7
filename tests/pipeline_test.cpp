// Every registry entry against its own RTL, for every built-in configuration: the port binding
// covers the model's fields exactly, the stall-free co-simulation's measured latency and rate are
// the entry's structural latency and rate, and its cycle model counts the RTL's cycles exactly.
// Plugins come from the build's cache (phongsim build-rtl --all runs in the build).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sim/cosim/cosim.h"
#include "sim/cosim/harness.h"
#include "sim/pipelines/registry.h"
#include "tests/config_items.h"

namespace phongsim {
namespace {

class PipelineEntry : public ::testing::TestWithParam<Item> {};

// An entry's configuration, model, stimulus and built-in RTL plugin (from the build's cache).
struct Built {
  explicit Built(const Item& it)
      : cfg(Config::load(it.config)),
        model(make_model(*it.pipeline, cfg)),
        library(RtlLibrary::open(
            locate_rtl(rtl_design(*it.pipeline, cfg), *model, RtlBuild::never, nullptr))),
        stimulus(it.pipeline->make_stimulus(*model, cfg)) {}
  Config cfg;
  std::unique_ptr<PipelineModel> model;
  std::shared_ptr<RtlLibrary> library;
  Stimulus stimulus;
};

TEST_P(PipelineEntry, PortsBindEveryFieldOnce) {
  const Item& it = GetParam();
  const Config cfg = Config::load(it.config);
  const auto model = make_model(*it.pipeline, cfg);
  for (const bool input : {true, false}) {
    const auto& fields = input ? model->inputs() : model->outputs();
    std::vector<std::string> bound;
    for (const PortBinding& b : it.pipeline->ports) {
      if (b.input == input) bound.insert(bound.end(), b.fields.begin(), b.fields.end());
    }
    ASSERT_EQ(bound.size(), fields.size()) << (input ? "inputs" : "outputs");
    for (const Field& f : fields) {
      EXPECT_EQ(std::count(bound.begin(), bound.end(), f.name), 1) << f.name;
    }
  }
}

TEST_P(PipelineEntry, MeasuredLatencyAndRateAreTheEntrys) {
  const Item& it = GetParam();
  const Built b(it);
  const Config& cfg = b.cfg;
  const auto& model = b.model;
  const auto& library = b.library;
  const Stimulus& stimulus = b.stimulus;
  CosimOptions o;
  o.directed = false;
  o.random_vectors = 1;  // a run with no vectors is refused; the measurement run is what counts
  o.measure_vectors = 2000;
  const CosimReport r = cosim({std::string(it.pipeline->name),
                               cfg,
                               *model,
                               stimulus,
                               it.pipeline->independent_vectors,
                               [&]() { return library->create(*model); },
                               {},
                               {},
                               {}},
                              o);
  ASSERT_TRUE(r.passed) << r.failure;
  EXPECT_EQ(r.latency_min, static_cast<std::uint64_t>(it.pipeline->latency(cfg)));
  if (it.pipeline->one_per_clock) {
    EXPECT_EQ(r.throughput, 1.0);
    // Every vector takes the same path (a span program's words wait their turn, so not kb's).
    if (it.pipeline->independent_vectors) {
      EXPECT_EQ(r.latency_max, r.latency_min);
    }
  } else {
    EXPECT_LT(r.throughput, 1.0);
  }
}

// The cycle model against the RTL on the stimulus's vectors (directed first, then random; cut
// where a group of vectors starts, so that kb's spans are whole), for two seeds.
TEST_P(PipelineEntry, CycleModelCountsTheRtlsCycles) {
  const Item& it = GetParam();
  const Built b(it);
  const Config& cfg = b.cfg;
  const auto& model = b.model;
  const auto& library = b.library;
  const Stimulus& stimulus = b.stimulus;
  const std::size_t n_in = model->inputs().size(), n_out = model->outputs().size();
  // Stateful pipelines also get arbitrary words, not only what a setup writes (kb: events on a
  // span's last pixel, events left over after it, a stream ending inside a span).
  const FieldRandom arbitrary(model->inputs());
  for (const std::uint64_t seed : {1, 2, 3}) {
    if (seed == 3 && it.pipeline->independent_vectors) break;
    const std::uint64_t count = seed == 3 ? 300 : stimulus.group_start(3000);
    std::vector<std::int64_t> in(count * n_in), out;
    for (std::uint64_t i = 0; i < count; ++i) {
      const auto v = std::span(in).subspan(i * n_in, n_in);
      if (seed == 3) {
        arbitrary(seed, i, v);
      } else {
        stimulus.vector(seed, i, v);
      }
    }
    std::vector<std::uint32_t> counts;
    model->reset();
    (void)model->eval_batch(in, out, &counts);
    std::vector<FrameCycles> own;
    const FrameCycles c = it.pipeline->cycles(cfg, in, out, counts, &own);
    auto dut = library->create(*model);
    const HarnessResult r = stream_vectors(*dut, n_in, n_out, in, [](auto) {});
    ASSERT_EQ(r.reason, StopReason::finished) << r.message;
    ASSERT_EQ(r.outputs, out.size() / n_out);
    EXPECT_EQ(c.outputs, r.outputs) << "seed " << seed;
    EXPECT_EQ(c.cycles, r.last_output_cycle + 1) << "seed " << seed << ", " << count << " vectors";
    EXPECT_EQ(c.cycles,
              c.fill_cycles + c.outputs + c.setup_cycles + c.empty_row_cycles + c.stall_cycles);
  }
}

std::string Name(const ::testing::TestParamInfo<Item>& info) {
  return std::string(info.param.pipeline->name) + "_" + info.param.config.stem().string();
}

INSTANTIATE_TEST_SUITE_P(Builtin, PipelineEntry, ::testing::ValuesIn(ConfigItems()), Name);

}  // namespace
}  // namespace phongsim
