// Small file helpers shared by the plugin cache, synthesis, configurations, scenes, meshes and
// sweeps: a whole file as text (the one read_file of the tree), and the content hash their caches
// and the plugins' records of their sources are keyed by (file_util.cpp).
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

// SHA-256 (OpenSSL) over a sequence of fields: what a verdict rests on (RTL plugin keys, the
// files a plugin was built from, the synthesis cache, sweep plans), so an adversary cannot make
// two contents share a key. Each field is framed by its length, so ("ab","c") and ("a","bc")
// differ.
class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;
  void add(std::string_view bytes);
  // 64 hex digits. The hash stays usable: more fields may be added after.
  [[nodiscard]] std::string hex() const;

 private:
  void* ctx_;  // EVP_MD_CTX
};

// The SHA-256 of one file's bytes, 64 hex digits (what `sha256sum` prints); Error when it cannot
// be read.
[[nodiscard]] std::string file_hash(const std::filesystem::path& path);

}  // namespace phongsim
