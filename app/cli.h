// What the phongsim subcommands share: choosing a pipeline configuration and its RTL, loading
// them, range-checked number options, and the progress line. Each subcommand lives in its own
// file (app/<command>.cpp) and registers itself through commands.h.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/cosim.h"
#include "sim/pipelines/registry.h"

namespace phongsim::cli {

// What a subcommand runs once the command line parsed; its exit status.
using Action = std::function<int()>;

// Upper bounds of counting options: far beyond any run that ends, far below wrap-around.
inline constexpr std::uint64_t kMaxVectors = 1'000'000'000'000;
inline constexpr std::uint64_t kMaxCycles = 1'000'000'000'000;
// A deadlock is declared after at most this many silent cycles (seconds of simulation).
inline constexpr std::uint64_t kMaxTimeout = 100'000'000;
// A waveform window: at most ten million cycles (gigabytes of FST beyond that).
inline constexpr std::uint64_t kMaxTraceWindow = 10'000'000;
// bench holds its vectors in memory (to time the model and the RTL, not the stimulus).
inline constexpr std::uint64_t kMaxBenchVectors = 10'000'000;
// PHONGSIM_QUICK=1 caps (docs/cosim.md): vectors of cosim, bench and vectors.
inline constexpr std::uint64_t kQuickVectors = 2000;

// A counting option: digits only, in min..max (no signs, no wrap-around: "-1" is refused).
CLI::Option* add_count(CLI::App& cmd, const std::string& name, std::uint64_t& value,
                       const std::string& description, std::uint64_t max, std::uint64_t min = 0);

// A whole-number option that may be negative: an optional '-' and digits, in lo..hi (no
// "1e3", no hex, no wrap-around).
CLI::Option* add_int(CLI::App& cmd, const std::string& name, int& value,
                     const std::string& description, int lo, int hi);

// A real-number option: a finite decimal number in lo..hi.
CLI::Option* add_real(CLI::App& cmd, const std::string& name, double& value,
                      const std::string& description, double lo, double hi);

// An option that is one of `choices`, shown as "a|b|c" in --help, its default the value's.
CLI::Option* add_choice(CLI::App& cmd, const std::string& name, std::string& value,
                        const std::string& description, const std::vector<std::string>& choices);

// What every command shares, once all are added (main() calls it): --help in plain words (an
// option's kind, a range or its choices, "(default X)" at the end of its description; no CLI11
// type names, validator texts or flag values), and --progress on every command that runs.
void add_common_options(CLI::App& app);

// PHONGSIM_QUICK=1 in the environment: every command runs at a reduced size, for smoke tests of
// the documented commands (tests/doc_commands_test.py; docs/cosim.md says what shrinks). Each
// quick command says so on stderr once.
[[nodiscard]] bool quick_mode();
// `value`, or at most `cap` in quick mode.
[[nodiscard]] std::uint64_t quick_cap(std::uint64_t value, std::uint64_t cap);

// --pipeline / --config and the RTL to use, shared by every subcommand that works on one
// configuration.
struct Target {
  std::string pipeline;
  std::string config;
  std::vector<std::string> configs;  // several --config, where the command takes a list
  bool no_build = false;
  // The user's RTL: --rtl's words (files, folders, +incdir+, +define+), file lists (-f, -F),
  // include folders (-I) and defines (-D); sim/cosim/rtl_args.h. sources() reads them in the
  // order given.
  std::vector<std::string> rtl;
  std::vector<std::string> lists_cwd, lists_here, include_dirs, defines;  // -f, -F, -I, -D
  std::string top;                      // its top module (--top; default: the built-in top's name)
  std::string plugin;                   // a plugin file given by hand (--rtl-plugin)
  std::string simulator = "verilator";  // or icarus (--simulator)
  std::string x_init = "zero";          // or random (--x-init): how Verilated registers start
  std::uint64_t x_seed = 1;             // --x-seed, with --x-init random
  CLI::Option* x_seed_opt = nullptr;
  std::string coverage_prefix;  // cosim --coverage: the coverage plugin, files under this prefix
  bool coverage_toggle = true;  // ... with toggle points (not with --no-toggle-coverage)
  const CLI::App* command = nullptr;  // where the options were added: their order as given

  // `rtl_options`: also --rtl, -f, -F, -I, -D, --top, --rtl-plugin and --no-build.
  // `many_configs`: --config may be given several times (into `configs`).
  void add_options(CLI::App& cmd, bool rtl_options = true, bool many_configs = false);
  // Only the options that name the user's sources: --rtl, -f, -F, -I, -D and --top.
  void add_source_options(CLI::App& cmd);
  // Whether the user gave RTL of their own (--rtl or a file list).
  [[nodiscard]] bool user_rtl() const {
    return !rtl.empty() || !lists_cwd.empty() || !lists_here.empty();
  }
  // The user's RTL as one set, in the order the options were given (files, lists read).
  [[nodiscard]] RtlSources sources() const;
  // The same; Error for include folders or defines without sources to go with them.
  [[nodiscard]] RtlSources checked_sources() const;
  // The options that name the user's RTL again, shell-quoted, in the order given
  // (" --rtl a.sv +incdir+inc -f files.f -D X=1"); "" for phongsim's RTL.
  [[nodiscard]] std::string rtl_options() const;
  // --simulator, --x-init and --x-seed, for the commands that run the RTL vector by vector
  // (cosim, eval).
  void add_simulator_option(CLI::App& cmd);
  // Error for --x-seed without --x-init random, and for --x-init random with --simulator icarus
  // or --rtl-plugin.
  void check_x_init() const;
  // What the command reads, each with the option that names it, for check_outputs(): the
  // configuration(s), --rtl-plugin, and --rtl's files and folders with what is in them (a
  // folder's files, and the SystemVerilog files and headers beside a given file, which an
  // `include may read).
  [[nodiscard]] std::vector<std::pair<std::string, std::filesystem::path>> inputs() const;
  // "zero", "random" or, for Icarus (four-state), "x"; and the seed, 0 when there is none.
  [[nodiscard]] std::string x_init_mode() const;
  [[nodiscard]] std::uint64_t x_init_seed() const { return x_init == "random" ? x_seed : 0; }
};

struct Loaded {
  Config cfg;
  const PipelineInfo* pipeline = nullptr;
  std::unique_ptr<PipelineModel> model;
};

// The configuration (default: configs/<pipeline>/default.toml) and its model.
[[nodiscard]] Loaded load(const Target& t);

// The design the target names: the user's files (--rtl, --top) or phongsim's rtl/.
[[nodiscard]] RtlDesign design_of(const Loaded& l, const Target& t);

// DUTs of the target's RTL (located, built on demand or refused under --no-build), what to call
// that RTL in a summary, and the options that select it again.
// What RTL a verdict is about, as data (the JSON's runs[].rtl; docs/json.md).
struct RtlIdentity {
  std::string top;
  std::string source;     // "builtin" (phongsim's rtl/), "rtl" (--rtl, -f), "plugin" (--rtl-plugin)
  std::string simulator;  // "verilator", "icarus"
  std::filesystem::path plugin;  // Verilator: the plugin run
  // Verilator: the plugin's record (key, files and included files as built, flags). Icarus,
  // which compiles the files when the run starts: the files' hashes then, no key, no flags.
  PluginSources sources;
  std::vector<std::filesystem::path> include_dirs;
  std::vector<std::string> defines;
  std::vector<RtlParam> params;
};

struct Rtl {
  DutFactory make_dut;
  std::string label;
  std::string options;
  RtlIdentity identity;
};
[[nodiscard]] Rtl rtl_of(const Loaded& l, const Target& t);

// A co-simulation subject for `l` and the target's RTL; `stimulus` must outlive it. `identity`
// (optional) receives what RTL it runs.
[[nodiscard]] CosimSubject subject_of(const Loaded& l, const Target& t, const Stimulus& stimulus,
                                      RtlIdentity* identity = nullptr);

// Progress on stderr (never stdout), as --progress says (docs/cosim.md):
//   auto (the default): the terminal line when stderr is a terminal, heartbeat lines otherwise;
//   always: the terminal line; never: nothing.
// The terminal line overwrites itself ("\r", erase to the end of the line): shown once the
// command has run for 2 s (short runs stay quiet), at most five updates a second, with the
// elapsed time, cleared when the work ends. A heartbeat line is one plain line for a CI log,
// "phongsim: WHAT: DONE of TOTAL, 1m40s": the first after 10 s, then at most one every 20 s (a
// sign of life without a flood). PHONGSIM_PROGRESS_AFTER=S changes the first delay of either,
// PHONGSIM_PROGRESS_EVERY=S the heartbeat's interval (0: every update; for tests).
enum class ProgressMode { automatic, always, never };
void set_progress_mode(ProgressMode mode);

// A task's progress: (what, done, total); total 0: unknown; done == total != 0: finished.
using Progress = std::function<void(std::string_view, std::uint64_t, std::uint64_t)>;
[[nodiscard]] Progress progress_line(bool quiet = false);

// Where `path` lies inside `dir`, relative to it (then a --json there is a file of a command's
// output set), or nothing.
[[nodiscard]] std::optional<std::filesystem::path> inside(const std::filesystem::path& path,
                                                          const std::filesystem::path& dir);

// The program as this process was run (argv[0], shell-quoted), for the commands phongsim prints
// to be pasted as they are; main() sets it.
void set_invocation(std::string_view argv0);
[[nodiscard]] const std::string& invocation();

// Progress of the helper programs phongsim waits for (Verilation through cmake, Yosys, nextpnr),
// shown as progress_line() is: the program, its elapsed time and, for a build, ninja's
// [done/total]. Refuses an unusable PHONGSIM_PROGRESS_AFTER or PHONGSIM_PROGRESS_EVERY (Error).
void install_tool_progress();

// One co-simulation of a command (cosim's matrix, sweep search's verification) and its time.
struct CosimRun {
  CosimReport report;
  double seconds = 0;
  RtlIdentity rtl;
};

// Text for XML (&, <, >, ", ').
[[nodiscard]] std::string xml_escaped(std::string_view text);

// JUnit XML as CI systems read it: one testsuite per pipeline, one testcase per run, the
// first-failure report as the failure's text (docs/cosim.md).
[[nodiscard]] std::string junit_xml(std::span<const CosimRun> runs);

}  // namespace phongsim::cli
