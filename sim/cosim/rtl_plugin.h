// Building, finding and loading the Verilated RTL of one design: a pipeline's top with one
// configuration's parameters, from phongsim's rtl/ or from the user's own files (--rtl).
//
// A plugin is a shared module exporting phongsim_rtl_create() (sim/cosim/verilated_dut.h). It is
// keyed by its content: every RTL file it compiles, the top, the parameters, the port binding,
// the C++ it is compiled with, and the Verilator and compiler versions and flags. The cache
// (rtl_cache_dir()) holds one directory per key; a design whose key is not there is Verilated
// now (or refused under RtlBuild::never). A changed file therefore always means a new build,
// never an old result.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "base/temporaries.h"
#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/rtl_dut.h"

namespace phongsim {

// A data port of the top and the model fields it carries, packed from bit 0 up, each as wide
// as its format. The stream handshake (clk_i, rst_ni, in_valid_i, in_ready_o, out_valid_o,
// out_ready_i) is implied.
struct PortBinding {
  std::string port;
  bool input = true;
  std::vector<std::string> fields;
};

// How the registers of a Verilated design start. zero: every register and every X assignment 0
// (-x-assign fast -x-initial fast; the plugin every command uses by default). random: a plugin
// of its own (-x-assign unique -x-initial unique; its key differs, so the zero plugin is
// untouched) whose registers power up, and whose X assignments evaluate, to values drawn from a
// seed given when each DUT is made (Verilator's randReset(2) and randSeed(seed)).
enum class XInit { zero, random };

// Everything that determines a plugin besides the tools.
struct RtlDesign {
  std::string name;                          // what it is, for messages and cache entries
  std::string top;                           // top module
  std::vector<std::filesystem::path> files;  // SystemVerilog sources, in compile order
  // Include folders searched before the folders of `files` (+incdir+, -I), and macros defined for
  // every file (NAME or NAME=VALUE: +define+, -D); sim/cosim/rtl_args.h.
  std::vector<std::filesystem::path> include_dirs;
  std::vector<std::string> defines;
  std::vector<RtlParam> params;  // the top's parameters
  std::vector<PortBinding> ports;
  XInit x_init = XInit::zero;
  // A coverage variant (Verilator --coverage-line, and --coverage-toggle with coverage_toggle;
  // its own key): each DUT writes its counts when destroyed (RtlLibrary::create). Toggle points
  // multiply the Verilated C++ (up to 30x for shade_quad), so its build and run time.
  bool coverage = false;
  bool coverage_toggle = true;
  std::string builtin_top;  // the pipeline's own top (what --top defaults to), for messages
  std::string config;       // its configuration's name, for progress lines
};

// "-GPFmt=65802 -GAFmt=266 ...": the parameters as Verilator takes them.
[[nodiscard]] std::string verilator_gflags(std::span<const RtlParam> params);

// -I<folder> for every include folder (rtl_include_dirs: the given ones, then the files') and
// -D<define> for every define: what Verilator, Icarus and Yosys all read the same way.
[[nodiscard]] std::vector<std::string> rtl_source_flags(const RtlDesign& design);

// The SystemVerilog files of PATHs, in compile order: a file as given, a folder's *.sv and *.v
// files sorted by name; the files that declare a package first, each after the packages it
// names (packages must precede their users), the rest in the order given. Error for a path that
// does not exist, a file that is not .sv/.v, or no files at all.
[[nodiscard]] std::vector<std::filesystem::path> rtl_files(
    std::span<const std::filesystem::path> paths);

// When `tool_output` (Verilator's or Yosys's) says the design's top is not in its files, one
// line naming the modules the files declare and --top; else "".
[[nodiscard]] std::string missing_top_problem(const RtlDesign& design,
                                              std::string_view tool_output);

// $PHONGSIM_CACHE, else <build tree>/rtl-cache.
[[nodiscard]] std::filesystem::path rtl_cache_dir();

// Checks the design's ports against its binding and `model`'s field formats: every bound port
// present with the right direction and width (the sum of its fields' widths), the handshake
// ports one bit each, no other ports. Verilates nothing but the interface (a fraction of a
// second). Error naming the first difference; otherwise every port's width.
std::map<std::string, int> check_ports(const RtlDesign& design, const PipelineModel& model);

enum class RtlBuild { if_missing, never };

struct RtlPlugin {
  std::filesystem::path path;
  std::string key;
  std::string origin;  // "cached", "built now"
};

// A file a plugin was built from, and the SHA-256 of the bytes Verilator read.
struct SourceHash {
  std::filesystem::path path;
  std::string sha256;
};

// What a plugin was built from, as its record says.
struct PluginSources {
  std::string key;
  std::vector<SourceHash> files;     // the design's files, in compile order
  std::vector<SourceHash> includes;  // the files they `include
  // Verilator's flags besides the sources, include folders, defines and -G parameters.
  std::vector<std::string> flags;
};

// The record of `plugin`, a cached build of `design`, with the paths where `design` finds its
// files now (a cached build may come from another copy of the same files).
[[nodiscard]] PluginSources plugin_sources(const RtlPlugin& plugin, const RtlDesign& design);

// The plugin of `design` (its fields' widths from `model`): from the cache, or Verilated now
// (progress on `log`), or under RtlBuild::never an Error saying how to build it.
[[nodiscard]] RtlPlugin locate_rtl(const RtlDesign& design, const PipelineModel& model,
                                   RtlBuild policy, std::FILE* log);

// Builds every design that is not cached yet, all in one parallel build; returns each one's
// plugin, in order. designs[i] goes with models[i].
std::vector<RtlPlugin> build_rtl(std::span<const RtlDesign> designs,
                                 std::span<const PipelineModel* const> models, std::FILE* log);

// Keeps the plugin loaded for as long as a DUT made from it exists.
struct DutDeleter {
  std::shared_ptr<void> library;
  void operator()(RtlDut* dut) const { delete dut; }
};
using DutPtr = std::unique_ptr<RtlDut, DutDeleter>;

class RtlLibrary : public std::enable_shared_from_this<RtlLibrary> {
 public:
  // Loads a plugin from the cache; refuses one of another ABI or whose key is not `key`.
  static std::shared_ptr<RtlLibrary> open(const RtlPlugin& plugin);
  // Loads a plugin file given by hand (--rtl-plugin): it must have been built for `design`'s top,
  // parameters and ports, and every source file it records must still have the content it was
  // built from (Error naming the first that changed).
  static std::shared_ptr<RtlLibrary> open_file(const std::filesystem::path& path,
                                               const RtlDesign& design);
  ~RtlLibrary();
  RtlLibrary(const RtlLibrary&) = delete;
  RtlLibrary& operator=(const RtlLibrary&) = delete;

  // A fresh DUT instance (own Verilator context), ports bound to the model's fields. Error when a
  // port was built narrower or wider than the model's fields need now. A plugin built with
  // XInit::random draws its power-up state from `x_seed` (1..2^31-1; the same seed gives the same
  // state); the seed is ignored by a zero plugin. A coverage plugin's DUT writes its coverage
  // counts (Verilator's coverage.dat format) to `coverage_prefix`<n>.dat when destroyed (n
  // counts the DUTs the plugin has made); an empty prefix writes nothing.
  [[nodiscard]] DutPtr create(const PipelineModel& model, std::uint32_t x_seed = 1,
                              const std::string& coverage_prefix = "");
  // Whether the plugin was built with XInit::random.
  [[nodiscard]] bool x_random() const { return x_seed_ != nullptr; }
  // The $PHONGSIM_VERILATOR_FLAGS it was built with ("" for none).
  [[nodiscard]] std::string verilator_extra() const;
  // Its record, with the paths of the build.
  [[nodiscard]] PluginSources sources() const;

 private:
  RtlLibrary() = default;
  static std::shared_ptr<RtlLibrary> load(const std::filesystem::path& path);
  void* handle_ = nullptr;
  RtlCreateFn create_ = nullptr;
  RtlInfoFn info_ = nullptr;
  void (*x_seed_)(int) = nullptr;            // phongsim_rtl_x_seed of an XInit::random plugin
  void (*coverage_)(const char*) = nullptr;  // phongsim_rtl_coverage_prefix of a coverage plugin
  std::filesystem::path path_;
  std::unique_ptr<CrashRegion> crash_;  // a crash in its code is reported naming it
};

// Makes fresh DUT instances of one plugin (each with its own Verilator context).
using DutFactory = std::function<DutPtr()>;

// The DUTs of `design` for `model`'s fields: located or built (policy, progress on `log`) and
// loaded; `located` (optional) receives which plugin. `model` must outlive the factory. With
// design.x_init random, every DUT powers up from `x_seed`; with design.coverage, each writes
// its counts to `coverage_prefix`<n>.dat (RtlLibrary::create).
[[nodiscard]] DutFactory rtl_duts(const RtlDesign& design, const PipelineModel& model,
                                  RtlBuild policy, std::FILE* log, RtlPlugin* located = nullptr,
                                  std::uint32_t x_seed = 1,
                                  const std::string& coverage_prefix = "");

}  // namespace phongsim
