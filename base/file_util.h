// Small file helpers shared by the plugin cache, synthesis, configurations, scenes, meshes and
// sweeps: a whole file as text (the one read_file of the tree), and the content hash their caches
// are keyed by.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

#include "base/error.h"

namespace phongsim {

// The file's bytes ("" when it cannot be read: callers that care check existence first).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The file's bytes; Error("<path>: cannot read <what>") when it cannot be opened or read (a
// directory included), e.g. read_file(path, "scene file").
inline std::string read_file(const std::filesystem::path& path, std::string_view what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(fmt::format("{}: cannot read {} (it is a directory)", path.string(), what));
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  if (in) s << in.rdbuf();
  if (!in || in.bad()) throw Error(fmt::format("{}: cannot read {}", path.string(), what));
  return s.str();
}

// FNV-1a, 64 bit, over a sequence of fields: a cache key, not a security boundary.
class ContentHash {
 public:
  void add(std::string_view bytes) {
    for (const unsigned char c : bytes) {
      h_ ^= c;
      h_ *= 0x100000001b3ULL;
    }
    h_ ^= 0xff;  // field separator, so ("ab","c") and ("a","bc") differ
    h_ *= 0x100000001b3ULL;
  }
  [[nodiscard]] std::string hex() const { return fmt::format("{:016x}", h_); }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

}  // namespace phongsim
