#include "sim/cosim/bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "base/error.h"
#include "sim/cosim/harness.h"

namespace phongsim {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

BenchRate rate(std::uint64_t vectors, std::uint64_t outputs, double seconds) {
  return {static_cast<double>(vectors) / seconds, static_cast<double>(outputs) / seconds, 0};
}

// The vectors a chunk at a time (outputs of a chunk discarded before the next: a quad bench
// would otherwise hold gigabytes of pixels).
constexpr std::size_t kChunk = 1024;

template <class Eval>
std::uint64_t run_chunks(std::span<const std::int64_t> inputs, std::size_t n_in, Eval&& eval,
                         std::vector<std::int64_t>& out) {
  std::uint64_t outputs = 0;
  for (std::size_t at = 0; at < inputs.size(); at += kChunk * n_in) {
    out.clear();
    outputs += eval(inputs.subspan(at, std::min(kChunk * n_in, inputs.size() - at)), out);
  }
  return outputs;
}

}  // namespace

BenchReport bench(const CosimSubject& subject, std::uint64_t vectors, const NativeKernel& native,
                  unsigned jobs) {
  BenchReport r;
  r.vectors = vectors;
  r.jobs = jobs;
  PipelineModel& model = subject.model;
  const Stimulus& stimulus = subject.stimulus;
  const std::size_t n_in = model.inputs().size();
  std::vector<std::int64_t> inputs(vectors * n_in);
  for (std::uint64_t i = 0; i < vectors; ++i) {
    stimulus.vector(1, stimulus.directed_count() + i, std::span(inputs).subspan(i * n_in, n_in));
  }
  std::vector<std::int64_t> out;
  out.reserve(1 << 20);

  if (native) {  // bit-identical to the model on these vectors, chunk by chunk (not timed)
    std::vector<std::int64_t> want;
    model.reset();
    for (std::size_t at = 0; at < inputs.size(); at += kChunk * n_in) {
      const auto chunk = std::span(inputs).subspan(at, std::min(kChunk * n_in, inputs.size() - at));
      want.clear();
      out.clear();
      (void)model.eval_batch(chunk, want);
      (void)native(chunk, out);
      if (out != want) {
        throw Error(fmt::format(
            "bench: the native kernel differs from the model on vectors {}..{} (seed 1)",
            stimulus.directed_count() + at / n_in,
            stimulus.directed_count() + (at + chunk.size()) / n_in - 1));
      }
    }
    r.native_note =
        fmt::format("native kernel bit-identical to the model on all {} vectors", vectors);
  }
  {
    model.reset();
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t outputs = run_chunks(
        inputs, n_in, [&](auto in, auto& o) { return model.eval_batch(in, o); }, out);
    r.model = rate(vectors, outputs, seconds_since(start));
  }
  if (native) {
    const auto start = std::chrono::steady_clock::now();
    const std::uint64_t outputs = run_chunks(inputs, n_in, native, out);
    r.native = rate(vectors, outputs, seconds_since(start));
  }
  {
    DutPtr dut = subject.make_dut();
    const auto start = std::chrono::steady_clock::now();
    const HarnessResult h = stream_vectors(*dut, n_in, model.outputs().size(), inputs,
                                           [](std::span<const std::int64_t>) {});
    const double s = seconds_since(start);
    r.rtl = rate(h.inputs, h.outputs, s);
    r.rtl.cycles_per_s = static_cast<double>(h.cycles) / s;
  }
  {
    DutPtr dut = subject.make_dut();
    dut->bare_load(inputs, n_in);
    const auto start = std::chrono::steady_clock::now();
    const BareStats b = dut->bare_run();
    const double s = seconds_since(start);
    r.bare_rtl = rate(b.inputs, b.outputs, s);
    r.bare_rtl.cycles_per_s = static_cast<double>(b.cycles) / s;
  }
  for (const unsigned j : {1U, jobs}) {
    if (j == 1 && r.cosim.outputs_per_s > 0) continue;
    CosimOptions o;
    o.directed = false;
    o.random_vectors = vectors;
    o.measure_vectors = 0;
    o.jobs = j;
    const auto start = std::chrono::steady_clock::now();
    const CosimReport c = cosim(subject, o);
    (j == 1 ? r.cosim : r.cosim_jobs) = rate(c.vectors, c.outputs, seconds_since(start));
  }
  return r;
}

std::string BenchReport::table() const {
  const auto row = [](std::string_view what, const BenchRate& b, std::string_view extra = "") {
    return fmt::format("  {:<22} {:>12.0f} {:>12.0f}{}\n", what, b.vectors_per_s, b.outputs_per_s,
                       extra);
  };
  std::string s = fmt::format("  {:<22} {:>12} {:>12}\n", "per second", "vectors", "outputs");
  s += row("model", model);
  if (native) s += row("native kernel", *native);
  s += row("Verilated RTL", rtl, fmt::format("   ({:.0f} cycles/s)", rtl.cycles_per_s));
  s += row("bare Verilator loop", bare_rtl,
           fmt::format("   ({:.0f} cycles/s)", bare_rtl.cycles_per_s));
  s += row("co-simulation", cosim);
  if (jobs > 1) s += row(fmt::format("co-simulation, {} jobs", jobs), cosim_jobs);
  const auto ratio = [](std::string_view what, double x) {
    return fmt::format("  {:<22} {:>25.2f}x\n", what, x);
  };
  if (native) s += ratio("model / native", model.outputs_per_s / native->outputs_per_s);
  s += ratio("model / RTL", model.outputs_per_s / rtl.outputs_per_s);
  s += ratio("RTL / bare loop", rtl.cycles_per_s / bare_rtl.cycles_per_s);
  s += ratio("co-sim / RTL", cosim.outputs_per_s / rtl.outputs_per_s);
  if (jobs > 1) {
    s +=
        ratio(fmt::format("{} jobs / 1 job", jobs), cosim_jobs.outputs_per_s / cosim.outputs_per_s);
  }
  if (!native_note.empty()) s += "  " + native_note + "\n";
  return s;
}

}  // namespace phongsim
