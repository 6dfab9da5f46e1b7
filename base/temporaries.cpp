#include "base/temporaries.h"

#include <dirent.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <ucontext.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <ctime>
#include <random>

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

// Code loaded at run time whose crashes are reported by name (CrashRegion, CrashContext: a
// context has no ranges and matches any crash).
constexpr int kCrashSlots = 64;
constexpr int kCrashRanges = 4;
constexpr std::size_t kWhatMax = 1024;
struct CrashSlot {
  std::atomic<int> state{kFree};
  AddressRange ranges[kCrashRanges];
  int range_count = 0;
  bool any = false;  // a CrashContext
  char what[kWhatMax];
};
CrashSlot g_crash[kCrashSlots];

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

// Stops the helper programs, removes every registered temporary and ends the process.
[[noreturn]] void cleanup_and_exit(int status) {
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
  _exit(status);
}

void on_signal(int sig) { cleanup_and_exit(128 + sig); }

void write_text(const char* text) {
  std::size_t n = std::strlen(text);
  while (n > 0) {
    const ssize_t w = write(STDERR_FILENO, text, n);
    if (w <= 0) return;
    text += w;
    n -= static_cast<std::size_t>(w);
  }
}

const char* signal_name(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "SIGSEGV (invalid memory access)";
    case SIGBUS:
      return "SIGBUS (bus error: a file mapped in memory was truncated?)";
    case SIGILL:
      return "SIGILL (illegal instruction: built for another CPU?)";
    case SIGFPE:
      return "SIGFPE (arithmetic exception)";
    default:
      return "a signal";
  }
}

// The crash slot that accounts for a crash at these addresses, or -1.
int crash_owner(std::uintptr_t address, std::uintptr_t pc) {
  for (int i = 0; i < kCrashSlots; ++i) {
    CrashSlot& c = g_crash[i];
    if (c.state.load() != kPublished) continue;
    for (int r = 0; r < c.range_count; ++r) {
      const AddressRange& range = c.ranges[r];
      if ((address >= range.begin && address < range.end) ||
          (pc >= range.begin && pc < range.end)) {
        return i;
      }
    }
  }
  for (int i = 0; i < kCrashSlots; ++i) {
    if (g_crash[i].state.load() == kPublished && g_crash[i].any) return i;
  }
  return -1;
}

void on_crash(int sig, siginfo_t* info, void* context) {
  std::uintptr_t pc = 0;
#if defined(__x86_64__)
  pc = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.gregs[REG_RIP]);
#elif defined(__aarch64__)
  pc = static_cast<std::uintptr_t>(static_cast<ucontext_t*>(context)->uc_mcontext.pc);
#else
  (void)context;
#endif
  const int owner = crash_owner(reinterpret_cast<std::uintptr_t>(info->si_addr), pc);
  if (owner < 0) {  // phongsim's own: the default action, at the faulting instruction again
    signal(sig, SIG_DFL);
    return;
  }
  write_text("phongsim: error: ");
  write_text(signal_name(sig));
  write_text(" in ");
  write_text(g_crash[owner].what);
  write_text(
      ": the file is damaged, or built for another machine; rebuild it (phongsim build-rtl, or "
      "a run without --no-build for a cached one), and report the crash if a fresh build crashes "
      "too\n");
  cleanup_and_exit(2);
}

// A temporary younger than this may not be locked yet (created, lock not yet taken): left alone.
constexpr auto kLockGrace = std::chrono::seconds(2);

// Removes `path` if it is a stale temporary: a regular file or directory whose lock is free and
// that is older than kLockGrace. The lock is held while it is removed.
void remove_if_stale(const fs::path& path) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0 || !(S_ISREG(st.st_mode) || S_ISDIR(st.st_mode))) return;
  const auto changed = std::chrono::system_clock::time_point(
      std::chrono::seconds(st.st_ctim.tv_sec) + std::chrono::nanoseconds(st.st_ctim.tv_nsec));
  if (std::chrono::system_clock::now() - changed < kLockGrace) return;
  const int fd = open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC |
                                        (S_ISDIR(st.st_mode) ? O_DIRECTORY : 0));
  if (fd < 0) return;
  if (flock(fd, LOCK_EX | LOCK_NB) == 0) {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  close(fd);
}

// Removes `dir`'s stale temporaries; `prefix` non-empty: only names starting with it.
void sweep_dir(const fs::path& dir, std::string_view prefix) {
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!prefix.empty() && name.rfind(prefix, 0) != 0) continue;
    if (is_temporary_name(name)) remove_if_stale(it->path());
  }
}

constexpr std::string_view kBeside = ".phongsim-tmp-";
constexpr std::size_t kRandom = 6;  // the random XXXXXX of a name

bool random_part(std::string_view s) {
  return s.size() == kRandom && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
         });
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
  struct sigaction crash {};
  crash.sa_sigaction = on_crash;
  crash.sa_flags = SA_SIGINFO;
  sigfillset(&crash.sa_mask);
  for (const int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE}) sigaction(sig, &crash, nullptr);
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

OwnedTemp::OwnedTemp(const fs::path& prefix, Kind kind) {
  // Made like any new file or folder (0666 or 0777 less the umask), under a name nobody has:
  // O_EXCL and mkdir fail on one that exists, and another is drawn.
  static constexpr std::string_view kAlphabet =
      "0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  std::random_device random;
  int fd = -1, err = 0;
  std::string name;
  // The name is only known once it was made: register it, and lock it, after, with the signals
  // that would need the registration blocked in between.
  sigset_t all, old;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, &old);
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    name = prefix.string();
    for (std::size_t i = 0; i < kRandom; ++i) name += kAlphabet[random() % kAlphabet.size()];
    if (kind == Kind::file) {
      fd = open(name.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    } else if (mkdir(name.c_str(), 0777) == 0) {
      fd = open(name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (fd < 0) rmdir(name.c_str());
    }
    err = errno;
    if (fd < 0 && err != EEXIST) break;
  }
  if (fd >= 0) {
    try {
      registration_ = TempRegistration(name);
    } catch (...) {
      close(fd);
      (void)(kind == Kind::file ? unlink(name.c_str()) : rmdir(name.c_str()));
      sigprocmask(SIG_SETMASK, &old, nullptr);
      throw;
    }
    flock(fd, LOCK_EX);  // new and unique: nobody else holds it
  }
  sigprocmask(SIG_SETMASK, &old, nullptr);
  if (fd < 0) {
    Error e(fmt::format("cannot create a temporary {} {}: {}",
                        kind == Kind::file ? "file" : "directory", name, std::strerror(err)));
    errno = err;  // for callers that word the error themselves
    throw e;
  }
  path_ = name;
  fd_ = fd;
}

OwnedTemp::~OwnedTemp() {
  if (!path_.empty()) {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  if (fd_ >= 0) close(fd_);
}

void OwnedTemp::release() {
  path_.clear();
  registration_ = TempRegistration();
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

fs::path temp_prefix_beside(const fs::path& destination) {
  fs::path p = destination;
  p += kBeside;
  return p;
}

TempDir::TempDir(std::string_view what)
    : temp_(fs::temp_directory_path() / fmt::format("phongsim-{}-", what),
            OwnedTemp::Kind::directory) {}

ChildRegistration::ChildRegistration(pid_t pgid) {
  slot_ = claim(g_children, kChildSlots);
  if (slot_ < 0) return;  // more helpers than slots: they still get the terminal's SIGINT
  g_children[slot_].pgid = pgid;
  g_children[slot_].state.store(kPublished);
}

ChildRegistration::~ChildRegistration() {
  if (slot_ >= 0) g_children[slot_].state.store(kFree);
}

namespace {

int publish_crash_slot(std::span<const AddressRange> ranges, std::string_view what, bool any) {
  const int slot = claim(g_crash, kCrashSlots);
  if (slot < 0) return -1;  // more than 64 at once: such a crash keeps the default action
  CrashSlot& c = g_crash[slot];
  c.range_count = static_cast<int>(std::min<std::size_t>(ranges.size(), kCrashRanges));
  std::copy_n(ranges.begin(), c.range_count, c.ranges);
  c.any = any;
  const std::size_t n = std::min(what.size(), kWhatMax - 1);
  std::memcpy(c.what, what.data(), n);
  c.what[n] = '\0';
  c.state.store(kPublished);
  return slot;
}

}  // namespace

CrashRegion::CrashRegion(std::span<const AddressRange> ranges, std::string_view what)
    : slot_(publish_crash_slot(ranges, what, false)) {}

CrashRegion::~CrashRegion() {
  if (slot_ >= 0) g_crash[slot_].state.store(kFree);
}

CrashContext::CrashContext(std::string_view what) : slot_(publish_crash_slot({}, what, true)) {}

CrashContext::~CrashContext() {
  if (slot_ >= 0) g_crash[slot_].state.store(kFree);
}

bool is_temporary_name(std::string_view name) {
  if (const auto at = name.rfind(kBeside); at != std::string_view::npos && at > 0) {
    return random_part(name.substr(at + kBeside.size()));
  }
  if (name.rfind("phongsim-", 0) != 0) return false;
  const std::string_view rest = name.substr(9);
  const auto dash = rest.find('-');
  if (dash == std::string_view::npos) return false;
  const std::string_view what = rest.substr(0, dash);
  return (what == "synth" || what == "ports" || what == "search" || what == "out" ||
          what == "icarus" || what == "study") &&
         random_part(rest.substr(dash + 1));
}

void sweep_stale_temporaries(const std::vector<fs::path>& dirs) {
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  if (!ec) sweep_dir(tmp, "phongsim-");
  for (const fs::path& d : dirs) sweep_dir(d, "");
}

void sweep_stale_siblings(const fs::path& path) {
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  sweep_dir(dir, path.filename().string() + std::string(kBeside));
}

}  // namespace phongsim
