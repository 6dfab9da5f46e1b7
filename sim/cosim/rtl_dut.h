// The RTL side of a pipeline as the harness drives it: a Verilated valid/ready stream design
// behind an interface, so one harness serves every pipeline. Each Verilated configuration is
// built as a plugin (a shared module) that exports phongsim_rtl_create(); rtl_plugin.h builds and
// loads plugins and sim/cosim/verilated_dut.h implements this interface inside them.
//
// Per-cycle protocol the harness follows (inputs change away from the sampling edge):
//   set_input / set_in_valid / set_out_ready  (clock low)
//   settle()                                  combinational logic sees the new inputs
//   in_ready() / out_valid() / output()       sample the handshake of this cycle
//   clock()                                   rising edge, then clock low again
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "model/pipeline.h"

namespace phongsim {

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
};

// Bumped whenever RtlDut or the plugin entry points change; a plugin built against another
// version is refused (and rebuilt when it lives in the cache).
inline constexpr int kRtlPluginAbi = 2;

// Plugin entry points (extern "C" so dlsym finds them by name).
using RtlCreateFn = std::unique_ptr<RtlDut> (*)(const std::vector<Field>& inputs,
                                                const std::vector<Field>& outputs);
// What the plugin was built from (sim/cosim/rtl_plugin.cpp writes it): lines "key K",
// "top T", "gflags G", "port ...", "file HASH PATH".
using RtlInfoFn = const char* (*)();
using RtlAbiFn = int (*)();

}  // namespace phongsim
