#include "sim/bench.h"

#include <fmt/format.h>

#include <chrono>

#include "sim/harness.h"

namespace phongsim {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

BenchReport bench(const PipelineInfo& pipeline, const Config& cfg, PipelineModel& model,
                  const DutFactory& make_dut, std::uint64_t vectors) {
  BenchReport r;
  r.vectors = vectors;
  const Stimulus stimulus = pipeline.make_stimulus(model);
  const std::size_t n_in = model.inputs().size();
  std::vector<std::int64_t> inputs(vectors * n_in);
  for (std::uint64_t i = 0; i < vectors; ++i) {
    stimulus.vector(1, stimulus.directed_count() + i, std::span(inputs).subspan(i * n_in, n_in));
  }

  {
    std::vector<std::int64_t> out;
    out.reserve(64);
    model.reset();
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t i = 0; i < vectors; ++i) {
      out.clear();
      model.eval(std::span(inputs).subspan(i * n_in, n_in), out);
    }
    r.model_per_s = static_cast<double>(vectors) / seconds_since(start);
  }
  {
    DutPtr dut = make_dut();
    const auto start = std::chrono::steady_clock::now();
    const HarnessResult h = stream_vectors(*dut, n_in, model.outputs().size(), inputs,
                                           [](std::span<const std::int64_t>) {});
    const double s = seconds_since(start);
    r.rtl_per_s = static_cast<double>(h.inputs) / s;
    r.rtl_cycles_per_s = static_cast<double>(h.cycles) / s;
  }
  {
    CosimOptions o;
    o.directed = false;
    o.random_vectors = vectors;
    o.measure_vectors = 0;
    const auto start = std::chrono::steady_clock::now();
    const CosimReport c = cosim(pipeline, cfg, model, make_dut, o);
    r.cosim_per_s = static_cast<double>(c.vectors) / seconds_since(start);
  }
  return r;
}

std::string BenchReport::table() const {
  return fmt::format(
      "  model            {:>12.0f} vectors/s\n"
      "  Verilated RTL    {:>12.0f} vectors/s  ({:.0f} cycles/s)\n"
      "  co-simulation    {:>12.0f} vectors/s\n"
      "  model / RTL      {:>12.1f}x\n"
      "  co-sim / RTL     {:>12.2f}x\n",
      model_per_s, rtl_per_s, rtl_cycles_per_s, cosim_per_s, model_per_s / rtl_per_s,
      cosim_per_s / rtl_per_s);
}

}  // namespace phongsim
