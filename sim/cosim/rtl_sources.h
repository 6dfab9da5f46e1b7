// What an RTL plugin was compiled from, file by file, and how phongsim knows it: every file
// Verilator read (the design's files and what they `include) with its content hash, hashed so
// that the hash provably describes what Verilator read. A file's stamp (size, inode, change and
// modification times) changes with every write; phongsim stamps a file, hashes it and stamps it
// again before a build, and Verilator records the stamp of every file it read after it read them
// (<prefix>__verFiles.dat). Equal stamps mean Verilator read the bytes that were hashed: a file
// saved, checked out or reverted during a build is detected, never recorded under the content it
// had before (rtl_plugin.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace phongsim {

struct FileStamp {
  std::uintmax_t size = 0;
  std::uintmax_t inode = 0;
  std::int64_t changed_ns = 0;   // ctime: every write or metadata change moves it forward
  std::int64_t modified_ns = 0;  // mtime
  bool operator==(const FileStamp&) const = default;
};

// The file's stamp, or nothing when it cannot be stat()ed.
[[nodiscard]] std::optional<FileStamp> file_stamp(const std::filesystem::path& path);

// A file's content hash (SHA-256) and the stamp it had all the while it was hashed.
struct HashedFile {
  std::filesystem::path path;  // absolute, normalized
  std::string hash;
  FileStamp stamp;
};

// Stamps, hashes and stamps `path` again; Error when it is missing, unreadable, or changed while
// it was hashed ("is being written").
[[nodiscard]] HashedFile hash_file(const std::filesystem::path& path);

// The folders an `include is searched in: the `given` include folders (+incdir+, -I), then the
// folders of `files`; absolute, in order, each once. phongsim's checks and builds give Verilator,
// Icarus and Yosys these as -I, and run Verilator in an empty folder, so that every tool finds
// the same files wherever phongsim runs.
[[nodiscard]] std::vector<std::filesystem::path> rtl_include_dirs(
    std::span<const std::filesystem::path> given, std::span<const std::filesystem::path> files);

// What one Verilator run read (its `mdir`/<prefix>__verFiles.dat): every source's absolute path
// (relative ones resolved against `cwd`, the folder it ran in) and the stamp Verilator saw,
// Verilator's own files left out. Error when the file is missing or malformed.
[[nodiscard]] std::map<std::filesystem::path, FileStamp> verilator_read(
    const std::filesystem::path& mdir, const std::string& prefix, const std::filesystem::path& cwd);

// An `include a design read, located so that the same design elsewhere (another checkout) finds
// its own copy: below include folder `dir` (an index into rtl_include_dirs) at `rel`, or, for
// dir -1, at the absolute path `rel`.
struct IncludedFile {
  int dir = -1;
  std::filesystem::path rel;
  std::string hash;
};

// `file` (an absolute path Verilator read) as an IncludedFile of a design with `dirs`: in the
// first folder that holds it.
[[nodiscard]] IncludedFile locate_include(const HashedFile& file,
                                          std::span<const std::filesystem::path> dirs);

// Where the recorded include is for a design with `dirs`: its path, or nothing when the folder
// is gone or an earlier folder now holds a file of that name (Verilator would read that one).
[[nodiscard]] std::optional<std::filesystem::path> resolve_include(
    const IncludedFile& include, std::span<const std::filesystem::path> dirs);

}  // namespace phongsim
