// phongsim's one error type: a one-line message for the user, no stack of causes.
#pragma once

#include <stdexcept>
#include <string>

namespace phongsim {

// Thrown for bad input (configuration, file, option) and for refused formats. The CLI prints
// `phongsim: error: <what()>` and exits with status 2; messages are single lines that name the
// offending thing (file and line, option, format).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace phongsim
