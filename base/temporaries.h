// Temporary files and directories phongsim must not leave behind, and the helper programs it
// starts. While a temporary exists it is registered, so that SIGINT, SIGTERM, SIGHUP and SIGPIPE
// stop the registered helper programs, remove every registered temporary and end phongsim with
// status 128 + the signal (130 for SIGINT, 143 for SIGTERM). What a process killed outright
// (SIGKILL, a power cut) leaves behind is swept away when phongsim next starts
// (sweep_stale_temporaries): every temporary's name carries the pid of its owner —
// `<destination>.tmp.<pid>[.<n>]` beside what it becomes, `phongsim-<what>-<pid>-<suffix>` in the
// temp directory — and a temporary whose owner no longer runs is stale.
#pragma once

#include <sys/types.h>

#include <filesystem>
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

// A new directory `<temp dir>/phongsim-<what>-<pid>-XXXXXX`, registered, removed with everything
// in it when destroyed. Throws Error when it cannot be created.
class TempDir {
 public:
  explicit TempDir(std::string_view what);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  TempRegistration registration_;
  std::filesystem::path path_;
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

// ".tmp.<pid>": the suffix of this process's temporaries beside their destinations.
[[nodiscard]] std::string temp_suffix();

// Whether a process with this pid exists.
[[nodiscard]] bool process_alive(long pid);

// The pid of the owner named in a temporary's file name: `<anything>.tmp.<pid>[.<n>]`, or
// `phongsim-<what>-<pid>[-<anything>]` with <what> one of synth, ports, search, out; -1 for any
// other name.
[[nodiscard]] long temp_owner(std::string_view name);

// Removes the stale temporaries (temp_owner() names a process that no longer runs) directly in
// the temp directory and in each of `dirs` (not below them). Symbolic links are removed, never
// followed; what cannot be removed (another user's) is left alone. Housekeeping: never fails.
void sweep_stale_temporaries(const std::vector<std::filesystem::path>& dirs);

// The stale temporaries of one destination: `<path>.tmp.<pid>*` beside it.
void sweep_stale_siblings(const std::filesystem::path& path);

}  // namespace phongsim
