// RTL code coverage of co-simulations (`phongsim cosim --coverage DIR`, docs/verification.md).
// A coverage plugin (RtlDesign::coverage: Verilator --coverage-line --coverage-toggle) makes
// DUTs that write their counts, one Verilator coverage.dat file each, into DIR/data when they
// are destroyed; merge_coverage() merges every file there — this run's and earlier runs' into
// the same DIR — into DIR/coverage.info (lcov, by verilator_coverage) and an HTML report in
// DIR/html (genhtml, Debian's lcov), and counts the points.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace phongsim {

// Line points that cannot be reached, left out of the line figures: the points of `file` (the
// path's end, e.g. "rtl/common/fx_resize.sv") whose statements start at lines first..last
// (Verilator's S field: an if's arm starts at its first statement; a point without statements
// is never waived) in every instance whose
// hierarchy matches `hier` (an ECMAScript regex searched in Verilator's "top.lyon_top...." name),
// with the reason. The functional coverpoints name them (CoverpointSampler::line_waivers): an
// fx_resize saturation arm of a requantization whose saturation is waived.
struct LineWaiver {
  std::string hier;
  std::string file;
  int first_line = 0;
  int last_line = 0;
  std::string reason;
};

// A line point a waiver left out: Verilator's file, statement lines ("78-79") and instance
// hierarchy, and the waiver's reason.
struct WaivedPoint {
  std::string file;
  std::string lines;
  std::string instance;
  std::string reason;
};

struct CoverageSummary {
  std::uint64_t files = 0;          // coverage.dat files merged
  std::uint64_t line_points = 0;    // Verilator's line and branch points (statements, if/case arms)
  std::uint64_t line_hit = 0;       // ... reached at least once
  std::uint64_t line_waived = 0;    // points a LineWaiver leaves out of the two above
  std::vector<WaivedPoint> waived;  // ... each, in key order
  std::uint64_t toggle_points = 0;  // one per signal bit and direction (0->1, 1->0)
  std::uint64_t toggle_hit = 0;
  [[nodiscard]] double line_percent() const;    // 100 * hit / points; 0 without points
  [[nodiscard]] double toggle_percent() const;  // likewise
  // False when the data has no toggle point: every run had a line-only build
  // (--no-toggle-coverage), so toggles were not measured (not 0 %).
  [[nodiscard]] bool toggles_measured() const { return toggle_points > 0; }
};

// The prefix a run's DUTs write their files under (RtlLibrary::create): DIR/data/<time>-<pid>-,
// unique per phongsim process. Creates DIR/data.
[[nodiscard]] std::string coverage_prefix(const std::filesystem::path& dir);

// Counts points (Verilator coverage keys, "\x01name\x02value..." with page, f, l, S, h, and
// their counts summed over files) into a summary, files 0: merge_coverage()'s counting. Error
// when a point a waiver matches was reached.
[[nodiscard]] CoverageSummary count_coverage_points(
    const std::map<std::string, std::uint64_t>& points, std::span<const LineWaiver> waivers);

// Merges DIR/data/*.dat into DIR/coverage.info and DIR/html (replacing both) and counts the
// points, each point's count summed over the files, the line points `waivers` match left out (the
// lcov file and the report keep them). Error when there is no file, a tool fails, or a waived
// point was reached (its reason is wrong).
CoverageSummary merge_coverage(const std::filesystem::path& dir,
                               std::span<const LineWaiver> waivers = {});

}  // namespace phongsim
