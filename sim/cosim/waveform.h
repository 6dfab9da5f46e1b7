// Waveform formats. The Verilated plugins trace to FST (the runtime they share is built with
// VerilatedFstC); a VCD is the same waveform converted by the FST reader of GTKWave's fstapi,
// which Verilator ships (the conversion GTKWave's fst2vcd does).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "model/pipeline.h"

namespace phongsim {

enum class WaveFormat { fst, vcd };

// The format a waveform path asks for by its extension (.fst or .vcd, any case); Error naming
// the path otherwise.
[[nodiscard]] WaveFormat wave_format(const std::filesystem::path& path);

// Writes the FST file `fst` to `vcd` as a Value Change Dump. Error when it cannot be read.
void fst_to_vcd(const std::filesystem::path& fst, std::FILE* vcd);

// A variable a waveform declares: its scope ("top.my_lirp.g_component[0]"), its name without
// the bit range ("m0_q"; an unpacked array's element "arr_q[2]"), its bits and its type as a VCD
// names it ("logic", "wire", "int", "real", "parameter", ...), and whether it is a port of its
// scope (a module's).
struct WaveSignal {
  std::string scope;
  std::string name;
  std::uint32_t bits = 0;
  std::string type;
  bool port = false;
};

// Every variable the FST `fst` declares, in its order. Error when it cannot be read.
[[nodiscard]] std::vector<WaveSignal> waveform_signals(const std::filesystem::path& fst);

// What the harness saw in the cycles a waveform covers: the inputs it handed over and the
// outputs it took, each output with the model's expected fields.
struct WaveNotes {
  struct Accept {
    std::uint64_t cycle = 0;
    std::uint64_t vector = 0;  // its index in the run's stream
  };
  struct Output {
    std::uint64_t cycle = 0;
    std::uint64_t number = 0;  // outputs of the run before it (from the DUT's reset)
    std::uint64_t vector = 0;  // the vector it belongs to, and which of its outputs it is
    std::uint64_t index = 0;
    bool owed = true;  // false: no vector owes it (an unexpected output); no expected values
    std::vector<std::int64_t> expected, got;  // raw, in `fields` order
  };
  std::vector<Field> fields;  // the outputs'
  std::vector<Accept> accepts;
  std::vector<Output> outputs;
};

// Adds a top-level scope `phongsim` to the FST `fst` (rewritten in place), one value per cycle
// at the clock-low time 2·cycle where the harness samples the handshake: in_accept/in_vector
// (the vector the DUT accepts), out_take/out_vector/out_index (the output the harness takes and
// the vector it answers), expected_<field> and mismatch_<field> per output field, and mismatch
// (any field). Between handshakes the strobes are 0 and the values x. Error when it cannot be read.
void annotate_waveform(const std::filesystem::path& fst, const WaveNotes& notes);

// A model stage looked for in the design's waveform: the signals named after it (the stage's
// name, or it with a register suffix _q _d _r _reg _ff, any case, in any scope; see
// named_after in waveform.cpp) and whether each held the model's value at some time in the window.
struct StageSighting {
  struct Signal {
    std::string path;  // dotted scope path
    bool held = false;
  };
  std::string stage;
  std::vector<Signal> signals;         // empty: the design has no signal of its name
  [[nodiscard]] bool missed() const {  // a signal of its name never held the model's value
    for (const Signal& s : signals) {
      if (!s.held) return true;
    }
    return false;
  }
};
[[nodiscard]] std::vector<StageSighting> find_stages(const std::filesystem::path& fst,
                                                     const std::vector<StageValue>& stages,
                                                     std::uint64_t from_time,
                                                     std::uint64_t to_time);

}  // namespace phongsim
