// RTL code coverage of co-simulations (`phongsim cosim --coverage DIR`, docs/verification.md).
// A coverage plugin (RtlDesign::coverage: Verilator --coverage-line --coverage-toggle) makes
// DUTs that write their counts, one Verilator coverage.dat file each, into DIR/data when they
// are destroyed; merge_coverage() merges every file there — this run's and earlier runs' into
// the same DIR — into DIR/coverage.info (lcov, by verilator_coverage) and an HTML report in
// DIR/html (genhtml, Debian's lcov), and counts the points.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace phongsim {

struct CoverageSummary {
  std::uint64_t files = 0;          // coverage.dat files merged
  std::uint64_t line_points = 0;    // Verilator's line and branch points (statements, if/case arms)
  std::uint64_t line_hit = 0;       // ... reached at least once
  std::uint64_t toggle_points = 0;  // one per signal bit and direction (0->1, 1->0)
  std::uint64_t toggle_hit = 0;
  [[nodiscard]] double line_percent() const;    // 100 * hit / points; 0 without points
  [[nodiscard]] double toggle_percent() const;  // likewise
};

// The prefix a run's DUTs write their files under (RtlLibrary::create): DIR/data/<time>-<pid>-,
// unique per phongsim process. Creates DIR/data.
[[nodiscard]] std::string coverage_prefix(const std::filesystem::path& dir);

// Merges DIR/data/*.dat into DIR/coverage.info and DIR/html (replacing both) and counts the
// points, each point's count summed over the files. Error when there is no file or a tool fails.
CoverageSummary merge_coverage(const std::filesystem::path& dir);

}  // namespace phongsim
