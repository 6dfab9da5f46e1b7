#include "sim/cosim/bench.h"

#include <fmt/format.h>

#include <chrono>

#include "sim/cosim/harness.h"

namespace phongsim {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

BenchReport bench(const CosimSubject& subject, std::uint64_t vectors) {
  BenchReport r;
  r.vectors = vectors;
  PipelineModel& model = subject.model;
  const Stimulus& stimulus = subject.stimulus;
  const std::size_t n_in = model.inputs().size();
  std::vector<std::int64_t> inputs(vectors * n_in);
  for (std::uint64_t i = 0; i < vectors; ++i) {
    stimulus.vector(1, stimulus.directed_count() + i, std::span(inputs).subspan(i * n_in, n_in));
  }

  const auto rate = [](double vectors_done, double outputs_done, double seconds) {
    return BenchRate{vectors_done / seconds, outputs_done / seconds};
  };
  {
    std::vector<std::int64_t> out;
    out.reserve(1 << 16);
    std::uint64_t outputs = 0;
    model.reset();
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t i = 0; i < vectors; ++i) {
      out.clear();
      outputs += model.eval(std::span(inputs).subspan(i * n_in, n_in), out);
    }
    r.model =
        rate(static_cast<double>(vectors), static_cast<double>(outputs), seconds_since(start));
  }
  {
    DutPtr dut = subject.make_dut();
    const auto start = std::chrono::steady_clock::now();
    const HarnessResult h = stream_vectors(*dut, n_in, model.outputs().size(), inputs,
                                           [](std::span<const std::int64_t>) {});
    const double s = seconds_since(start);
    r.rtl = rate(static_cast<double>(h.inputs), static_cast<double>(h.outputs), s);
    r.rtl_cycles_per_s = static_cast<double>(h.cycles) / s;
  }
  {
    CosimOptions o;
    o.directed = false;
    o.random_vectors = vectors;
    o.measure_vectors = 0;
    const auto start = std::chrono::steady_clock::now();
    const CosimReport c = cosim(subject, o);
    r.cosim =
        rate(static_cast<double>(c.vectors), static_cast<double>(c.outputs), seconds_since(start));
  }
  return r;
}

std::string BenchReport::table() const {
  return fmt::format(
      "  {:<16} {:>12} {:>12}\n"
      "  model            {:>12.0f} {:>12.0f}\n"
      "  Verilated RTL    {:>12.0f} {:>12.0f}   ({:.0f} cycles/s)\n"
      "  co-simulation    {:>12.0f} {:>12.0f}\n"
      "  model / RTL      {:>25.2f}x\n"
      "  co-sim / RTL     {:>25.2f}x\n",
      "per second", "vectors", "outputs", model.vectors_per_s, model.outputs_per_s,
      rtl.vectors_per_s, rtl.outputs_per_s, rtl_cycles_per_s, cosim.vectors_per_s,
      cosim.outputs_per_s, model.outputs_per_s / rtl.outputs_per_s,
      cosim.outputs_per_s / rtl.outputs_per_s);
}

}  // namespace phongsim
