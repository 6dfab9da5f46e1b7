// RtlDut for a Verilated top with the project's stream port convention (clk_i, rst_ni,
// in_valid_i, in_ready_o, out_valid_o, out_ready_i). Included only by the plugin adapters that
// sim/cosim/rtl_plugin.cpp generates from a design's port binding, which say which data port
// carries which model field:
//
//   PHONGSIM_RTL_PLUGIN(Vlirp_unit, [](Vlirp_unit& top, phongsim::PortMap& map) {
//     map.input(top.in_p0_i, {"p0_x", "p0_y", "p0_z"});  // packed from the LSB up
//     ...
//   })
//
// The cycle loop (cycle_loop.h) runs here, on the top directly: per cycle two eval() calls and a
// few byte stores and loads; a transaction's fields are packed into (or read from) its ports by
// precomputed shifts and masks, one store per port.
#pragma once

#include <verilated.h>
#include <verilated_fst_c.h>

#include <fmt/format.h>

#include <algorithm>
#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string_view>
#include <type_traits>

#include "model/fixed.h"
#include "sim/cosim/rtl_dut.h"

namespace phongsim {

// Which bits of which port carry each model field. Built once per DUT by the plugin's binder.
class PortMap {
 public:
  PortMap(const std::vector<Field>& inputs, const std::vector<Field>& outputs)
      : in_fields_(inputs),
        out_fields_(outputs),
        in_bound_(inputs.size()),
        out_bound_(outputs.size()) {}

  // Fields `names` packed into `port` from bit 0 up, each as wide as its format.
  template <class T>
  void input(T& port, std::initializer_list<std::string_view> names) {
    in_ports_.push_back(bind(port, names, in_fields_, in_bound_));
    image_size_ += in_ports_.back().words == 0 ? 2 : in_ports_.back().words;
  }

  template <class T>
  void output(const T& port, std::initializer_list<std::string_view> names) {
    out_ports_.push_back(bind(const_cast<T&>(port), names, out_fields_, out_bound_));
  }

  // Every field must be bound exactly once.
  void check_complete() const {
    for (std::size_t i = 0; i < in_bound_.size(); ++i) {
      if (!in_bound_[i])
        throw std::runtime_error("RTL adapter binds no port to input field " + in_fields_[i].name);
    }
    for (std::size_t i = 0; i < out_bound_.size(); ++i) {
      if (!out_bound_[i])
        throw std::runtime_error("RTL adapter binds no port to output field " +
                                 out_fields_[i].name);
    }
  }

  // A transaction's input ports as an image of image_size() 32-bit words: two (low, high) for
  // each port up to 64 bits, a wider port's words as Verilator stores them.
  [[nodiscard]] std::size_t image_size() const { return image_size_; }
  void pack(std::span<const std::int64_t> fields, std::uint32_t* image) const {
    for (const Port& p : in_ports_) {
      if (p.words == 0) {
        const std::uint64_t v = narrow_bits(p, fields);
        image[0] = static_cast<std::uint32_t>(v);
        image[1] = static_cast<std::uint32_t>(v >> 32);
        image += 2;
      } else {
        wide_bits(p, fields, image);
        image += p.words;
      }
    }
  }
  // Drives the input ports from an image.
  void load(const std::uint32_t* image) const {
    for (const Port& p : in_ports_) {
      if (p.words != 0) {
        std::copy_n(image, p.words, static_cast<EData*>(p.data));
        image += p.words;
      } else {
        store(p, image[0] | (static_cast<std::uint64_t>(image[1]) << 32));
        image += 2;
      }
    }
  }
  // Drives the input ports from a transaction's fields: pack() and load() in one pass, without
  // the image between them (the harness does this every time it presents an input).
  void write(std::span<const std::int64_t> fields) const {
    for (const Port& p : in_ports_) {
      if (p.words == 0) {
        store(p, narrow_bits(p, fields));
      } else {
        wide_bits(p, fields, static_cast<EData*>(p.data));
      }
    }
  }

  void read(std::span<std::int64_t> fields) const {
    for (const Port& p : out_ports_) {
      if (p.words == 0) {
        std::uint64_t v = 0;
        switch (p.bytes) {
          case 1:
            v = *static_cast<const CData*>(p.data);
            break;
          case 2:
            v = *static_cast<const SData*>(p.data);
            break;
          case 4:
            v = *static_cast<const IData*>(p.data);
            break;
          default:
            v = *static_cast<const QData*>(p.data);
        }
        for (const Slice& s : p.slices) fields[s.field] = extend(v >> s.lsb, s);
      } else {
        const auto* w = static_cast<const EData*>(p.data);
        for (const Slice& s : p.slices) {
          unsigned __int128 x = 0;
          for (int k = 0; k < 3 && s.lsb / 32 + k < p.words; ++k) {
            x |= static_cast<unsigned __int128>(w[s.lsb / 32 + k]) << (32 * k);
          }
          fields[s.field] = extend(static_cast<std::uint64_t>(x >> (s.lsb % 32)), s);
        }
      }
    }
  }

 private:
  struct Slice {
    std::size_t field = 0;
    int lsb = 0;
    std::uint64_t mask = 0;  // the field's width of low bits
    std::uint64_t sign = 0;  // its sign bit when signed (fx::from_bits)
  };
  struct Port {
    void* data = nullptr;
    int bytes = 0;  // 1, 2, 4 or 8; 0: words 32-bit words (VlWide)
    int words = 0;
    std::vector<Slice> slices;
  };

  // A port of up to 64 bits: its value from the fields; stored as the port's type.
  static std::uint64_t narrow_bits(const Port& p, std::span<const std::int64_t> fields) {
    std::uint64_t v = 0;
    for (const Slice& s : p.slices) {
      v |= (static_cast<std::uint64_t>(fields[s.field]) & s.mask) << s.lsb;
    }
    return v;
  }
  static void store(const Port& p, std::uint64_t v) {
    switch (p.bytes) {
      case 1:
        *static_cast<CData*>(p.data) = static_cast<CData>(v);
        break;
      case 2:
        *static_cast<SData*>(p.data) = static_cast<SData>(v);
        break;
      case 4:
        *static_cast<IData*>(p.data) = static_cast<IData>(v);
        break;
      default:
        *static_cast<QData*>(p.data) = v;
    }
  }
  // A wider port's words (as Verilator stores them) from the fields.
  static void wide_bits(const Port& p, std::span<const std::int64_t> fields, std::uint32_t* w) {
    std::fill(w, w + p.words, 0U);
    for (const Slice& s : p.slices) {
      const auto x =
          static_cast<unsigned __int128>(static_cast<std::uint64_t>(fields[s.field]) & s.mask)
          << (s.lsb % 32);
      for (int k = 0; k < 3 && s.lsb / 32 + k < p.words; ++k) {
        w[s.lsb / 32 + k] |= static_cast<std::uint32_t>(x >> (32 * k));
      }
    }
  }

  static std::int64_t extend(std::uint64_t bits, const Slice& s) {
    return static_cast<std::int64_t>(((bits & s.mask) ^ s.sign) - s.sign);
  }

  template <class T>
  Port bind(T& port, std::initializer_list<std::string_view> names,
            const std::vector<Field>& fields, std::vector<bool>& bound) {
    Port p;
    int capacity = 0;
    if constexpr (std::is_integral_v<T>) {
      p.data = &port;
      p.bytes = static_cast<int>(sizeof(T));
      capacity = 8 * p.bytes;
    } else {
      p.data = port.data();
      p.words = static_cast<int>(sizeof(T) / sizeof(EData));
      capacity = 32 * p.words;
    }
    int lsb = 0;
    for (const auto name : names) {
      const std::size_t i = index_of(fields, name);
      const fx::Format f = fields[i].fmt;
      const int width = f.width();
      check_fits(name, lsb + width, capacity);
      p.slices.push_back({i, lsb, (std::uint64_t{1} << width) - 1,
                          f.is_signed ? std::uint64_t{1} << (width - 1) : 0});
      bound[i] = true;
      lsb += width;
    }
    return p;
  }

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
  std::vector<bool> in_bound_;
  std::vector<bool> out_bound_;
  std::vector<Port> in_ports_;
  std::vector<Port> out_ports_;
  std::size_t image_size_ = 0;
};

template <class Top>
class VerilatedDut final : public RtlDut {
 public:
  using Binder = void (*)(Top&, PortMap&);

  VerilatedDut(const std::vector<Field>& inputs, const std::vector<Field>& outputs, Binder bind)
      : context_(std::make_unique<VerilatedContext>()), map_(inputs, outputs) {
    context_->traceEverOn(true);
    context_->fatalOnError(false);
#ifdef PHONGSIM_VERILATED_THREADS  // set by phongsim's plugin builds (cmake/PhongsimRtl.cmake)
    context_->threads(PHONGSIM_VERILATED_THREADS);
#endif
    top_ = std::make_unique<Top>(context_.get(), "top");
    bind(*top_, map_);
    map_.check_complete();
  }

  ~VerilatedDut() override {
    own_thread_context();
    close_trace();
    top_->final();
  }

  void reset() override {
    own_thread_context();
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
    if (trace_) trace_->dump(2 * cycle_);
  }

  [[nodiscard]] bool in_ready() const override { return top_->in_ready_o != 0; }
  [[nodiscard]] bool out_valid() const override { return top_->out_valid_o != 0; }
  void output(std::span<std::int64_t> fields) const override { map_.read(fields); }

  void clock() override {
    top_->clk_i = 1;
    top_->eval();
    if (trace_) trace_->dump(2 * cycle_ + 1);
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

  // The loop instantiated on this class: every per-cycle call above is direct and inlined.
  void run(CycleBatch& batch, CycleState& state) override {
    own_thread_context();
    run_cycles(*this, batch, state);
  }

  void bare_load(std::span<const std::int64_t> vectors, std::size_t input_fields) override {
    const std::size_t n_in = input_fields;
    bare_count_ = n_in == 0 ? 0 : vectors.size() / n_in;
    images_.assign(bare_count_ * map_.image_size(), 0);
    for (std::size_t i = 0; i < bare_count_; ++i) {
      map_.pack(vectors.subspan(i * n_in, n_in), images_.data() + i * map_.image_size());
    }
  }

  BareStats bare_run() override {
    reset();  // and the thread's context
    BareStats s;
    const std::size_t n = bare_count_;
    const std::size_t size = map_.image_size();
    std::size_t i = 0;
    if (n > 0) map_.load(images_.data());
    top_->in_valid_i = n > 0 ? 1 : 0;
    top_->out_ready_i = 1;
    std::uint64_t quiet = 0;
    while (i < n || quiet < kDrainCycles) {
      top_->eval();
      const bool fire = top_->in_valid_i != 0 && top_->in_ready_o != 0;
      const bool out = top_->out_valid_o != 0;
      top_->clk_i = 1;
      top_->eval();
      top_->clk_i = 0;
      ++s.cycles;
      s.outputs += out ? 1 : 0;
      quiet = out || fire ? 0 : quiet + 1;
      if (fire && ++i < n) map_.load(images_.data() + i * size);
      if (i == n) top_->in_valid_i = 0;
    }
    s.inputs = i;
    return s;
  }

 private:
  // Verilator reports $error and $finish to, and tears a model's scopes down through, the
  // thread's current context: the last one constructed on the thread, which may belong to
  // another DUT, or to one already destroyed (a hang in the teardown, an assertion missed). So
  // each entry point makes it this DUT's.
  void own_thread_context() { Verilated::threadContextp(context_.get()); }

  void edge() {
    top_->clk_i = 1;
    top_->eval();
    top_->clk_i = 0;
    top_->eval();
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
  PortMap map_;
  std::unique_ptr<VerilatedFstC> trace_;
  std::uint64_t cycle_ = 0;
  std::vector<std::uint32_t> images_;
  std::size_t bare_count_ = 0;
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
