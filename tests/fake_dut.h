// Test fixture for the co-simulation framework's tests (harness_faults_test.cpp,
// harness_runs_test.cpp), without Verilator: FakeDut is a correct L-stage valid/ready pipeline
// computing the lirp model, with one injectable fault; the Cosim fixture runs it through
// phongsim::cosim and spells out the reports the framework must produce.
//
// Unless a test says otherwise: seed 7, the 1859 directed vectors plus 2000 random ones, no
// stalls, so vector i is accepted in cycle i and its output is taken in cycle i + L. The
// expected cycles in the tests follow from that.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "model/config.h"
#include "model/fixed.h"
#include "model/lirp.h"
#include "sim/cosim/cosim.h"
#include "sim/cosim/harness.h"
#include "sim/cosim/rtl_dut.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/stall.h"
#include "sim/pipelines/registry.h"

namespace phongsim::testing {

namespace fx = phongsim::fx;
using phongsim::Config;
using phongsim::CosimOptions;
using phongsim::CosimReport;
using phongsim::DutDeleter;
using phongsim::DutPtr;
using phongsim::LirpFormats;
using phongsim::LirpModel;
using phongsim::StallPattern;

inline constexpr const char* kConfigPath = PHONGSIM_SOURCE_DIR "/configs/lirp/default.toml";
inline constexpr std::size_t kLatency = 3;
inline constexpr std::uint64_t kSeed = 7;
inline constexpr std::uint64_t kDirected =
    11 * 13 * 13;  // 11 a corners x 13 x 13 p corners (S1.10)
inline constexpr std::uint64_t kRandom = 2000;
inline constexpr std::uint64_t kVectors = kDirected + kRandom;
inline constexpr std::uint64_t kTimeout = 200;
inline constexpr std::uint64_t kK = 2500;  // victim transaction: a random vector, so its outputs
                                           // are unlike its neighbours' (directed ones repeat)

// ---- the fake RTL ----

enum class Fault {
  none,
  corrupt_lsb,           // flip bit 0 of one output field of #k
  drop,                  // never emit #k
  duplicate,             // emit #k twice
  swap,                  // emit #k+1 before #k
  stall_forever,         // in_ready stays low once #k is accepted
  withdraw_valid,        // the first output after #k held by the sink loses out_valid a cycle
  change_while_stalled,  // ... or has its data changed
  never_ready_output,    // out_valid never asserted for anything after #k
  late_extra,            // once idle for k cycles after its last output, one extra output
};

struct FaultSpec {
  Fault fault = Fault::none;
  std::int64_t k = 0;  // transaction ordinal, in acceptance order from 0; -1 = before the first
  std::vector<std::int64_t> trigger;   // corrupt_lsb: hit the first transaction with these inputs
  std::vector<std::int64_t> trigger2;  // ... or with these
  std::size_t field = 1;               // corrupt_lsb: output field (p_y)
};

inline FaultSpec Inject(Fault fault, std::int64_t k, std::size_t field = 1) {
  FaultSpec f;
  f.fault = fault;
  f.k = k;
  f.field = field;
  return f;
}

// What the fake did, for exact expectations in runs with stalls. Outlives the DUTs.
struct Probe {
  int instances = 0;
  std::optional<std::uint64_t> fault_cycle;    // cycle in which the fault first hit the ports
  std::optional<std::uint64_t> fault_ordinal;  // transaction it hit
};

// A correct pipeline of `latency` registers with bubble-collapsing backpressure: a stage advances
// when the next one is empty or advancing; the last stage is the output register, held while
// out_ready is low. Accepted in cycle c, visible in cycle c + latency at the earliest.
class FakeDut final : public phongsim::RtlDut {
 public:
  FakeDut(const LirpFormats& formats, std::size_t latency, FaultSpec fault, Probe* probe)
      : model_(formats),
        fault_(std::move(fault)),
        probe_(probe),
        stages_(latency),
        moves_(latency) {
    if (probe_ != nullptr) ++probe_->instances;
  }

  void reset() override {
    for (auto& s : stages_) s.reset();
    cycle_ = 0;
    accepted_ = 0;
    in_valid_ = out_ready_ = in_ready_ = out_valid_ = false;
    withdraw_now_ = protocol_fault_done_ = trigger_used_ = false;
    idle_ = 0;
  }
  void set_input(std::span<const std::int64_t> fields) override {
    in_.assign(fields.begin(), fields.end());
  }
  void set_in_valid(bool valid) override { in_valid_ = valid; }
  void set_out_ready(bool ready) override { out_ready_ = ready; }

  void settle() override {
    const auto& head = stages_.back();
    out_valid_ = head.has_value() && Visible(*head);
    const bool fire = out_valid_ && out_ready_;
    // The duplicated transaction stays in the output register for a second handshake.
    const bool leaves =
        fire && !(Is(Fault::duplicate) && Ordinal(*head) == fault_.k && !head->repeated);
    const std::size_t last = stages_.size() - 1;
    moves_[last] = leaves;
    bool free_next = !head.has_value() || leaves;
    for (std::size_t j = last; j-- > 0;) {
      moves_[j] = stages_[j].has_value() && free_next;
      free_next = !stages_[j].has_value() || moves_[j];
    }
    in_ready_ = free_next && !(Is(Fault::stall_forever) && Ordinal(accepted_) > fault_.k);
  }

  [[nodiscard]] bool in_ready() const override { return in_ready_; }
  [[nodiscard]] bool out_valid() const override { return out_valid_; }
  void output(std::span<std::int64_t> fields) const override {
    const auto& out = stages_.back()->out;
    std::copy(out.begin(), out.end(), fields.begin());
  }

  void clock() override {
    auto& head = stages_.back();
    if (out_valid_ && out_ready_) {
      if (head->faulty) Record(cycle_, head->ordinal);
      if (Is(Fault::duplicate) && Ordinal(*head) == fault_.k && !head->repeated) {
        head->repeated = true;
        head->faulty = true;  // the second handshake is the fault
      }
    }
    withdraw_now_ = false;
    if (out_valid_ && !out_ready_ && !protocol_fault_done_ && Ordinal(*head) > fault_.k) {
      if (Is(Fault::withdraw_valid)) {
        withdraw_now_ = true;
        protocol_fault_done_ = true;
        Record(cycle_ + 1, head->ordinal);
      } else if (Is(Fault::change_while_stalled)) {
        head->out[0] ^= 1;
        protocol_fault_done_ = true;
        Record(cycle_ + 1, head->ordinal);
      }
    }
    for (std::size_t j = stages_.size(); j-- > 0;) {  // downstream first: frees the next stage
      if (!moves_[j]) continue;
      if (j + 1 < stages_.size()) stages_[j + 1] = std::move(stages_[j]);
      stages_[j].reset();
    }
    if (in_valid_ && in_ready_) Accept();
    // late_extra: a copy of the last output, k idle cycles after it, once.
    const bool empty =
        std::none_of(stages_.begin(), stages_.end(), [](const auto& st) { return st.has_value(); });
    idle_ = empty && !in_valid_ && accepted_ > 0 ? idle_ + 1 : 0;
    if (Is(Fault::late_extra) && !protocol_fault_done_ &&
        idle_ == static_cast<std::uint64_t>(fault_.k)) {
      Entry e;
      e.ordinal = accepted_;
      (void)model_.eval(in_, e.out);
      e.faulty = true;
      stages_.back() = std::move(e);
      protocol_fault_done_ = true;
    }
    ++cycle_;
  }

  [[nodiscard]] std::uint64_t cycle() const override { return cycle_; }
  [[nodiscard]] bool assertion_failed() const override { return false; }
  void open_trace(const std::string&) override {}
  void close_trace() override {}

 private:
  struct Entry {
    std::uint64_t ordinal = 0;
    std::vector<std::int64_t> out;
    bool faulty = false;    // its next handshake shows the fault
    bool repeated = false;  // duplicate: first handshake done
  };

  [[nodiscard]] bool Is(Fault f) const { return fault_.fault == f; }
  static std::int64_t Ordinal(std::uint64_t n) { return static_cast<std::int64_t>(n); }
  static std::int64_t Ordinal(const Entry& e) { return Ordinal(e.ordinal); }

  [[nodiscard]] bool Visible(const Entry& e) const {
    if (Is(Fault::never_ready_output) && Ordinal(e) > fault_.k) return false;
    // Swap: #k waits until #k+1 is in (so the swap is never seen as data changing under valid).
    if (Is(Fault::swap) && Ordinal(e) == fault_.k && Ordinal(accepted_) < fault_.k + 2) {
      return false;
    }
    return !withdraw_now_;
  }

  void Record(std::uint64_t cycle, std::uint64_t ordinal) {
    if (probe_ == nullptr || probe_->fault_cycle) return;
    probe_->fault_cycle = cycle;
    probe_->fault_ordinal = ordinal;
  }

  void Accept() {
    Entry e;
    e.ordinal = accepted_++;
    (void)model_.eval(in_, e.out);
    const std::int64_t n = Ordinal(e);
    if (Is(Fault::corrupt_lsb)) {
      const bool hit = fault_.trigger.empty()
                           ? n == fault_.k
                           : !trigger_used_ && (in_ == fault_.trigger || in_ == fault_.trigger2);
      if (hit) {
        trigger_used_ = true;
        e.out[fault_.field] ^= 1;
        e.faulty = true;
      }
    }
    if (Is(Fault::drop) && n == fault_.k) return;  // accepted, never stored
    if (Is(Fault::drop) && n == fault_.k + 1) e.faulty = true;
    if (Is(Fault::swap) && n == fault_.k + 1) {
      for (auto& s : stages_) {
        if (s && Ordinal(*s) == fault_.k) {
          std::swap(s->out, e.out);
          s->faulty = true;
        }
      }
    }
    stages_[0] = std::move(e);
  }

  LirpModel model_;  // its own copy: the DUT computes independently of the scoreboard's model
  FaultSpec fault_;
  Probe* probe_;
  std::vector<std::optional<Entry>> stages_;  // [0] input side ... [L-1] output register
  std::vector<bool> moves_;                   // per stage: advances at this edge
  std::vector<std::int64_t> in_;
  std::uint64_t cycle_ = 0;
  std::uint64_t accepted_ = 0;
  bool in_valid_ = false;
  bool out_ready_ = false;
  bool in_ready_ = false;
  bool out_valid_ = false;
  bool withdraw_now_ = false;
  bool protocol_fault_done_ = false;
  bool trigger_used_ = false;
  std::uint64_t idle_ = 0;  // cycles with nothing in flight and nothing offered
};

// ---- expected report text ----

// One field line of a report, as specified by cosim.cpp's describe().
// One value as the reports print it: bit pattern, raw integer, real.
inline std::string Value(const phongsim::Field& f, std::int64_t raw) {
  return fmt::format("0x{:0{}x} {:>6} {}", fx::to_bits(raw, f.fmt), (f.fmt.width() + 3) / 4, raw,
                     fx::to_real(raw, f.fmt));
}

// A report line for one field: name, format, value.
inline std::string Describe(const phongsim::Field& f, std::int64_t raw) {
  return fmt::format("{:<8} {:>7}  {}", f.name, f.fmt.str(), Value(f, raw));
}

class Cosim : public ::testing::Test {
 protected:
  Config cfg_ = Config::load(kConfigPath);
  const phongsim::PipelineInfo& lirp_ = phongsim::find_pipeline("lirp");
  std::unique_ptr<phongsim::PipelineModel> model_ = phongsim::make_model(lirp_, cfg_);
  LirpFormats formats_ = dynamic_cast<const LirpModel&>(*model_).formats();
  phongsim::Stimulus stimulus_ = lirp_.make_stimulus(*model_, cfg_);

  static CosimOptions Options(const std::string& source = "none",
                              const std::string& sink = "none") {
    CosimOptions o;
    o.seed = kSeed;
    o.random_vectors = kRandom;
    o.timeout = kTimeout;
    o.source = StallPattern::parse(source);
    o.sink = StallPattern::parse(sink);
    return o;
  }

  // contract: counted against LIRP's input contract (none: nothing counted).
  CosimReport Run(const FaultSpec& fault, const CosimOptions& o, Probe* probe = nullptr,
                  bool contract = false) {
    const phongsim::DutFactory factory = [&] {
      return DutPtr(new FakeDut(formats_, kLatency, fault, probe), DutDeleter{});
    };
    const phongsim::CosimSubject subject{
        "lirp",    cfg_, *model_,
        stimulus_, true, factory,
        "",        "",   contract ? lirp_.contract(*model_, cfg_) : phongsim::InputContract()};
    return phongsim::cosim(subject, o);
  }

  std::vector<std::int64_t> Inputs(std::uint64_t index) const {
    std::vector<std::int64_t> in(model_->inputs().size());
    stimulus_.vector(kSeed, index, in);
    return in;
  }
  std::vector<std::int64_t> Outputs(std::uint64_t index) {
    std::vector<std::int64_t> out;
    LirpModel m(formats_);
    (void)m.eval(Inputs(index), out);
    return out;
  }

  // The MISMATCH block for vector `index` receiving `got` in `cycle`.
  std::string Mismatch(std::uint64_t cycle, std::uint64_t index, const std::string& hint,
                       const std::vector<std::int64_t>& got) {
    std::string s = fmt::format("MISMATCH at cycle {}, vector {} (output 1 of 1 for it){}\n", cycle,
                                index, hint);
    s += "  inputs:\n";
    const auto in = Inputs(index);
    for (std::size_t i = 0; i < in.size(); ++i) {
      s += "    " + Describe(model_->inputs()[i], in[i]) + "\n";
    }
    const auto want = Outputs(index);
    std::size_t column = 16;  // widest expected value + 4
    for (std::size_t i = 0; i < want.size(); ++i) {
      column = std::max(column, Value(model_->outputs()[i], want[i]).size() + 4);
    }
    s += "  outputs:" + std::string(12, ' ') + "expected" + std::string(column - 8, ' ') + "got\n";
    for (std::size_t i = 0; i < want.size(); ++i) {
      const auto& f = model_->outputs()[i];
      const std::string w = Value(f, want[i]);
      s += "    " + Describe(f, want[i]) + std::string(column - w.size(), ' ') + Value(f, got[i]) +
           (want[i] != got[i] ? "   <-- differs" : "") + "\n";
    }
    return s;
  }

  // The lines cosim appends to every main-run failure.
  static std::string Context(const CosimOptions& o, std::optional<std::uint64_t> alone) {
    std::string patterns =
        fmt::format("--source-idle {} --backpressure {}", o.source.str(), o.sink.str());
    if (o.timeout != 0) patterns += fmt::format(" --timeout {}", o.timeout);
    const std::string cmd =
        fmt::format("phongsim cosim --pipeline lirp --config {} --seed {}", kConfigPath, o.seed);
    std::string s = fmt::format(
        "  pipeline lirp, config default ({}), seed {}, source idle {}, sink backpressure {}\n",
        kConfigPath, o.seed, o.source.str(), o.sink.str());
    if (o.only_index) {
      s += fmt::format("  reproduce: {} --vector-index {} {}\n", cmd, *o.only_index, patterns);
    } else {
      s += fmt::format("  reproduce: {} --vectors {} {}\n", cmd, o.random_vectors, patterns);
      if (alone)
        s += fmt::format("  this vector alone: {} --vector-index {} {}\n", cmd, *alone, patterns);
    }
    return s;
  }
};

}  // namespace phongsim::testing
