// Co-simulation: the model and the Verilated RTL get identical transactions; a scoreboard
// compares every output field bit-exactly and in order. Stops at the first mismatch, dropped,
// duplicated or reordered output, deadlock or handshake violation, with a report that names
// configuration, seed, vector index and cycle and the command that reproduces it.
#pragma once

#include <algorithm>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/contract.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/stall.h"
#include "sim/cosim/stimulus.h"
#include "sim/cosim/waveform.h"

namespace phongsim {

struct CosimOptions {
  std::uint64_t seed = 1;
  std::uint64_t random_vectors = 100000;  // after the directed corners
  bool directed = true;
  std::optional<std::uint64_t> only_index;  // run this one vector (directed or random) alone
  StallPattern source;                      // source idle pattern
  StallPattern sink;                        // sink backpressure pattern
  std::string trace_path;                   // FST waveform; empty = none
  std::uint64_t trace_window = 1000;        // cycles before a failure (or from the start)
  std::uint64_t timeout = 0;                // deadlock timeout in cycles; 0 = harness default
  std::uint64_t measure_vectors = 1000;     // stall-free run that measures throughput/latency
  // Workers (threads). The main run's vectors go to `jobs` DUTs, each taking a contiguous share
  // from reset to its end (at group starts when vectors are not independent: Stimulus), unless
  // reset_every is set.
  unsigned jobs = 1;
  // A fresh DUT (from reset) every this many vectors, at group starts; the workers share those
  // runs, and --jobs changes nothing but the time. 0: no resets but one per worker's share.
  std::uint64_t reset_every = 0;
  // Called now and then during the main run with (inputs accepted, inputs in total).
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
};

// One field's value in a failure: its raw integer and the real value it stands for.
struct FieldValue {
  std::string name;
  std::string format;  // "S1.10"
  std::int64_t raw = 0;
  double real = 0;
};

// One output field of the failing output: what the model expected (absent for an output nobody
// owed) and what the RTL gave.
struct FieldComparison {
  std::string name;
  std::string format;
  std::optional<FieldValue> expected;
  std::optional<FieldValue> got;
  bool differs = false;
};

// The first failure as data — the same facts as the text report, for JSON (docs/json.md).
struct CosimFailure {
  std::string kind;         // "mismatch", "unexpected output", "deadlock", "protocol", "assertion",
                            // "unknown value"
  std::uint64_t cycle = 0;  // the cycle it was detected in
  std::optional<std::uint64_t> vector;   // mismatch: the vector owning the output; deadlock,
                                         // protocol: the vector owing the next output
  std::optional<std::uint64_t> output;   // mismatch: which of that vector's outputs (0-based)
  std::uint64_t outputs_of_vector = 0;   // mismatch: how many outputs that vector has
  std::vector<FieldValue> inputs;        // mismatch: the vector's inputs
  std::vector<FieldComparison> outputs;  // mismatch, unexpected output: per output field
  // mismatch: the model's stage values for the vector (docs/<pipeline>.md's names), when the
  // subject has them, and whether it lies inside the input contract ("inside", or the clause it
  // breaks; "" without a contract).
  std::vector<FieldValue> stages;
  // mismatch, Verilator: each stage looked for in the design's signals named after it, in a
  // waveform of the failing run, while the vector was in flight (from its acceptance to the
  // failing output); the first stage with signals that never held the model's value is where the
  // design parts from the model ("" when none is found).
  std::vector<StageSighting> sightings;
  std::string first_differing_stage;
  std::string contract;
  std::string message;              // one line: what failed, where (also the harness's words)
  bool in_measurement_run = false;  // found by the stall-free measurement run
};

struct CosimReport {
  std::string pipeline;
  std::string rtl_label;
  std::string rtl_options;
  std::string config_name;
  std::string config_path;
  std::string command;        // CosimSubject::command
  std::string config_option;  // CosimSubject::config_option, or " --config <its file>"
  CosimOptions options;
  std::uint64_t directed = 0;  // directed vectors in the main run
  std::uint64_t random = 0;    // random vectors in the main run
  std::uint64_t vectors = 0;   // inputs accepted by the RTL in the main run
  std::uint64_t outputs = 0;   // outputs compared in the main run
  // The accepted vectors of the main run inside and outside the subject's input contract (empty
  // clauses and no counts when it has none).
  std::vector<std::string> contract_clauses;
  std::optional<ContractCounts> contract;
  std::string contract_text;  // InputContract::summary of the counts, for the summary line
  std::uint64_t mismatches = 0;
  std::uint64_t cycles = 0;  // main run
  // The main run's DUTs (each from reset), and the most vectors and outputs one of them took
  // since its reset: the longest sequence the verdict vouches for.
  std::uint64_t duts = 0;
  std::uint64_t longest_vectors = 0;
  std::uint64_t longest_outputs = 0;
  // The longest drain window of the main run's DUTs: cycles after the last expected output with
  // the sink ready and no input, in which any output fails the run (0: no run finished).
  std::uint64_t drain_cycles = 0;
  // The main run's stall patterns at work (HarnessResult): what the stall-pattern coverpoints
  // count.
  std::uint64_t source_idle_cycles = 0;
  std::uint64_t sink_stall_cycles = 0;
  // From the stall-free measurement run (0 when it did not run: measured false).
  bool measured = false;
  double throughput = 0.0;  // outputs per clock in steady state
  std::uint64_t latency_min = 0;
  std::uint64_t latency_max = 0;
  bool passed = false;
  std::string failure_kind;                    // "", or a CosimFailure kind
  std::string failure;                         // multi-line first-failure report
  std::optional<CosimFailure> failure_detail;  // the same as data
  std::string trace_written;                   // waveform path, when one was written

  [[nodiscard]] std::string summary() const;  // one line
};

// "0x802  -2046 -1.998046875": a raw value as reports show it (bit pattern, raw, real).
[[nodiscard]] std::string value_text(std::int64_t raw, fx::Format fmt);

// What a co-simulation runs: one configuration's model and stimulus against DUTs from make_dut.
struct CosimSubject {
  std::string pipeline;  // its name, for reports
  const Config& cfg;
  PipelineModel& model;
  const Stimulus& stimulus;
  // True when every output depends only on its own input vector, so one vector can be re-run
  // alone (the failure report then offers that command).
  bool independent_vectors = true;
  DutFactory make_dut;
  // Which RTL make_dut makes, for the summary line ("built-in lirp_unit"), and the options that
  // select it again, for reproduce commands (" --rtl my/lirp --top my_lirp").
  std::string rtl_label;
  std::string rtl_options;
  // The pipeline's input contract for this configuration; the report counts the main run's
  // vectors against it. None (default): nothing counted.
  InputContract contract;
  // How reproduce commands begin and name the configuration: the program as it was run
  // ("./build/phongsim"), and the configuration as the user named it (" --config my.toml"; ""
  // for the pipeline's default). Defaults: "phongsim" and the configuration's file.
  std::string command = "phongsim";
  std::optional<std::string> config_option = std::nullopt;
  // The model's stage values of one vector (PipelineInfo::stages), for the failure report; the
  // model is reset and has seen the vectors before it since reset. None: no stage table.
  std::function<std::vector<StageValue>(PipelineModel&, std::span<const std::int64_t>)> stages;
  // Whether make_dut's DUTs write waveforms (Verilator's do, Icarus's do not).
  bool traceable = true;
};

// Error (nothing is checked, so nothing may pass) when the options give no vector; and when
// reset_every or jobs > 1 ask for resets in a stream whose vectors depend on each other with no
// group starts.
CosimReport cosim(const CosimSubject& subject, const CosimOptions& options);

// The scoreboard makes and evaluates the vectors a batch at a time: at most kCosimBatch, and
// after a batch of `n` vectors whose expected outputs came to `values` values, as many as would
// come to about kCosimBatchValues (512 KB, about a core's L2: the walkers' triangles have
// hundreds of pixels each, and 1,024 of them, 20 MB of expected outputs, were written and read
// back from memory). The bench times the model in the same batches.
inline constexpr std::uint64_t kCosimBatch = 1024;
inline constexpr std::uint64_t kCosimBatchValues = 1 << 16;
[[nodiscard]] inline std::uint64_t next_cosim_batch(std::uint64_t n, std::uint64_t values) {
  return std::clamp<std::uint64_t>(n * kCosimBatchValues / std::max<std::uint64_t>(values, 1), 1,
                                   kCosimBatch);
}

}  // namespace phongsim
