#include "base/output_file.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <optional>
#include <set>
#include <system_error>

#include "base/error.h"
#include "base/file_util.h"

namespace phongsim {
namespace fs = std::filesystem;

namespace {

// Destinations claimed by this process's open outputs: no two outputs write one place.
std::set<std::string>& claims() {
  static std::set<std::string> c;
  return c;
}

// The descriptor a path stands for: `-`, /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N.
std::optional<int> descriptor_of(const fs::path& p) {
  const std::string s = p.string();
  if (s == "-" || s == "/dev/stdout") return 1;
  if (s == "/dev/stderr") return 2;
  for (const std::string& prefix : {std::string("/dev/fd/"), std::string("/proc/self/fd/"),
                                    fmt::format("/proc/{}/fd/", getpid())}) {
    if (s.rfind(prefix, 0) != 0) continue;
    const std::string n = s.substr(prefix.size());
    if (n.empty() || n.size() > 6 || n.find_first_not_of("0123456789") != std::string::npos) {
      return std::nullopt;
    }
    return std::stoi(n);
  }
  return std::nullopt;
}

// `p` with its symbolic links followed (a dangling one to where it points), as far as they go.
fs::path follow_links(fs::path p) {
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) break;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) break;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p;
}

std::string claim_key(const fs::path& target) {
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(fs::absolute(target), ec);
  return (ec ? fs::absolute(target) : canon).lexically_normal().string();
}

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

OutputFile::OutputFile(fs::path path) : path_(std::move(path)) {
  if (path_.empty()) throw Error("an output file name is empty");
  const auto fail = [&](std::string_view why) {
    return Error(fmt::format("cannot write {}: {}", path_.string(), why));
  };
  mode_t keep_mode = 0;
  bool existing = false;
  fs::path p = path_;
  for (int hops = 0;; ++hops) {
    if (const auto fd = descriptor_of(p)) {
      const int flags = fcntl(*fd, F_GETFL);
      if (flags < 0) throw fail(fmt::format("descriptor {} is not open", *fd));
      if ((flags & O_ACCMODE) == O_RDONLY) {
        throw fail(fmt::format("descriptor {} is open for reading only", *fd));
      }
      fd_ = *fd;
      break;
    }
    struct stat st {};
    if (lstat(p.c_str(), &st) != 0) {
      if (errno != ENOENT) throw fail(std::strerror(errno));
      target_ = p;  // a new file (fopen below says when its directory is missing)
      break;
    }
    if (S_ISLNK(st.st_mode)) {
      if (hops == 40) throw fail("too many levels of symbolic links");
      std::error_code ec;
      const fs::path link = fs::read_symlink(p, ec);
      if (ec) throw fail(ec.message());
      p = link.is_absolute() ? link : p.parent_path() / link;
      continue;
    }
    if (S_ISREG(st.st_mode)) {
      target_ = p;
      keep_mode = st.st_mode & 07777;
      existing = true;
    } else if (S_ISDIR(st.st_mode)) {
      throw fail("it is a directory");
    } else if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) {
      if (access(p.c_str(), W_OK) != 0) throw fail(std::strerror(errno));
      target_ = p;
      in_place_ = true;
    } else if (S_ISBLK(st.st_mode)) {
      throw fail("it is a block device (phongsim does not write those)");
    } else {
      throw fail("it is a socket (phongsim does not write those)");
    }
    break;
  }

  // One output per destination (a character device such as /dev/null may take several).
  struct stat st {};
  const bool chardev = in_place_ && stat(target_.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
  if (!chardev) {
    const std::string key = fd_ >= 0 ? fmt::format("fd:{}", fd_) : claim_key(target_);
    if (claims().contains(key)) throw fail("it is also another output of this command");
    claims().insert(key);
    claim_ = key;
  }

  const auto release_claim = [&] {
    if (!claim_.empty()) claims().erase(claim_);
  };
  if (fd_ == 1 || fd_ == 2) {
    file_ = fd_ == 1 ? stdout : stderr;
    return;
  }
  int fd = -1;
  if (fd_ >= 0) {
    fd = fcntl(fd_, F_DUPFD_CLOEXEC, 3);
  } else if (in_place_) {
    fd = open(target_.c_str(), O_WRONLY | O_CLOEXEC);  // a FIFO waits for its reader here
  } else {
    sweep_stale_siblings(target_);
    try {
      temp_.emplace(temp_prefix_beside(target_), OwnedTemp::Kind::file);
    } catch (const Error&) {
      const int err = errno;
      release_claim();
      throw fail(std::strerror(err));
    }
    if (existing) (void)fchmod(temp_->fd(), keep_mode);
    fd = fcntl(temp_->fd(), F_DUPFD_CLOEXEC, 3);  // the temporary keeps its own, locked
  }
  if (fd >= 0) file_ = fdopen(fd, "wb");
  if (file_ == nullptr) {
    const int err = errno;
    if (fd >= 0) close(fd);
    temp_.reset();
    release_claim();
    throw fail(std::strerror(err));
  }
  owns_file_ = true;
}

OutputFile::~OutputFile() {
  if (owns_file_ && file_ != nullptr) std::fclose(file_);
  temp_.reset();  // removes an uncommitted temporary
  if (!claim_.empty()) claims().erase(claim_);
}

const fs::path& OutputFile::temp_path() {
  if (!temp_) {  // a stream: a file to copy into it on commit
    temp_.emplace(fs::temp_directory_path() / "phongsim-out-", OwnedTemp::Kind::file);
  }
  return temp_->path();
}

void OutputFile::commit() {
  const auto fail = [&](int err) {
    return Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(err)));
  };
  if (committed_) return;
  if (stream() && temp_) {  // a writer used temp_path(): copy that file into the stream
    const int in = open(temp_->path().c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) throw fail(errno);
    std::fflush(file_);
    char buf[65536];
    bool copied = true;
    while (copied) {
      const ssize_t n = read(in, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        copied = n == 0;
        break;
      }
      copied = write_all(fileno(file_), buf, static_cast<std::size_t>(n));
    }
    const int err = errno;
    close(in);
    if (!copied) throw fail(err);
  }
  const bool ok = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  if (!ok) throw fail(errno);
  if (owns_file_) {
    // fsync would make the rename durable across a crash; not worth its cost here: a crash
    // leaves the old file or the new one, and the stale temporary is swept later.
    const int closed = std::fclose(file_);
    file_ = nullptr;
    if (closed != 0) throw fail(errno);
  }
  if (!stream()) {
    if (std::rename(temp_->path().c_str(), target_.c_str()) != 0) throw fail(errno);
    temp_->release();
  }
  temp_.reset();
  committed_ = true;
}

bool same_destination(const fs::path& a, const fs::path& b) {
  const auto fd_a = descriptor_of(a), fd_b = descriptor_of(b);
  if (fd_a || fd_b) return fd_a == fd_b;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec)) return true;
  return claim_key(follow_links(a)) == claim_key(follow_links(b));
}

void check_distinct(const std::vector<std::pair<std::string, fs::path>>& named) {
  for (std::size_t i = 0; i < named.size(); ++i) {
    for (std::size_t j = i + 1; j < named.size(); ++j) {
      if (named[i].second.empty() || named[j].second.empty()) continue;
      if (same_destination(named[i].second, named[j].second)) {
        throw Error(fmt::format("{} and {} name the same file {}", named[i].first, named[j].first,
                                named[j].second.string()));
      }
    }
  }
}

void check_outputs(const std::vector<std::pair<std::string, fs::path>>& outputs,
                   const std::vector<std::pair<std::string, fs::path>>& inputs) {
  check_distinct(outputs);
  for (const auto& [out_name, out] : outputs) {
    for (const auto& [in_name, in] : inputs) {
      if (out.empty() || in.empty() || !same_destination(out, in)) continue;
      throw Error(
          fmt::format("{} {} is also an input ({} {}): an output never replaces what the "
                      "command reads",
                      out_name, out.string(), in_name, in.string()));
    }
  }
}

// ---- OutputSet ----

namespace {

constexpr std::string_view kManifest = "manifest.json";

nlohmann::json read_manifest(const fs::path& dir) {
  const fs::path m = dir / kManifest;
  std::error_code ec;
  if (!fs::is_regular_file(m, ec)) return nlohmann::json::object();
  try {
    nlohmann::json j = nlohmann::json::parse(read_file(m));
    if (j.is_object() && j.contains("sets") && j["sets"].is_object()) return j["sets"];
  } catch (const nlohmann::json::exception&) {
  }
  return nlohmann::json::object();  // unreadable: trust nothing in it
}

// A relative path inside the set's directory: no root, no "..".
bool inside(const fs::path& relative) {
  if (relative.empty() || relative.is_absolute() || relative.has_root_name()) return false;
  for (const auto& part : relative) {
    if (part == "..") return false;
  }
  return true;
}

}  // namespace

OutputSet::OutputSet(fs::path dir, std::string set, std::vector<std::string> replaces)
    : dir_(std::move(dir)), set_(std::move(set)), replaces_(std::move(replaces)) {
  if (dir_.empty()) throw Error("an output directory name is empty");
  std::error_code ec;
  const auto status = fs::status(dir_, ec);
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw Error(fmt::format("cannot write {}: it exists and is not a directory", dir_.string()));
  }
  // The missing ancestors, outermost first; each registered before it is made.
  std::vector<fs::path> missing;
  for (fs::path p = fs::absolute(dir_).lexically_normal(); !p.empty() && !fs::exists(p, ec);
       p = p.parent_path()) {
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  for (const fs::path& p : missing) {
    created_registrations_.emplace_back(p);
    if (mkdir(p.c_str(), 0777) != 0 && errno != EEXIST) {
      const int err = errno;
      created_registrations_.pop_back();
      for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) rmdir(it->c_str());
      throw Error(fmt::format("cannot create {}: {}", dir_.string(), std::strerror(err)));
    }
    created_dirs_.push_back(p);
  }
  if (access(dir_.c_str(), W_OK) != 0) {
    const int err = errno;
    for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) rmdir(it->c_str());
    throw Error(fmt::format("cannot write {}: {}", dir_.string(), std::strerror(err)));
  }
}

OutputSet::~OutputSet() {
  files_.clear();  // removes the temporaries of an uncommitted set
  if (!committed_) {
    for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) rmdir(it->c_str());
  }
}

OutputFile& OutputSet::add(const fs::path& relative) {
  const fs::path rel = relative.lexically_normal();
  if (!inside(rel)) {
    throw Error(
        fmt::format("{}: an output of a set must lie inside {}", relative.string(), dir_.string()));
  }
  if (rel == kManifest) {
    throw Error(fmt::format("{}: the name is the set's manifest", (dir_ / rel).string()));
  }
  for (const auto& f : files_) {
    if (f.first == rel) {
      throw Error(fmt::format("cannot write {}: it is already an output of this command",
                              (dir_ / rel).string()));
    }
  }
  // Sub-directories of the set, made (and registered) as needed.
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = (dir_ / rel).parent_path(); !fs::exists(p, ec); p = p.parent_path()) {
    missing.insert(missing.begin(), p);
  }
  for (const fs::path& p : missing) {
    created_registrations_.emplace_back(p);
    if (mkdir(p.c_str(), 0777) != 0 && errno != EEXIST) {
      throw Error(fmt::format("cannot create {}: {}", p.string(), std::strerror(errno)));
    }
    created_dirs_.push_back(p);
  }
  files_.emplace_back(rel, std::make_unique<OutputFile>(dir_ / rel));
  return *files_.back().second;
}

std::vector<fs::path> OutputSet::files() const {
  std::vector<fs::path> v;
  for (const auto& f : files_) v.push_back(f.first);
  return v;
}

void OutputSet::commit() {
  // Every file is complete before any is moved into place.
  for (auto& f : files_) {
    std::FILE* file = f.second->get();
    if (std::fflush(file) != 0 || std::ferror(file) != 0) {
      throw Error(
          fmt::format("cannot write {}: {}", f.second->path().string(), std::strerror(errno)));
    }
  }
  for (auto& f : files_) f.second->commit();

  nlohmann::json sets = read_manifest(dir_);
  std::set<std::string> now;
  for (const auto& f : files_) now.insert(f.first.generic_string());
  std::set<std::string> kept;  // listed by sets this one does not replace
  for (const auto& [name, list] : sets.items()) {
    if (std::find(replaces_.begin(), replaces_.end(), name) != replaces_.end()) continue;
    for (const auto& f : list) {
      if (f.is_string()) kept.insert(f.get<std::string>());
    }
  }
  for (const std::string& name : replaces_) {
    if (!sets.contains(name)) continue;
    for (const auto& f : sets[name]) {
      if (!f.is_string()) continue;
      const std::string old = f.get<std::string>();
      if (now.contains(old) || kept.contains(old) || !inside(old) || old == kManifest) continue;
      std::error_code ec;
      fs::remove(dir_ / old, ec);
    }
    sets.erase(name);
  }
  std::vector<std::string> ordered;
  for (const auto& f : files_) ordered.push_back(f.first.generic_string());
  sets[set_] = ordered;
  OutputFile manifest(dir_ / kManifest);
  const nlohmann::json j{{"schema", "phongsim/1"}, {"sets", sets}};
  std::fputs((j.dump(2) + "\n").c_str(), manifest.get());
  manifest.commit();
  committed_ = true;
  created_registrations_.clear();
}

std::vector<fs::path> manifest_files(const fs::path& dir, std::string_view set) {
  const nlohmann::json sets = read_manifest(dir);
  std::vector<fs::path> v;
  const std::string key(set);
  if (!sets.contains(key) || !sets[key].is_array()) return v;
  for (const auto& f : sets[key]) {
    if (f.is_string()) v.emplace_back(f.get<std::string>());
  }
  return v;
}

}  // namespace phongsim
