// Running helper programs (python for -G parameters, cmake for on-demand Verilator builds)
// without a shell, so paths with spaces or quotes need no escaping.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace phongsim {

struct ProcessResult {
  int exit_code = -1;  // -1 when the program could not be started or was killed
  std::string out;     // stdout and stderr together, when captured
};

// Runs argv[0] (searched in PATH) with the given arguments. Output goes to `log` when given,
// otherwise it is captured into the result.
ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::filesystem::path& log = {});

}  // namespace phongsim
