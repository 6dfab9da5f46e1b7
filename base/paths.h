// Where phongsim finds its own files, and the tools it was configured with. One place, so that
// nothing else compiles a path in.
//
// phongsim's files live in one tree, found relative to the running program, never compiled in:
//   <tree>/share/phongsim/    rtl/, configs/, data/, scripts/, sweeps/, cmake/   (data_root())
//   <tree>/include/phongsim/  the C++ headers RTL plugins compile with          (include_root())
// An install has the program in <prefix>/bin and the tree at <prefix>; a build tree is its own
// tree (CMake links share/ and include/ there to the sources at configure time; the program is
// in <build>, tests in <build>/tests). The tree is the first of: $PHONGSIM_ROOT; the closest
// ancestor (up to four levels) of the running executable, or of the shared object holding this
// code (a Python module), that has share/phongsim/configs; the same for `phongsim` on PATH.
#pragma once

#include <filesystem>

namespace phongsim {

// <tree>/share/phongsim. Error naming what was searched when there is no tree.
[[nodiscard]] const std::filesystem::path& data_root();

// <tree>/include/phongsim.
[[nodiscard]] const std::filesystem::path& include_root();

// The phongsim executable of the tree (<tree>/bin/phongsim, or <build>/phongsim).
[[nodiscard]] std::filesystem::path phongsim_program();

// Where RTL plugins and synthesis results are cached unless $PHONGSIM_CACHE says otherwise:
// <build>/rtl-cache in a build tree (it has a CMakeCache.txt), else $XDG_CACHE_HOME/phongsim
// (~/.cache/phongsim).
[[nodiscard]] std::filesystem::path default_cache_dir();

// Tools found when phongsim was configured.
[[nodiscard]] const char* cmake_program();
[[nodiscard]] const char* cxx_compiler();
// The Python that runs scripts/ at run time (Debian's /usr/bin/python3 when present: it has
// matplotlib for scripts/plot.py; a python3 earlier in PATH may be a separate install).
[[nodiscard]] const char* python_program();

}  // namespace phongsim
