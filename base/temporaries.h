// Temporary files and directories phongsim must not leave behind, and the helper programs it
// starts. While a temporary exists it is registered, so that SIGINT, SIGTERM, SIGHUP and SIGPIPE
// stop the registered helper programs, remove every registered temporary and end phongsim with
// status 128 + the signal (130 for SIGINT, 143 for SIGTERM).
//
// What a process killed outright (SIGKILL, a power cut) leaves behind is swept away when phongsim
// next starts (sweep_stale_temporaries). A temporary is recognised by its name alone —
// `<destination>.phongsim-tmp-XXXXXX` beside what it becomes, `phongsim-<what>-XXXXXX` in the
// temp directory, XXXXXX random — and its owner holds an flock on it for as
// long as it lives: a sweep removes only a temporary it can lock, so the live temporaries of a
// process in another PID namespace (two CI containers sharing a cache volume) stay, and nothing
// named otherwise is ever touched.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace phongsim {

// Installs the signal handlers (main() calls it first). SIGINT and SIGHUP stay ignored when they
// were ignored at start (a background job of a non-interactive shell), as shells expect.
void install_signal_cleanup();

// While alive, `path` (a file, or a directory with everything in it) is removed if a signal ends
// the process. Register before creating the path. Construction, move and destruction never
// create or remove anything. Throws Error when more than 1024 temporaries are registered at once.
class TempRegistration {
 public:
  TempRegistration() = default;
  explicit TempRegistration(const std::filesystem::path& path);
  ~TempRegistration();
  TempRegistration(TempRegistration&& other) noexcept;
  TempRegistration& operator=(TempRegistration&& other) noexcept;
  TempRegistration(const TempRegistration&) = delete;
  TempRegistration& operator=(const TempRegistration&) = delete;

 private:
  int slot_ = -1;
};

// A temporary file or directory of this process: created as `<prefix>XXXXXX` (XXXXXX random, a
// name nobody has; permissions as any new file or folder), registered, and locked (flock) while
// this object lives. Destroyed, it is removed (with everything in it) unless release()d — after
// it was renamed into place. Throws Error (errno set) when it cannot be created.
class OwnedTemp {
 public:
  enum class Kind { file, directory };
  OwnedTemp(const std::filesystem::path& prefix, Kind kind);
  ~OwnedTemp();
  OwnedTemp(const OwnedTemp&) = delete;
  OwnedTemp& operator=(const OwnedTemp&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  // The open file (read/write) of a Kind::file temporary; the lock's descriptor of a directory.
  [[nodiscard]] int fd() const { return fd_; }
  // Keeps the path (it has been renamed into place) and drops the lock.
  void release();

 private:
  TempRegistration registration_;
  std::filesystem::path path_;
  int fd_ = -1;
};

// "<destination>.phongsim-tmp-": the prefix of a temporary beside `destination`.
[[nodiscard]] std::filesystem::path temp_prefix_beside(const std::filesystem::path& destination);

// A new directory `<temp dir>/phongsim-<what>-XXXXXX` (an OwnedTemp), removed with everything in
// it when destroyed. `what` is one of the names sweep_stale_temporaries knows (is_temporary_name).
class TempDir {
 public:
  explicit TempDir(std::string_view what);
  [[nodiscard]] const std::filesystem::path& path() const { return temp_.path(); }

 private:
  OwnedTemp temp_;
};

// While alive, the process group `pgid` (a helper program started in a group of its own) gets
// SIGTERM when a signal ends phongsim — and SIGKILL if it has not ended 2 s later.
class ChildRegistration {
 public:
  explicit ChildRegistration(pid_t pgid);
  ~ChildRegistration();
  ChildRegistration(const ChildRegistration&) = delete;
  ChildRegistration& operator=(const ChildRegistration&) = delete;

 private:
  int slot_ = -1;
};

// Crashes (SIGSEGV, SIGBUS, SIGILL, SIGFPE) in code phongsim loads at run time — an RTL plugin —
// end phongsim with one line naming that code and status 2, its temporaries removed and its
// helper programs stopped. A crash elsewhere keeps the default action (phongsim's own bug: a
// core dump). install_signal_cleanup() installs the handler.
struct AddressRange {
  std::uintptr_t begin = 0;
  std::uintptr_t end = 0;  // one past the last byte
};

// While alive, a crash whose faulting address or instruction lies in one of `ranges` is
// reported as a crash in `what` ("the RTL plugin /c/lyon-.../plugin.so"). At most 4 ranges.
class CrashRegion {
 public:
  CrashRegion(std::span<const AddressRange> ranges, std::string_view what);
  ~CrashRegion();
  CrashRegion(const CrashRegion&) = delete;
  CrashRegion& operator=(const CrashRegion&) = delete;

 private:
  int slot_ = -1;
};

// While alive, any crash (of the thread that made it or another) is reported as a crash in
// `what` ("loading the RTL plugin ..."): for code that has no address range yet.
class CrashContext {
 public:
  explicit CrashContext(std::string_view what);
  ~CrashContext();
  CrashContext(const CrashContext&) = delete;
  CrashContext& operator=(const CrashContext&) = delete;

 private:
  int slot_ = -1;
};

// Whether `name` is a temporary's name: `<anything>.phongsim-tmp-XXXXXX`, or
// `phongsim-<what>-XXXXXX` with <what> one of synth, ports, search, out, icarus, study.
[[nodiscard]] bool is_temporary_name(std::string_view name);

// Removes the stale temporaries — a temporary's name, a regular file or directory (never a
// symbolic link or anything else), its lock free, and more than a few seconds old — directly in
// the temp directory and in each of `dirs` (not below them). What cannot be removed (another
// user's) is left alone. Housekeeping: never fails.
void sweep_stale_temporaries(const std::vector<std::filesystem::path>& dirs);

// The stale temporaries of one destination: `<path>.phongsim-tmp-XXXXXX` beside it.
void sweep_stale_siblings(const std::filesystem::path& path);

}  // namespace phongsim
