#include "sim/cosim/rtl_library.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "base/error.h"
#include "base/file_util.h"
#include "base/paths.h"
#include "base/process.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

// Paths and tools fixed when phongsim was configured (CMakeLists.txt).
const fs::path& kSourceDir = data_root();
const fs::path& kBuildDir = build_root();
const char* const kCmake = cmake_program();
const char* const kCxxCompiler = cxx_compiler();

std::string tool_version(const std::vector<std::string>& argv) {
  const auto r = run_process(argv);
  if (r.exit_code != 0) throw Error(fmt::format("cannot run '{}': is it installed?", argv[0]));
  return r.out;
}

// Everything a plugin's bits depend on besides the -G parameters.
std::string cache_key(const std::string& pipeline, const std::string& gflags) {
  ContentHash h;
  h.add(fmt::format("abi {}", kRtlPluginAbi));
  h.add(pipeline);
  h.add(gflags);
  h.add(tool_version({"verilator", "--version"}));
  h.add(kCxxCompiler);
  h.add(__VERSION__);
  std::vector<fs::path> files;
  for (const char* dir : {"rtl", "sim", "model", "cmake"}) {
    for (const auto& e : fs::recursive_directory_iterator(kSourceDir / dir)) {
      if (e.is_regular_file()) files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    h.add(fs::relative(f, kSourceDir).string());
    h.add(read_file(f));
  }
  return h.hex();
}

std::string join_lines(std::string_view text) {
  std::string out;
  std::istringstream in{std::string(text)};
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    out += (out.empty() ? "" : " ") + line;
  }
  return out;
}

std::string last_lines(const std::string& text, int n) {
  std::size_t pos = text.size();
  for (int i = 0; i <= n && pos != std::string::npos && pos > 0; ++i) {
    pos = text.rfind('\n', pos - 1);
  }
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

std::optional<fs::path> find_built_in(const std::string& pipeline, const std::string& gflags) {
  std::ifstream in(kBuildDir / "rtl" / "manifest.tsv");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string p, g, path;
    if (std::getline(fields, p, '\t') && std::getline(fields, g, '\t') &&
        std::getline(fields, path) && p == pipeline && g == gflags && fs::exists(path)) {
      return fs::path(path);
    }
  }
  return std::nullopt;
}

fs::path build_plugin(const Config& cfg, const fs::path& dir, std::FILE* log) {
  const fs::path tmp = fs::path(dir.string() + fmt::format(".tmp.{}", getpid()));
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const fs::path log_path = tmp / "build.log";
  fs::copy_file(cfg.origin(), tmp / "config.toml");
  fmt::print(log, "phongsim: Verilating {} for {} (first use of these parameters; cached in {})\n",
             cfg.pipeline(), cfg.origin(), dir.string());
  std::fflush(log);
  const fs::path build = tmp / "build";
  const unsigned jobs = std::max(1U, std::thread::hardware_concurrency());
  const std::vector<std::vector<std::string>> steps = {
      {kCmake, "-S", (kSourceDir / "sim" / "cosim" / "rtl_build").string(), "-B", build.string(),
       "-DCMAKE_BUILD_TYPE=Release", std::string("-DCMAKE_CXX_COMPILER=") + kCxxCompiler,
       "-DPHONGSIM_SOURCE_DIR=" + kSourceDir.string(), "-DPHONGSIM_PIPELINE=" + cfg.pipeline(),
       "-DPHONGSIM_CONFIG=" + fs::absolute(cfg.origin()).string()},
      {kCmake, "--build", build.string(), "--parallel", std::to_string(jobs)},
  };
  for (const auto& step : steps) {
    if (run_process(step, log_path).exit_code != 0) {
      throw Error(fmt::format("building the RTL for {} failed; log: {} (last lines: {})",
                              cfg.origin(), log_path.string(),
                              join_lines(last_lines(read_file(log_path), 3))));
    }
  }
  fs::copy_file(build / "plugin.so", tmp / "plugin.so");
  fs::remove_all(build);
  std::error_code ec;
  fs::rename(tmp, dir, ec);  // atomic publish; if another process won the race, use theirs
  if (ec) fs::remove_all(tmp);
  return dir / "plugin.so";
}

}  // namespace

std::shared_ptr<RtlLibrary> RtlLibrary::open(const fs::path& path, const std::string& gflags) {
  std::shared_ptr<RtlLibrary> lib(new RtlLibrary());
  lib->path_ = path;
  lib->handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (lib->handle_ == nullptr) {
    throw Error(fmt::format("cannot load RTL plugin {}: {}", path.string(), dlerror()));
  }
  const auto abi = reinterpret_cast<RtlAbiFn>(dlsym(lib->handle_, "phongsim_rtl_abi"));
  const auto flags = reinterpret_cast<RtlGflagsFn>(dlsym(lib->handle_, "phongsim_rtl_gflags"));
  lib->create_ = reinterpret_cast<RtlCreateFn>(dlsym(lib->handle_, "phongsim_rtl_create"));
  if (abi == nullptr || flags == nullptr || lib->create_ == nullptr || abi() != kRtlPluginAbi) {
    throw Error(fmt::format("{} is not a phongsim RTL plugin of ABI {}; rebuild it", path.string(),
                            kRtlPluginAbi));
  }
  if (flags() != gflags) {
    throw Error(fmt::format("{} was Verilated with '{}', not '{}'; rebuild it", path.string(),
                            flags(), gflags));
  }
  return lib;
}

RtlLibrary::~RtlLibrary() {
  if (handle_ != nullptr) dlclose(handle_);
}

DutPtr RtlLibrary::create(const PipelineModel& model) {
  try {
    auto dut = create_(model.inputs(), model.outputs());
    return DutPtr(dut.release(), DutDeleter{shared_from_this()});
  } catch (const std::runtime_error& e) {
    throw Error(fmt::format("{}: {}", path_.string(), e.what()));
  }
}

std::string rtl_gflags(const Config& cfg) {
  std::string flags;
  for (const RtlParam& p : cfg.rtl_parameters()) {
    flags += fmt::format("{}-G{}={}", flags.empty() ? "" : " ", p.name, p.value);
  }
  return flags;
}

fs::path rtl_cache_dir() {
  if (const char* c = std::getenv("PHONGSIM_CACHE"); c != nullptr && *c != '\0') return c;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x != nullptr && *x != '\0') {
    return fs::path(x) / "phongsim";
  }
  const char* home = std::getenv("HOME");
  return fs::path(home != nullptr ? home : "/tmp") / ".cache" / "phongsim";
}

RtlPlugin locate_rtl(const Config& cfg, RtlBuild policy, std::FILE* log) {
  RtlPlugin plugin;
  plugin.gflags = rtl_gflags(cfg);
  if (auto built_in = find_built_in(cfg.pipeline(), plugin.gflags)) {
    plugin.path = *built_in;
    plugin.origin = "built in";
    return plugin;
  }
  const fs::path dir =
      rtl_cache_dir() / "rtl" / (cfg.pipeline() + "-" + cache_key(cfg.pipeline(), plugin.gflags));
  plugin.path = dir / "plugin.so";
  if (fs::exists(plugin.path)) {
    plugin.origin = "cached";
    return plugin;
  }
  if (policy == RtlBuild::never) {
    throw Error(
        fmt::format("the RTL for {} ({}) is not built yet; build it with: phongsim "
                    "build-rtl --pipeline {} --config {}",
                    cfg.origin(), plugin.gflags, cfg.pipeline(), cfg.origin()));
  }
  try {
    fs::create_directories(dir.parent_path());
  } catch (const fs::filesystem_error& e) {
    throw Error(fmt::format("cannot create the RTL cache {}: {}", dir.parent_path().string(),
                            e.code().message()));
  }
  plugin.path = build_plugin(cfg, dir, log);
  plugin.origin = "built now";
  return plugin;
}

}  // namespace phongsim
