// Verilator's lint output as findings (`phongsim lint`, docs/cosim.md): each `%Warning-CODE:` or
// `%Error[-CODE]:` line with its location, rule and message, the lines under it (source excerpt,
// instance, notes, hints) left to the text report; and a finding in the shapes CI systems read: a
// GCC-style line for log parsers, a GitHub Actions workflow command for annotations.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace phongsim {

enum class LintSeverity { warning, error };

struct LintFinding {
  std::optional<std::string> file;  // none when Verilator names no location
  std::optional<int> line;
  std::optional<int> column;
  std::optional<std::string> rule;  // Verilator's code (UNUSEDSIGNAL, WIDTH, ...); none: %Error
  LintSeverity severity = LintSeverity::error;
  std::string message;  // the finding's own line, without location and code

  bool operator==(const LintFinding&) const = default;
};

// "warning" or "error".
[[nodiscard]] std::string_view severity_name(LintSeverity severity);

// The findings in `output` (what Verilator printed, stdout and stderr together), in order.
// Verilator's closing lines ("%Error: Exiting due to 3 warning(s)", "%Error: Cannot continue")
// are no findings. A file is shown relative to `cwd` (an absolute path) when it lies under it,
// also through a symbolic link to its folder; else absolute (a relative one such as ../x.sv made
// absolute against `cwd`).
[[nodiscard]] std::vector<LintFinding> parse_lint_findings(std::string_view output,
                                                           const std::filesystem::path& cwd);

// GCC's shape: "file:line:col: severity: message [RULE]" (no column, rule or location: those parts
// left out).
[[nodiscard]] std::string gcc_line(const LintFinding& finding);

// A GitHub Actions workflow command: "::warning file=F,line=L,col=C,title=RULE::message"
// ("::error" for errors; parts without a value left out), with GitHub's escapes: %, CR and LF
// in the message, and also : and , in the properties.
[[nodiscard]] std::string github_line(const LintFinding& finding);

}  // namespace phongsim
