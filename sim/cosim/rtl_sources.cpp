#include "sim/cosim/rtl_sources.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "base/file_util.h"

namespace phongsim {
namespace fs = std::filesystem;

std::optional<FileStamp> file_stamp(const fs::path& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return std::nullopt;
  const auto ns = [](const timespec& t) {
    return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
  };
  return FileStamp{static_cast<std::uintmax_t>(st.st_size), static_cast<std::uintmax_t>(st.st_ino),
                   ns(st.st_ctim), ns(st.st_mtim)};
}

HashedFile hash_file(const fs::path& path) {
  const fs::path abs = fs::absolute(path).lexically_normal();
  const auto before = file_stamp(abs);
  std::error_code ec;
  if (!before || !fs::is_regular_file(abs, ec)) {
    throw Error(fmt::format("{}: no such RTL file", path.string()));
  }
  HashedFile f{abs, file_hash(abs), *before};
  if (file_stamp(abs) != before) {
    throw Error(
        fmt::format("{} changed while phongsim read it (is it being written?)", path.string()));
  }
  return f;
}

std::vector<fs::path> rtl_include_dirs(std::span<const fs::path> given,
                                       std::span<const fs::path> files) {
  std::vector<fs::path> dirs;
  const auto add = [&](const fs::path& d) {
    if (std::find(dirs.begin(), dirs.end(), d) == dirs.end()) dirs.push_back(d);
  };
  for (const fs::path& d : given) add(fs::absolute(d).lexically_normal());
  for (const fs::path& f : files) add(fs::absolute(f).lexically_normal().parent_path());
  return dirs;
}

std::map<fs::path, FileStamp> verilator_read(const fs::path& mdir, const std::string& prefix,
                                             const fs::path& cwd) {
  const fs::path dat = mdir / (prefix + "__verFiles.dat");
  std::ifstream in(dat);
  if (!in)
    throw Error(fmt::format("{}: Verilator wrote no list of the files it read", dat.string()));
  // Source lines: S <size> <inode> <ctime s> <ctime ns> <mtime s> <mtime ns> "<path>"
  std::map<fs::path, FileStamp> read;
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("S ")) continue;
    std::istringstream words(line.substr(2));
    std::uintmax_t size = 0, inode = 0;
    std::int64_t cs = 0, cns = 0, ms = 0, mns = 0;
    words >> size >> inode >> cs >> cns >> ms >> mns;
    const auto open = line.find('"'), close = line.rfind('"');
    if (!words || open == std::string::npos || close <= open) {
      throw Error(fmt::format("{}: unreadable line '{}'", dat.string(), line));
    }
    fs::path p = line.substr(open + 1, close - open - 1);
    // Verilator's own executable (its version is part of every key), and names it records but
    // could not stat (it lists the part of a path with a space before the space): no content.
    if (p.filename().string().starts_with("verilator_bin") || (inode == 0 && size == 0)) continue;
    if (p.is_relative()) p = cwd / p;
    read[p.lexically_normal()] =
        FileStamp{size, inode, cs * 1'000'000'000 + cns, ms * 1'000'000'000 + mns};
  }
  return read;
}

IncludedFile locate_include(const HashedFile& file, std::span<const fs::path> dirs) {
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const fs::path rel = file.path.lexically_relative(dirs[k]);
    if (!rel.empty() && *rel.begin() != "..") return {static_cast<int>(k), rel, file.hash};
  }
  return {-1, file.path, file.hash};
}

std::optional<fs::path> resolve_include(const IncludedFile& include,
                                        std::span<const fs::path> dirs) {
  if (include.dir < 0) return include.rel;
  if (static_cast<std::size_t>(include.dir) >= dirs.size()) return std::nullopt;
  // Verilator tries the name as written, then with .v and .sv appended: a file of any of those
  // names in an earlier folder would be read instead.
  std::vector<fs::path> names{include.rel};
  for (const char* ext : {".v", ".sv"}) {
    if (include.rel.extension() == ext) names.push_back(fs::path(include.rel).replace_extension());
  }
  for (std::size_t j = 0; j < static_cast<std::size_t>(include.dir); ++j) {
    for (const fs::path& n : names) {
      for (const char* ext : {"", ".v", ".sv"}) {
        std::error_code ec;
        if (fs::exists(dirs[j] / (n.string() + ext), ec)) return std::nullopt;
      }
    }
  }
  return (dirs[static_cast<std::size_t>(include.dir)] / include.rel).lexically_normal();
}

}  // namespace phongsim
