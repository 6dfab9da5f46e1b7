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

// Thrown when the design under test disagrees with the model outside a co-simulation (a frame
// rendered through RTL): a verdict, not bad input. The CLI prints `phongsim: FAIL: <what()>` and
// exits with status 1, as a failing co-simulation does.
class DesignFailure : public Error {
 public:
  explicit DesignFailure(const std::string& message) : Error(message) {}
};

}  // namespace phongsim
