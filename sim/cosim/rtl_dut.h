// The RTL side of a pipeline as the harness drives it: a Verilated valid/ready stream design
// behind an interface, so one harness serves every pipeline. Each Verilated configuration is
// built as a plugin (a shared module) that exports phongsim_rtl_create(); rtl_plugin.h builds and
// loads plugins and sim/cosim/verilated_dut.h implements this interface inside them.
//
// Per-cycle protocol (inputs change away from the sampling edge):
//   set_input / set_in_valid / set_out_ready  (clock low)
//   settle()                                  combinational logic sees the new inputs
//   in_ready() / out_valid() / output()       sample the handshake of this cycle
//   clock()                                   rising edge, then clock low again
// The harness does not call these per cycle: it calls run(), which runs the cycle loop of
// sim/cosim/cycle_loop.h over a batch of inputs and stall decisions. The default run() drives
// the per-cycle methods above (a DUT written in C++, as the tests' fakes); the Verilated DUT runs
// the same loop inside the plugin on its top directly, without a virtual call per cycle.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/error.h"
#include "model/pipeline.h"
#include "sim/cosim/cycle_loop.h"

namespace phongsim {

// Thrown by a four-state DUT (Icarus) whose ports show an X or Z where a value is due: on a
// handshake output, or on a data output while it is valid. Not bad input but a wrong design: the
// harness stops the run there and reports it as the run's failure ("unknown value").
class UnknownValue : public Error {
 public:
  using Error::Error;
};

// What the bare loop of run_bare() did.
struct BareStats {
  std::uint64_t cycles = 0;
  std::uint64_t inputs = 0;
  std::uint64_t outputs = 0;
};

class RtlDut {
 public:
  virtual ~RtlDut() = default;

  virtual void reset() = 0;  // holds reset for a few cycles; afterwards cycle() == 0

  virtual void set_input(std::span<const std::int64_t> fields) = 0;  // model inputs() order
  virtual void set_in_valid(bool valid) = 0;
  virtual void set_out_ready(bool ready) = 0;
  virtual void settle() = 0;

  [[nodiscard]] virtual bool in_ready() const = 0;
  [[nodiscard]] virtual bool out_valid() const = 0;
  virtual void output(std::span<std::int64_t> fields) const = 0;  // model outputs() order

  virtual void clock() = 0;
  [[nodiscard]] virtual std::uint64_t cycle() const = 0;

  // True once an RTL assertion ($error) has fired; its message went to stderr.
  [[nodiscard]] virtual bool assertion_failed() const = 0;

  // FST waveform of every cycle between open and close.
  virtual void open_trace(const std::string& path) = 0;
  virtual void close_trace() = 0;

  // Runs the cycle loop (cycle_loop.h) until it needs the harness; state carries over between
  // calls. The caller resets the DUT before the first call.
  virtual void run(CycleBatch& batch, CycleState& state) { run_cycles(*this, batch, state); }

  // The yardstick of `phongsim bench`: resets, then drives `vectors` (model inputs() order, back
  // to back) into the top directly — input valid and output ready every cycle, no checks, no
  // outputs read — until every vector is in and no output has come for kDrainCycles cycles.
  // Packing the vectors into port images happens in bare_load(), outside the timed run. The
  // default drives the per-cycle methods (a C++ DUT has no cheaper way in).
  virtual void bare_load(std::span<const std::int64_t> vectors, std::size_t input_fields) {
    bare_vectors_.assign(vectors.begin(), vectors.end());
    bare_fields_ = input_fields;
  }
  virtual BareStats bare_run() {
    reset();
    BareStats s;
    const std::size_t n = bare_fields_ == 0 ? 0 : bare_vectors_.size() / bare_fields_;
    std::uint64_t quiet = 0;
    while (s.inputs < n || quiet < kDrainCycles) {
      const bool valid = s.inputs < n;
      if (valid) set_input(std::span(bare_vectors_).subspan(s.inputs * bare_fields_, bare_fields_));
      set_in_valid(valid);
      set_out_ready(true);
      settle();
      const bool fire = valid && in_ready();
      const bool out = out_valid();
      clock();
      ++s.cycles;
      s.outputs += out ? 1 : 0;
      s.inputs += fire ? 1 : 0;
      quiet = out || fire ? 0 : quiet + 1;
    }
    return s;
  }

 private:
  std::vector<std::int64_t> bare_vectors_;
  std::size_t bare_fields_ = 0;
};

// Bumped whenever RtlDut or the plugin entry points change; a plugin built against another
// version is refused (and rebuilt when it lives in the cache).
inline constexpr int kRtlPluginAbi = 4;

// Plugin entry points (extern "C" so dlsym finds them by name).
using RtlCreateFn = std::unique_ptr<RtlDut> (*)(const std::vector<Field>& inputs,
                                                const std::vector<Field>& outputs);
// What the plugin was built from (sim/cosim/rtl_plugin.cpp writes it): lines "key K",
// "top T", "gflags G", "port ...", "file HASH PATH".
using RtlInfoFn = const char* (*)();
using RtlAbiFn = int (*)();

}  // namespace phongsim
