#include "base/temporaries.h"

#include <dirent.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>

#include "base/error.h"

namespace phongsim {
namespace fs = std::filesystem;

namespace {

// ---- The registry, read by the signal handler ----
// Fixed slots, so the handler touches no allocator: a slot is claimed (1), filled, then
// published (2); the handler acts only on published slots.
constexpr int kFree = 0, kClaimed = 1, kPublished = 2;
constexpr int kPathSlots = 1024;  // phongsim study: two scene files per scene
constexpr int kChildSlots = 32;
constexpr std::size_t kPathMax = 4096;

struct PathSlot {
  std::atomic<int> state{kFree};
  char path[kPathMax];
};
struct ChildSlot {
  std::atomic<int> state{kFree};
  pid_t pgid = 0;
};
PathSlot g_paths[kPathSlots];
ChildSlot g_children[kChildSlots];

template <class Slot>
int claim(Slot* slots, int count) {
  for (int i = 0; i < count; ++i) {
    int expected = kFree;
    if (slots[i].state.compare_exchange_strong(expected, kClaimed)) return i;
  }
  return -1;
}

// ---- Async-signal-safe removal: system calls only, no allocation ----

struct LinuxDirent64 {
  ino64_t d_ino;
  off64_t d_off;
  unsigned short d_reclen;
  unsigned char d_type;
  char d_name[];
};

// Removes `name` in directory `dirfd` (a file, or a directory tree up to `depth` levels deep).
void remove_at(int dirfd, const char* name, int depth) {
  if (unlinkat(dirfd, name, 0) == 0 || errno == ENOENT) return;
  if (depth <= 0) return;
  const int fd = openat(dirfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) char buf[4096];
  for (;;) {
    const long n = syscall(SYS_getdents64, fd, buf, sizeof buf);
    if (n <= 0) break;
    for (long at = 0; at < n;) {
      const auto* d = reinterpret_cast<const LinuxDirent64*>(buf + at);
      at += d->d_reclen;
      const char* entry = d->d_name;
      if (entry[0] == '.' && (entry[1] == '\0' || (entry[1] == '.' && entry[2] == '\0'))) continue;
      remove_at(fd, entry, depth - 1);
    }
  }
  close(fd);
  unlinkat(dirfd, name, AT_REMOVEDIR);
}

void sleep_ms(long ms) {
  timespec t{ms / 1000, (ms % 1000) * 1000000};
  while (nanosleep(&t, &t) != 0 && errno == EINTR) {
  }
}

void on_signal(int sig) {
  // Stop the helper programs first, so that nothing writes into a temporary being removed.
  bool any = false;
  for (ChildSlot& c : g_children) {
    if (c.state.load() == kPublished) {
      kill(-c.pgid, SIGTERM);
      any = true;
    }
  }
  for (int waited = 0; any && waited < 2000; waited += 20) {
    any = false;
    for (ChildSlot& c : g_children) {
      if (c.state.load() != kPublished) continue;
      if (waitpid(c.pgid, nullptr, WNOHANG) == 0) {
        any = true;
      } else {
        c.state.store(kFree);
      }
    }
    if (any) sleep_ms(20);
  }
  for (ChildSlot& c : g_children) {
    if (c.state.load() == kPublished) kill(-c.pgid, SIGKILL);
  }
  for (PathSlot& p : g_paths) {
    if (p.state.load() == kPublished) remove_at(AT_FDCWD, p.path, 16);
  }
  _exit(128 + sig);
}

std::string_view digits_prefix(std::string_view s) {
  std::size_t n = 0;
  while (n < s.size() && s[n] >= '0' && s[n] <= '9') ++n;
  return s.substr(0, n);
}

long to_pid(std::string_view digits) {
  if (digits.empty() || digits.size() > 9) return -1;
  long pid = 0;
  for (const char c : digits) pid = pid * 10 + (c - '0');
  return pid > 0 ? pid : -1;
}

// Removes `dir`'s entries whose owner is gone; `prefix` non-empty: only names starting with it.
void sweep_dir(const fs::path& dir, std::string_view prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!prefix.empty() && name.rfind(prefix, 0) != 0) continue;
    const long owner = temp_owner(name);
    if (owner < 0 || process_alive(owner)) continue;
    std::error_code rm;
    fs::remove_all(it->path(), rm);
  }
}

}  // namespace

void install_signal_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigfillset(&sa.sa_mask);  // one handler at a time
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
    struct sigaction old {};
    sigaction(sig, nullptr, &old);
    if ((sig == SIGINT || sig == SIGHUP) && old.sa_handler == SIG_IGN) continue;
    sigaction(sig, &sa, nullptr);
  }
  // A file-size limit (ulimit -f) makes writes fail with EFBIG, reported like a full disk,
  // instead of killing phongsim with its temporaries in place.
  std::signal(SIGXFSZ, SIG_IGN);
}

TempRegistration::TempRegistration(const fs::path& path) {
  const std::string text = fs::absolute(path).string();
  if (text.size() >= kPathMax) {
    throw Error(fmt::format("{}: the path is too long for a temporary", text));
  }
  slot_ = claim(g_paths, kPathSlots);
  if (slot_ < 0) throw Error("too many temporary files at once (at most 1024)");
  std::memcpy(g_paths[slot_].path, text.c_str(), text.size() + 1);
  g_paths[slot_].state.store(kPublished);
}

TempRegistration::~TempRegistration() {
  if (slot_ >= 0) g_paths[slot_].state.store(kFree);
}

TempRegistration::TempRegistration(TempRegistration&& other) noexcept : slot_(other.slot_) {
  other.slot_ = -1;
}

TempRegistration& TempRegistration::operator=(TempRegistration&& other) noexcept {
  if (this != &other) {
    if (slot_ >= 0) g_paths[slot_].state.store(kFree);
    slot_ = other.slot_;
    other.slot_ = -1;
  }
  return *this;
}

TempDir::TempDir(std::string_view what) {
  std::string pattern =
      (fs::temp_directory_path() / fmt::format("phongsim-{}-{}-XXXXXX", what, getpid())).string();
  // The name is only known once mkdtemp made it: register the pattern's directory entry after,
  // with the signals that would need it blocked in between.
  sigset_t all, old;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, &old);
  const bool made = mkdtemp(pattern.data()) != nullptr;
  const int err = errno;
  if (made) {
    try {
      registration_ = TempRegistration(pattern);
    } catch (...) {
      rmdir(pattern.c_str());
      sigprocmask(SIG_SETMASK, &old, nullptr);
      throw;
    }
  }
  sigprocmask(SIG_SETMASK, &old, nullptr);
  if (!made) {
    throw Error(
        fmt::format("cannot create a temporary directory {}: {}", pattern, std::strerror(err)));
  }
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

ChildRegistration::ChildRegistration(pid_t pgid) {
  slot_ = claim(g_children, kChildSlots);
  if (slot_ < 0) return;  // more helpers than slots: they still get the terminal's SIGINT
  g_children[slot_].pgid = pgid;
  g_children[slot_].state.store(kPublished);
}

ChildRegistration::~ChildRegistration() {
  if (slot_ >= 0) g_children[slot_].state.store(kFree);
}

std::string temp_suffix() { return fmt::format(".tmp.{}", getpid()); }

bool process_alive(long pid) {
  return pid > 0 && (kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
}

long temp_owner(std::string_view name) {
  if (name.rfind("phongsim-", 0) == 0) {
    const std::string_view rest = name.substr(9);
    const auto dash = rest.find('-');
    if (dash == std::string_view::npos) return -1;
    const std::string_view what = rest.substr(0, dash);
    if (what != "synth" && what != "ports" && what != "search" && what != "out") return -1;
    const std::string_view tail = rest.substr(dash + 1);
    const std::string_view digits = digits_prefix(tail);
    if (digits.size() != tail.size() && tail[digits.size()] != '-') return -1;
    return to_pid(digits);
  }
  const auto at = name.rfind(".tmp.");
  if (at == std::string_view::npos) return -1;
  std::string_view tail = name.substr(at + 5);
  const std::string_view digits = digits_prefix(tail);
  tail.remove_prefix(digits.size());
  if (!tail.empty() && (tail[0] != '.' || digits_prefix(tail.substr(1)).size() != tail.size() - 1 ||
                        tail.size() == 1)) {
    return -1;
  }
  return to_pid(digits);
}

void sweep_stale_temporaries(const std::vector<fs::path>& dirs) {
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  if (!ec) sweep_dir(tmp, "phongsim-");
  for (const fs::path& d : dirs) sweep_dir(d, "");
}

void sweep_stale_siblings(const fs::path& path) {
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  sweep_dir(dir, path.filename().string() + ".tmp.");
}

}  // namespace phongsim
