// RTL code coverage of co-simulations (`phongsim cosim --coverage DIR`, docs/cosim.md).
// A coverage plugin (RtlDesign::coverage: Verilator --coverage-line --coverage-toggle) makes
// DUTs that write their counts, one Verilator coverage.dat file each, into DIR/data when they
// are destroyed; merge_coverage() merges every file there — this run's and earlier runs' into
// the same DIR — counts the points (waived ones left out), lists the design's signals Verilator
// counts no toggles of, and writes DIR/coverage.info (lcov) and an HTML report in DIR/html
// (genhtml, Debian's lcov) whose figures are the counted ones.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/waveform.h"

namespace phongsim {

// Line points that cannot be reached, left out of the line figures: the points of `file` (the
// path's end, e.g. "rtl/common/fx_resize.sv") whose statements (Verilator's S field; a point
// without statements, an if's implicit else, is never waived) lie on the lines the RTL marks
// `marker`, in every instance whose hierarchy matches `hier` (an ECMAScript regex searched in
// Verilator's "top.lyon_top...." name), with the reason. The functional coverpoints name them
// (CoverpointSampler::line_waivers): an fx_resize saturation arm of a requantization whose
// saturation is waived.
//
// The RTL marks a line with the comment `// phongsim: waive MARKER` on it, and a region with
// `// phongsim: waive-begin MARKER` on its first line and `// phongsim: waive-end MARKER` on its
// last; the counting finds the marker in the file the points name, so a waiver follows its code
// when lines move and no C++ names a line. A marker missing from the file, on two lines, or a
// region without its end is an error naming the file and the marker (when the points are
// counted, wherever the design has a point in the file). The reason stays here, not in the
// marker: one marked line (fx_resize's saturation arm) serves every requantization, each waived
// for a reason its configuration's formats give.
struct LineWaiver {
  std::string hier;
  std::string file;
  std::string marker;
  std::string reason;
};

// A waiver of the saturation arm on `side` ("high": `wide > MaxV`, "low": `wide < MinV`) of
// rtl/common/fx_resize.sv (every fx_rq's requantization), marked there `saturate.high` and
// `saturate.low`, in the instances `hier`.
[[nodiscard]] LineWaiver fx_resize_saturation_waiver(std::string hier, std::string_view side,
                                                     std::string reason);

// A waiver of the user's (`cosim --waivers FILE`, docs/cosim.md "Waivers"), one line of the file:
//
//   SOURCE[:LINE[-LAST]] [/REGEX/] [@INSTANCE] REASON
//
// It leaves out the line and branch points of the source file SOURCE (its name or its path's
// end, matched at a '/' against the path Verilator read) that lie on the lines given: LINE..LAST,
// or every line whose text REGEX (ECMAScript, searched; `\/` for a '/') matches, or, with
// neither, the whole file. A point lies on the lines of its statements (Verilator's S: an if
// arm's or case item's body), a point without statements (an if's implicit else) on its `if`'s
// line. @INSTANCE (a regex searched in Verilator's hierarchy, "top.my_top.u_x") narrows it to
// some instances. A waiver that leaves out no point, and a waived point that was reached, are
// errors naming the waiver's FILE:LINE. The recommended REGEX is a marker like phongsim's own
// (LineWaiver) on the waived statement's line: `/phongsim: waive NAME\b/`.
struct UserWaiver {
  std::string origin;  // "waivers.txt:3": where it is written, for messages and the report
  std::string file;    // SOURCE
  int first_line = 0;  // LINE..LAST; 0: none given
  int last_line = 0;
  std::string pattern;   // REGEX; "": none given
  std::string instance;  // INSTANCE; "": every instance
  std::string reason;
  // "my_lirp.sv:61-62", "my_lirp.sv /default:/" or "my_lirp.sv", and " @INSTANCE".
  [[nodiscard]] std::string where() const;
};

// The waivers of a waiver file: one a line, `#` comment lines and blank lines skipped. Error
// "FILE:LINE: what is wrong" for the first line it cannot read (no reason, a bad range or
// regex), and for a file it cannot read.
[[nodiscard]] std::vector<UserWaiver> read_waivers(const std::filesystem::path& file);

// A line point a waiver left out: Verilator's file, statement lines ("78-79") and instance
// hierarchy, and the waiver's reason; `waiver` is the user's waiver ("waivers.txt:3"), "" for
// a configuration's (LineWaiver).
struct WaivedPoint {
  std::string file;
  std::string lines;
  std::string instance;
  std::string reason;
  std::string waiver;
};

// A signal of the design that Verilator counted no toggles of: its path in the waveform
// ("top.my_lirp.g_component[0].m0_q"; an unpacked array once, by its name), its bits and why
// ("in a generate or named block", "real", "longint", "300 bits, over the toggle limit (256)",
// "no toggle point (coverage_off?)").
struct UncountedSignal {
  std::string path;
  std::uint64_t bits = 0;
  std::string why;
};

struct CoverageSummary {
  std::uint64_t files = 0;          // coverage.dat files merged
  std::uint64_t line_points = 0;    // Verilator's line and branch points (statements, if/case arms)
  std::uint64_t line_hit = 0;       // ... reached at least once
  std::uint64_t line_waived = 0;    // points a waiver leaves out of the two above
  std::vector<WaivedPoint> waived;  // ... each, in key order
  std::uint64_t toggle_points = 0;  // one per signal bit (Verilator counts its changes)
  std::uint64_t toggle_hit = 0;     // ... that changed at least once
  // With the design's signals given (CoverageInputs::signals) and toggles measured: the signals
  // without a toggle point, in waveform order; their bits are in neither toggle figure.
  bool signals_checked = false;
  std::vector<UncountedSignal> not_toggled;
  [[nodiscard]] std::uint64_t not_toggled_bits() const;
  [[nodiscard]] double line_percent() const;    // 100 * hit / points; 0 without points
  [[nodiscard]] double toggle_percent() const;  // likewise
  // False when the data has no toggle point: every run had a line-only build
  // (--no-toggle-coverage), so toggles were not measured (not 0 %).
  [[nodiscard]] bool toggles_measured() const { return toggle_points > 0; }
};

// What the counting takes besides the points.
struct CoverageInputs {
  std::vector<LineWaiver> line_waivers;  // the configurations' (CoverpointSampler::line_waivers)
  std::vector<UserWaiver> user_waivers;  // cosim --waivers
  // The design's signals (probe_design(), of every configuration run); empty: not checked.
  std::vector<WaveSignal> signals;
  // Source paths the points name that are elsewhere now (moved_sources()): the points are
  // counted, matched and reported at the new paths.
  std::map<std::string, std::string> moved;
};

// The prefix a run's DUTs write their files under (RtlLibrary::create): DIR/data/<time>-<pid>-,
// unique per phongsim process. Creates DIR/data.
[[nodiscard]] std::string coverage_prefix(const std::filesystem::path& dir);

// What a coverage plugin's design declares, learnt before any run from one DUT of it: its
// coverage points (with the counts of a reset) and the signals of its waveform (FST).
struct DesignProbe {
  std::map<std::string, std::uint64_t> points;
  std::vector<WaveSignal> signals;
  std::map<std::string, std::string> moved;  // moved_sources(), for the caller to fill
};
// `make(prefix)` makes a DUT of the coverage plugin writing its counts under `prefix`
// (rtl_duts); the probe's go to a temporary folder, never into a coverage DIR.
[[nodiscard]] DesignProbe probe_design(const std::function<DutPtr(const std::string&)>& make);

// The paths of a plugin's sources as Verilator named them in its coverage points, when the
// design has them elsewhere now, to where: a plugin is keyed by content, so a copy of the same
// files in another folder (another checkout, a CI workspace) runs the plugin built from the
// first, whose points name the first's paths (which may be gone). Each source the plugin
// records (its files and includes) whose content the design now has at another path.
[[nodiscard]] std::map<std::string, std::string> moved_sources(const RtlPlugin& plugin,
                                                               const RtlDesign& design);
// `points` with their source paths (f) moved (old path -> new path).
[[nodiscard]] std::map<std::string, std::uint64_t> relocated(
    const std::map<std::string, std::uint64_t>& points,
    const std::map<std::string, std::string>& moved);

// Error, as count_coverage_points gives it, for the first of the user's waivers that matches no
// line or branch point of `points` (a design's, probe_design): a stale waiver stops a command
// before its runs.
void check_waivers(const std::map<std::string, std::uint64_t>& points,
                   std::span<const UserWaiver> waivers);

// Counts points (Verilator coverage keys, "\x01name\x02value..." with page, f, l, S, h, o, and
// their counts summed over files) into a summary, files 0: merge_coverage()'s counting. Error
// when a point a waiver matches was reached, and when a user's waiver matches no point.
[[nodiscard]] CoverageSummary count_coverage_points(
    const std::map<std::string, std::uint64_t>& points, const CoverageInputs& inputs);
[[nodiscard]] CoverageSummary count_coverage_points(
    const std::map<std::string, std::uint64_t>& points, std::span<const LineWaiver> waivers);

// The lcov file of the points (DIR/coverage.info): per source file, a branch record (BRDA) per
// line or branch point, the lines of their statements (DA: a line's count is the smallest of
// the points on it), and a function record (FN, FNDA) per toggle point named after its signal
// bit ("top.my_lirp.valid_q[3]"); waived points (as counted) left out. genhtml's Branches and
// Functions figures are then the summary's line and toggle figures.
[[nodiscard]] std::string lcov_info(const std::map<std::string, std::uint64_t>& points,
                                    const CoverageInputs& inputs);

// Merges DIR/data/*.dat and counts the points, each point's count summed over the files, and
// writes DIR/coverage.info (lcov_info) and DIR/html (genhtml; both replaced). Error when there
// is no file, genhtml fails, a waived point was reached (its reason is wrong) or a user's waiver
// matches no point (stale): then nothing is written.
CoverageSummary merge_coverage(const std::filesystem::path& dir, const CoverageInputs& inputs);
CoverageSummary merge_coverage(const std::filesystem::path& dir,
                               std::span<const LineWaiver> waivers = {});

}  // namespace phongsim
