#include "base/paths.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "base/error.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

bool is_tree(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "share" / "phongsim" / "configs", ec);
}

// The closest ancestor of `file` (up to four levels up) that is a tree.
std::optional<fs::path> tree_above(const fs::path& file) {
  std::error_code ec;
  fs::path dir = fs::weakly_canonical(file, ec).parent_path();
  for (int up = 0; up < 5 && !dir.empty(); ++up, dir = dir.parent_path()) {
    if (is_tree(dir)) return dir;
    if (dir == dir.root_path()) break;
  }
  return std::nullopt;
}

std::optional<fs::path> phongsim_on_path() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::istringstream dirs(path);
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / "phongsim";
    if (access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

fs::path find_tree() {
  if (const char* root = std::getenv("PHONGSIM_ROOT"); root != nullptr && *root != '\0') {
    if (!is_tree(root)) {
      throw Error(fmt::format("PHONGSIM_ROOT={} has no share/phongsim/configs", root));
    }
    return root;
  }
  std::vector<fs::path> starts;
  std::error_code ec;
  starts.push_back(fs::read_symlink("/proc/self/exe", ec));
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&find_tree), &info) != 0 && info.dli_fname != nullptr) {
    starts.emplace_back(info.dli_fname);
  }
  if (const auto p = phongsim_on_path()) starts.push_back(*p);
  for (const fs::path& start : starts) {
    if (start.empty()) continue;
    if (const auto tree = tree_above(start)) return *tree;
  }
  throw Error(
      "cannot find phongsim's files (share/phongsim/configs) near this program or a phongsim "
      "on PATH; set PHONGSIM_ROOT to the install prefix or the build directory");
}

const fs::path& tree() {
  static const fs::path t = find_tree();
  return t;
}

}  // namespace

const fs::path& data_root() {
  static const fs::path p = tree() / "share" / "phongsim";
  return p;
}

const fs::path& include_root() {
  static const fs::path p = tree() / "include" / "phongsim";
  return p;
}

fs::path phongsim_program() {
  const fs::path installed = tree() / "bin" / "phongsim";
  return fs::exists(installed) ? installed : tree() / "phongsim";
}

fs::path default_cache_dir() {
  if (fs::exists(tree() / "CMakeCache.txt")) return tree() / "rtl-cache";
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x != nullptr && *x != '\0') {
    return fs::path(x) / "phongsim";
  }
  const char* home = std::getenv("HOME");
  return fs::path(home != nullptr && *home != '\0' ? home : "/tmp") / ".cache" / "phongsim";
}

const char* cmake_program() { return PHONGSIM_CMAKE; }
const char* cxx_compiler() { return PHONGSIM_CXX_COMPILER; }
const char* python_program() { return PHONGSIM_PYTHON; }

}  // namespace phongsim
