// RtlDut for a Verilated top with the project's stream port convention (clk_i, rst_ni,
// in_valid_i, in_ready_o, out_valid_o, out_ready_i). Included only by the plugin adapters that
// sim/cosim/rtl_plugin.cpp generates from a design's port binding, which say which data port
// carries which model field:
//
//   PHONGSIM_RTL_PLUGIN(Vlirp_unit, [](Vlirp_unit& top, phongsim::PortMap& map) {
//     map.input(top.in_p0_i, {"p0_x", "p0_y", "p0_z"});  // packed from the LSB up
//     ...
//   })
#pragma once

#include <verilated.h>
#include <verilated_fst_c.h>

#include <fmt/format.h>

#include <functional>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "model/fixed.h"
#include "sim/cosim/rtl_dut.h"

namespace phongsim {

namespace detail {

// Bit slices of a Verilated port, whatever C++ type Verilator chose for its width
// (CData/SData/IData/QData up to 64 bits, VlWide above).
template <class T>
void write_bits(T& port, int lsb, int width, std::uint64_t value) {
  if constexpr (std::is_integral_v<T>) {
    const std::uint64_t mask = (width == 64 ? ~0ULL : (1ULL << width) - 1) << lsb;
    port = static_cast<T>((static_cast<std::uint64_t>(port) & ~mask) | ((value << lsb) & mask));
  } else {
    for (int b = 0; b < width; ++b) {
      const int bit = lsb + b;
      const EData word_mask = EData{1} << (bit % 32);
      if (((value >> b) & 1U) != 0) {
        port[bit / 32] |= word_mask;
      } else {
        port[bit / 32] &= ~word_mask;
      }
    }
  }
}

template <class T>
std::uint64_t read_bits(const T& port, int lsb, int width) {
  if constexpr (std::is_integral_v<T>) {
    const std::uint64_t v = static_cast<std::uint64_t>(port) >> lsb;
    return width == 64 ? v : v & ((1ULL << width) - 1);
  } else {
    std::uint64_t v = 0;
    for (int b = 0; b < width; ++b) {
      const int bit = lsb + b;
      v |= static_cast<std::uint64_t>((port[bit / 32] >> (bit % 32)) & 1U) << b;
    }
    return v;
  }
}

template <class T>
constexpr int port_capacity() {
  if constexpr (std::is_integral_v<T>) {
    return static_cast<int>(8 * sizeof(T));
  } else {
    return 32 * static_cast<int>(sizeof(T) / sizeof(EData));
  }
}

}  // namespace detail

// Which bits of which port carry each model field. Built once per DUT by the plugin's binder.
class PortMap {
 public:
  PortMap(const std::vector<Field>& inputs, const std::vector<Field>& outputs)
      : in_fields_(inputs),
        out_fields_(outputs),
        writers_(inputs.size()),
        readers_(outputs.size()) {}

  // Fields `names` packed into `port` from bit 0 up, each as wide as its format.
  template <class T>
  void input(T& port, std::initializer_list<std::string_view> names) {
    int lsb = 0;
    for (const auto name : names) {
      const std::size_t i = index_of(in_fields_, name);
      const int width = in_fields_[i].fmt.width();
      check_fits(name, lsb + width, detail::port_capacity<T>());
      writers_[i] = [&port, lsb, width](std::uint64_t bits) {
        detail::write_bits(port, lsb, width, bits);
      };
      lsb += width;
    }
  }

  template <class T>
  void output(const T& port, std::initializer_list<std::string_view> names) {
    int lsb = 0;
    for (const auto name : names) {
      const std::size_t i = index_of(out_fields_, name);
      const int width = out_fields_[i].fmt.width();
      check_fits(name, lsb + width, detail::port_capacity<T>());
      readers_[i] = [&port, lsb, width]() { return detail::read_bits(port, lsb, width); };
      lsb += width;
    }
  }

  // Every field must be bound exactly once.
  void check_complete() const {
    for (std::size_t i = 0; i < writers_.size(); ++i) {
      if (!writers_[i])
        throw std::runtime_error("RTL adapter binds no port to input field " + in_fields_[i].name);
    }
    for (std::size_t i = 0; i < readers_.size(); ++i) {
      if (!readers_[i])
        throw std::runtime_error("RTL adapter binds no port to output field " +
                                 out_fields_[i].name);
    }
  }

  void write(std::span<const std::int64_t> fields) const {
    for (std::size_t i = 0; i < writers_.size(); ++i) {
      writers_[i](fx::to_bits(fields[i], in_fields_[i].fmt));
    }
  }

  void read(std::span<std::int64_t> fields) const {
    for (std::size_t i = 0; i < readers_.size(); ++i) {
      fields[i] = fx::from_bits(readers_[i](), out_fields_[i].fmt);
    }
  }

 private:
  static std::size_t index_of(const std::vector<Field>& fields, std::string_view name) {
    for (std::size_t i = 0; i < fields.size(); ++i) {
      if (fields[i].name == name) return i;
    }
    throw std::runtime_error(fmt::format("RTL adapter names unknown field '{}'", name));
  }
  static void check_fits(std::string_view name, int msb_plus_one, int capacity) {
    if (msb_plus_one > capacity) {
      throw std::runtime_error(fmt::format(
          "RTL adapter: field '{}' ends at bit {} but its port has only {} bits; the plugin was "
          "built for other widths",
          name, msb_plus_one, capacity));
    }
  }

  std::vector<Field> in_fields_;
  std::vector<Field> out_fields_;
  std::vector<std::function<void(std::uint64_t)>> writers_;
  std::vector<std::function<std::uint64_t()>> readers_;
};

template <class Top>
class VerilatedDut final : public RtlDut {
 public:
  using Binder = void (*)(Top&, PortMap&);

  VerilatedDut(const std::vector<Field>& inputs, const std::vector<Field>& outputs, Binder bind)
      : context_(std::make_unique<VerilatedContext>()), map_(inputs, outputs) {
    context_->traceEverOn(true);
    context_->fatalOnError(false);
    top_ = std::make_unique<Top>(context_.get(), "top");
    bind(*top_, map_);
    map_.check_complete();
  }

  ~VerilatedDut() override {
    close_trace();
    top_->final();
  }

  void reset() override {
    top_->clk_i = 0;
    top_->in_valid_i = 0;
    top_->out_ready_i = 0;
    top_->rst_ni = 0;
    top_->eval();
    for (int i = 0; i < 4; ++i) edge();
    top_->rst_ni = 1;
    top_->eval();
    cycle_ = 0;
  }

  void set_input(std::span<const std::int64_t> fields) override { map_.write(fields); }
  void set_in_valid(bool valid) override { top_->in_valid_i = valid ? 1 : 0; }
  void set_out_ready(bool ready) override { top_->out_ready_i = ready ? 1 : 0; }

  void settle() override {
    top_->eval();
    dump(2 * cycle_);
  }

  [[nodiscard]] bool in_ready() const override { return top_->in_ready_o != 0; }
  [[nodiscard]] bool out_valid() const override { return top_->out_valid_o != 0; }
  void output(std::span<std::int64_t> fields) const override { map_.read(fields); }

  void clock() override {
    top_->clk_i = 1;
    top_->eval();
    dump(2 * cycle_ + 1);
    top_->clk_i = 0;
    ++cycle_;
  }

  [[nodiscard]] std::uint64_t cycle() const override { return cycle_; }
  [[nodiscard]] bool assertion_failed() const override { return context_->gotError(); }

  void open_trace(const std::string& path) override {
    close_trace();
    trace_ = std::make_unique<VerilatedFstC>();
    top_->trace(trace_.get(), 99);
    trace_->open(path.c_str());
    if (!trace_->isOpen()) throw std::runtime_error("cannot write waveform " + path);
  }

  void close_trace() override {
    if (trace_) {
      trace_->close();
      trace_.reset();
    }
  }

 private:
  void edge() {
    top_->clk_i = 1;
    top_->eval();
    top_->clk_i = 0;
    top_->eval();
  }
  void dump(std::uint64_t time) {
    if (trace_) trace_->dump(time);
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
  PortMap map_;
  std::unique_ptr<VerilatedFstC> trace_;
  std::uint64_t cycle_ = 0;
};

}  // namespace phongsim

// Exports the plugin entry points for a Verilated top and its port binder. PHONGSIM_RTL_INFO is
// defined by the generated adapter (sim/cosim/rtl_plugin.cpp): what the plugin was built from.
#define PHONGSIM_RTL_PLUGIN(TOP, BINDER)                                              \
  extern "C" __attribute__((visibility("default"))) std::unique_ptr<phongsim::RtlDut> \
  phongsim_rtl_create(const std::vector<phongsim::Field>& inputs,                     \
                      const std::vector<phongsim::Field>& outputs) {                  \
    return std::make_unique<phongsim::VerilatedDut<TOP>>(inputs, outputs, BINDER);    \
  }                                                                                   \
  extern "C" __attribute__((visibility("default"))) const char* phongsim_rtl_info() { \
    return PHONGSIM_RTL_INFO;                                                         \
  }                                                                                   \
  extern "C" __attribute__((visibility("default"))) int phongsim_rtl_abi() {          \
    return phongsim::kRtlPluginAbi;                                                   \
  }
