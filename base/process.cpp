#include "base/process.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <optional>

#include "base/temporaries.h"

extern char** environ;

namespace phongsim {
namespace {

WaitHook& wait_hook() {
  static WaitHook hook;
  return hook;
}

}  // namespace

void set_wait_hook(WaitHook hook) { wait_hook() = std::move(hook); }

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                          const std::filesystem::path& cwd) {
  ProcessResult result;
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  int pipe_fds[2] = {-1, -1};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (log.empty()) {
    if (pipe2(pipe_fds, O_CLOEXEC) != 0) return result;
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDERR_FILENO);
  } else {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  // The child leads a process group of its own, so that phongsim's signal handler can stop it
  // and everything it starts (base/temporaries.h); signals stay blocked until it is registered.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setpgroup(&attr, 0);
  sigset_t all, old;
  sigfillset(&all);
  sigprocmask(SIG_BLOCK, &all, &old);
  posix_spawnattr_setsigmask(&attr, &old);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, &attr, args.data(), environ);
  std::optional<ChildRegistration> child;
  if (rc == 0) child.emplace(pid);
  sigprocmask(SIG_SETMASK, &old, nullptr);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  if (log.empty()) close(pipe_fds[1]);
  if (rc != 0) {
    if (log.empty()) close(pipe_fds[0]);
    result.out = "cannot start " + argv[0];
    return result;
  }
  const auto start = std::chrono::steady_clock::now();
  const auto tick = [&] {
    if (wait_hook()) {
      wait_hook()(argv,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                  log);
    }
  };
  if (log.empty()) {
    std::array<char, 4096> buf{};
    for (;;) {
      pollfd p{pipe_fds[0], POLLIN, 0};
      const int ready = poll(&p, 1, 200);
      if (ready == 0) {
        tick();
        continue;
      }
      if (ready < 0 && errno == EINTR) continue;
      const ssize_t n = read(pipe_fds[0], buf.data(), buf.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      result.out.append(buf.data(), static_cast<std::size_t>(n));
    }
    close(pipe_fds[0]);
  }
  int status = 0;
  for (;;) {
    const pid_t w = waitpid(pid, &status, log.empty() ? 0 : WNOHANG);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) break;
    if (w == 0) {
      tick();
      usleep(200000);
    }
  }
  if (wait_hook()) wait_hook()(argv, -1, log);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace phongsim
