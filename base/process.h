// Running helper programs (python for figures, cmake for on-demand Verilator builds, Yosys,
// nextpnr) without a shell, so paths with spaces or quotes need no escaping. Each runs in a
// process group of its own that phongsim stops when a signal ends it (base/temporaries.h).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace phongsim {

struct ProcessResult {
  int exit_code = -1;  // -1 when the program could not be started or was killed
  std::string out;     // stdout and stderr together, when captured
};

// Runs argv[0] (searched in PATH) with the given arguments, in the folder `cwd` (default: this
// process's). Output goes to `log` when given, otherwise it is captured into the result.
ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::filesystem::path& log = {},
                          const std::filesystem::path& cwd = {});

// Called about five times a second while a helper program runs — its argv, the seconds since it
// started, and its log (empty when captured) — and once more with seconds < 0 when it ended.
// The CLI installs one that shows progress on a terminal; nothing is called when none is
// installed.
using WaitHook = std::function<void(const std::vector<std::string>& argv, double seconds,
                                    const std::filesystem::path& log)>;
void set_wait_hook(WaitHook hook);

}  // namespace phongsim
