// The JSON documents phongsim's commands write (docs/json.md): one versioned schema, every
// document an object with "schema": "phongsim/1" and "command": "<the command>", the rest per
// command.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "base/output_file.h"
#include "sim/cosim/contract.h"

namespace phongsim::cli {

struct RtlIdentity;

inline constexpr std::string_view kJsonSchema = "phongsim/1";

// {"schema": "phongsim/1", "command": command}.
[[nodiscard]] nlohmann::ordered_json json_document(std::string_view command);

// A number, or null when it is not finite (JSON has no infinity or NaN).
[[nodiscard]] inline nlohmann::ordered_json json_number(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

// Per input contract clause, in order: {"clause": name, "out_of_contract": vectors that broke it
// first} (docs/json.md).
[[nodiscard]] nlohmann::ordered_json contract_json(const std::vector<std::string>& clauses,
                                                   const ContractCounts& counts);

// The RTL a verdict is about: {top, source, simulator, key, plugin, files, includes, include_dirs,
// defines, parameters, flags} (docs/json.md, runs[].rtl).
[[nodiscard]] nlohmann::ordered_json rtl_json(const RtlIdentity& rtl);

// A --json output opened up front (an unwritable path fails before the work); `-` is standard
// output. Empty path: none.
class JsonOutput {
 public:
  explicit JsonOutput(const std::string& path);
  [[nodiscard]] bool wanted() const { return file_.has_value(); }
  // True when the document goes to standard output: the command's text then goes to stderr.
  [[nodiscard]] bool to_stdout() const { return file_ && file_->is_stdout(); }
  // Where the command prints its human-readable report.
  [[nodiscard]] std::FILE* text() const { return to_stdout() ? stderr : stdout; }
  void write(const nlohmann::ordered_json& document);

 private:
  std::optional<OutputFile> file_;
};

}  // namespace phongsim::cli
