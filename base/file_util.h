// Small file helpers shared by the plugin cache, synthesis, meshes and sweeps: a whole file as
// text, and the content hash their caches are keyed by.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>

namespace phongsim {

// The file's bytes ("" when it cannot be read: callers that care check existence first).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
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
