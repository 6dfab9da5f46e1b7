// Finding, building and loading the Verilated RTL of a (pipeline, configuration).
//
// Each configuration's RTL is a plugin: a shared module made by cmake/PhongsimRtl.cmake from the
// pipeline's RTL, its adapter in sim/rtl/ and the configuration's -G parameters. Lookup order:
//   1. plugins CMake built for configs/ (listed in <build>/rtl/manifest.tsv), matched by
//      pipeline and -G parameters, so a copy of a built-in configuration needs no new build;
//   2. the on-demand cache, keyed by pipeline, -G parameters, the content of rtl/, sim/, model/
//      and cmake/, and the Verilator and compiler versions;
//   3. otherwise Verilate and compile into the cache now (slow the first time only), unless the
//      caller asks not to, in which case the error gives the command that builds it.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "model/config.h"
#include "model/pipeline.h"
#include "sim/cosim/rtl_dut.h"

namespace phongsim {

// Keeps the plugin loaded for as long as a DUT made from it exists.
struct DutDeleter {
  std::shared_ptr<void> library;
  void operator()(RtlDut* dut) const { delete dut; }
};
using DutPtr = std::unique_ptr<RtlDut, DutDeleter>;

class RtlLibrary : public std::enable_shared_from_this<RtlLibrary> {
 public:
  // Loads a plugin; refuses one built for another ABI or other -G parameters than `gflags`.
  static std::shared_ptr<RtlLibrary> open(const std::filesystem::path& path,
                                          const std::string& gflags);
  ~RtlLibrary();
  RtlLibrary(const RtlLibrary&) = delete;
  RtlLibrary& operator=(const RtlLibrary&) = delete;

  // A fresh DUT instance (own Verilator context), ports bound to the model's fields.
  [[nodiscard]] DutPtr create(const PipelineModel& model);

 private:
  RtlLibrary() = default;
  void* handle_ = nullptr;
  RtlCreateFn create_ = nullptr;
  std::filesystem::path path_;
};

// The -G parameters of a configuration, space-separated (Config::rtl_parameters()).
[[nodiscard]] std::string rtl_gflags(const Config& cfg);

// $PHONGSIM_CACHE, else $XDG_CACHE_HOME/phongsim, else ~/.cache/phongsim.
[[nodiscard]] std::filesystem::path rtl_cache_dir();

enum class RtlBuild { if_missing, never };

struct RtlPlugin {
  std::filesystem::path path;
  std::string gflags;
  std::string origin;  // "built in", "cached", "built now"
};

// Finds (or builds) the plugin for `cfg`. Progress of a build goes to `log`.
[[nodiscard]] RtlPlugin locate_rtl(const Config& cfg, RtlBuild policy, std::FILE* log);

}  // namespace phongsim
