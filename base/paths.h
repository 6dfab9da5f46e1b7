// Where phongsim finds its own files (rtl/, configs/, data/, scripts/) and the tools it was
// configured with. One place, so that nothing else compiles a path in.
#pragma once

#include <filesystem>

namespace phongsim {

// The tree holding rtl/, configs/, data/ and scripts/ (the source tree phongsim was built from).
[[nodiscard]] const std::filesystem::path& data_root();

// The build tree phongsim was built in (its prebuilt RTL plugins live under it).
[[nodiscard]] const std::filesystem::path& build_root();

// Tools found when phongsim was configured.
[[nodiscard]] const char* cmake_program();
[[nodiscard]] const char* cxx_compiler();
// The Python that runs scripts/ at run time (Debian's /usr/bin/python3 when present: it has
// matplotlib for scripts/plot.py; a python3 earlier in PATH may be a separate install).
[[nodiscard]] const char* python_program();

}  // namespace phongsim
