#include "base/paths.h"

namespace phongsim {

const std::filesystem::path& data_root() {
  static const std::filesystem::path p = PHONGSIM_SOURCE_DIR;
  return p;
}

const std::filesystem::path& build_root() {
  static const std::filesystem::path p = PHONGSIM_BUILD_DIR;
  return p;
}

const char* cmake_program() { return PHONGSIM_CMAKE; }
const char* cxx_compiler() { return PHONGSIM_CXX_COMPILER; }
const char* python_program() { return PHONGSIM_PYTHON; }

}  // namespace phongsim
