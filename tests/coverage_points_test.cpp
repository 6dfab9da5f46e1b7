// The counting of RTL coverage points (sim/cosim/coverage.h) on Verilator-format keys: the user's
// waivers (their file, what they leave out, stale and reached ones refused), phongsim's own
// waivers found by their markers in the RTL (following moved lines; a missing marker refused),
// the signals Verilator counts no toggles of, and the lcov file whose figures are the counted
// ones.
#include "sim/cosim/coverage.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "base/file_util.h"
#include "sim/cosim/coverpoints.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace phongsim {
namespace {

using Points = std::map<std::string, std::uint64_t>;

// A line or branch point of `file`: its line (l), its statements (S, "" for none), instance (h).
std::string line_key(const std::string& file, int line, const std::string& statements,
                     const std::string& hier, const std::string& page = "v_branch/m") {
  std::string key = fmt::format(
      "\x01"
      "f\x02{}\x01"
      "l\x02{}\x01"
      "page\x02{}",
      file, line, page);
  if (!statements.empty())
    key += fmt::format(
        "\x01"
        "S\x02{}",
        statements);
  return key + fmt::format(
                   "\x01"
                   "h\x02{}",
                   hier);
}

std::string toggle_key(const std::string& file, int line, const std::string& bit,
                       const std::string& hier) {
  return fmt::format(
      "\x01"
      "f\x02{}\x01"
      "l\x02{}\x01"
      "page\x02v_toggle/m\x01"
      "o\x02{}\x01"
      "h\x02{}",
      file, line, bit, hier);
}

// A source file of ten lines; line 4 holds `default: q = lo;`, line 7 `q = hi;`.
const char* const kSource =
    "module m;\n"             // 1
    "  case (r)\n"            // 2
    "    0: q = a;\n"         // 3
    "    default: q = lo;\n"  // 4
    "  endcase\n"             // 5
    "  if (x) begin\n"        // 6
    "    q = hi;\n"           // 7
    "    q = hj;\n"           // 8
    "  end\n"                 // 9
    "endmodule\n";            // 10

TEST(UserWaivers, FileFormat) {
  const testing::TempDir tmp;
  const auto file = tmp.Write("w.txt",
                              "# comment\n"
                              "\n"
                              "  my.sv:12 the reason, with # and : in it\n"
                              "src/my.sv:3-5 @u_a\\.u_b why\n"
                              "./my.sv /a\\/b [0-9]+/ @^top\\.t$ slash\n"
                              "my.sv whole file\n");
  const std::vector<UserWaiver> w = read_waivers(file);
  ASSERT_EQ(w.size(), 4U);
  EXPECT_EQ(w[0].origin, file.string() + ":3");
  EXPECT_EQ(w[0].file, "my.sv");
  EXPECT_EQ(w[0].first_line, 12);
  EXPECT_EQ(w[0].last_line, 12);
  EXPECT_EQ(w[0].reason, "the reason, with # and : in it");
  EXPECT_EQ(w[1].file, "src/my.sv");
  EXPECT_EQ(w[1].last_line, 5);
  EXPECT_EQ(w[1].instance, "u_a\\.u_b");
  EXPECT_EQ(w[1].where(), "src/my.sv:3-5 @u_a\\.u_b");
  EXPECT_EQ(w[2].file, "my.sv");
  EXPECT_EQ(w[2].pattern, "a/b [0-9]+");
  EXPECT_EQ(w[2].instance, "^top\\.t$");
  EXPECT_EQ(w[2].reason, "slash");
  EXPECT_EQ(w[3].first_line, 0);
  EXPECT_TRUE(w[3].pattern.empty());
  EXPECT_EQ(w[3].reason, "whole file");
  // Every line it cannot read is one error naming the file and line.
  const auto error = [&](const std::string& line) {
    return testing::ErrorOf([&] { (void)read_waivers(tmp.Write("bad.txt", "# x\n" + line)); });
  };
  const std::string at = tmp.path().string() + "/bad.txt:2: ";
  EXPECT_EQ(error("my.sv:12\n"), at + "a waiver needs a reason (why the points cannot be reached)");
  EXPECT_EQ(error("my.sv /x/\n").rfind(at + "a waiver needs a reason", 0), 0U);
  EXPECT_EQ(error("my.sv:0 r\n").rfind(at + "'my.sv:0' is not SOURCE:LINE", 0), 0U);
  EXPECT_EQ(error("my.sv:9-3 r\n").rfind(at + "'my.sv:9-3' is not SOURCE:LINE", 0), 0U);
  EXPECT_EQ(error("my.sv:x r\n").rfind(at + "'my.sv:x' is not SOURCE:LINE", 0), 0U);
  EXPECT_EQ(error("my.sv /abc r\n").rfind(at + "the /REGEX/ has no closing '/'", 0), 0U);
  EXPECT_EQ(error("my.sv /(/ r\n").rfind(at + "the pattern /(/ is not a regular expression", 0),
            0U);
  EXPECT_EQ(error("my.sv:3 /x/ r\n").rfind(at + "give lines (SOURCE:LINE) or a /REGEX/", 0), 0U);
  EXPECT_EQ(error("/x/ r\n").rfind(at + "a waiver starts with the source file", 0), 0U);
  EXPECT_EQ(error("my.sv @ r\n").rfind(at + "an empty @INSTANCE", 0), 0U);
  EXPECT_NE(testing::ErrorOf([&] {
              (void)read_waivers(tmp.path() / "none.txt");
            }).find("none.txt: cannot read waiver file"),
            std::string::npos);
}

TEST(UserWaivers, LeaveOutPointsOnTheirLines) {
  const testing::TempDir tmp;
  const std::string src = tmp.Write("my.sv", kSource).string();
  const Points points{{line_key(src, 3, "3", "top.t"), 5},    // case 0: reached
                      {line_key(src, 4, "4", "top.t"), 0},    // default arm
                      {line_key(src, 6, "7-8", "top.t"), 0},  // if arm: statements 7-8
                      {line_key(src, 6, "", "top.t"), 3},     // implicit else: the if's line
                      {line_key(src, 6, "7-8", "top.t.u_other"), 0},           // another instance
                      {line_key("/elsewhere/my.sv.bak", 4, "4", "top.t"), 0},  // another file
                      {toggle_key(src, 7, "q[0]", "top.t"), 0}};
  CoverageInputs in;
  in.user_waivers = {{"w:1", "my.sv", 0, 0, "default:\\s+q = lo", "", "no default"},
                     {"w:2", "my.sv", 8, 8, "", "^top\\.t$", "if never taken"}};
  const CoverageSummary s = count_coverage_points(points, in);
  EXPECT_EQ(s.line_waived, 2U);  // line 4 (regex) and the if arm whose statements reach line 8
  EXPECT_EQ(s.line_points, 4U);
  EXPECT_EQ(s.line_hit, 2U);
  EXPECT_EQ(s.toggle_points, 1U);  // toggles are never waived
  ASSERT_EQ(s.waived.size(), 2U);
  EXPECT_EQ(s.waived[0].lines, "4");
  EXPECT_EQ(s.waived[0].waiver, "w:1");
  EXPECT_EQ(s.waived[0].reason, "no default");
  EXPECT_EQ(s.waived[1].lines, "7-8");
  EXPECT_EQ(s.waived[1].instance, "top.t");
  EXPECT_EQ(s.waived[1].waiver, "w:2");
  // Without the waivers the totals hold the two points.
  const CoverageSummary none = count_coverage_points(points, CoverageInputs{});
  EXPECT_EQ(none.line_points, s.line_points + 2);
  EXPECT_EQ(none.line_hit, s.line_hit);
}

TEST(UserWaivers, ReachedAndStaleAreErrors) {
  const testing::TempDir tmp;
  const std::string src = tmp.Write("my.sv", kSource).string();
  const Points points{{line_key(src, 3, "3", "top.t"), 5},
                      {line_key(src, 4, "4", "top.t"), 0},
                      {line_key(src, 6, "7-8", "top.t"), 0},
                      {line_key(src, 6, "", "top.t"), 3}};
  const auto error = [&](const UserWaiver& w) {
    CoverageInputs in;
    in.user_waivers = {w};
    return testing::ErrorOf([&] { (void)count_coverage_points(points, in); });
  };
  // The implicit else lies on its if's line and was reached: the waiver's reason is wrong.
  EXPECT_EQ(
      error({"w:3", "my.sv", 6, 6, "", "", "x is always set"}),
      fmt::format("w:3: {} line 6 in top.t is waived (x is always set) but was reached", src));
  EXPECT_EQ(error({"w:4", "my.sv", 0, 0, "no such text", "", "r"}),
            fmt::format("w:4: the waiver 'my.sv /no such text/' matches no coverage point (/no "
                        "such text/ matches no line of {}; a stale waiver would waive other "
                        "code: fix or remove it)",
                        src));
  EXPECT_NE(error({"w:5", "my.sv", 10, 10, "", "", "r"})
                .find("w:5: the waiver 'my.sv:10' matches no coverage point (no line or branch "
                      "point lies on my.sv:10"),
            std::string::npos);
  EXPECT_NE(error({"w:6", "other.sv", 4, 4, "", "", "r"})
                .find("(no line or branch point is in a source file other.sv;"),
            std::string::npos);
  EXPECT_NE(error({"w:7", "my.sv", 4, 4, "", "u_none", "r"})
                .find("(no instance matching @u_none has a point on those lines;"),
            std::string::npos);
  // "y.sv" is not the end of ".../my.sv" at a '/'.
  EXPECT_NE(
      error({"w:8", "y.sv", 4, 4, "", "", "r"}).find("no line or branch point is in a source"),
      std::string::npos);
  // check_waivers: the same stale check on a design's points, before any run; reached points
  // are no concern there (a probe's counts are a reset's).
  EXPECT_NO_THROW(
      check_waivers(points, std::vector<UserWaiver>{{"w:3", "my.sv", 6, 6, "", "", "r"}}));
  EXPECT_NE(testing::ErrorOf([&] {
              check_waivers(points, std::vector<UserWaiver>{{"w:5", "my.sv", 10, 10, "", "", "r"}});
            }).find("w:5: the waiver 'my.sv:10' matches no coverage point"),
            std::string::npos);
  // Two waivers of one point: both match (neither is stale), the first one's reason is listed.
  CoverageInputs in;
  in.user_waivers = {{"w:1", "my.sv", 4, 4, "", "", "first"}, {"w:2", "my.sv", 4, 4, "", "", "x"}};
  const CoverageSummary s = count_coverage_points(points, in);
  ASSERT_EQ(s.waived.size(), 1U);
  EXPECT_EQ(s.waived[0].reason, "first");
}

// The signals of the waveform without toggle points, each with why.
TEST(NotToggleCounted, ListsWhatVerilatorSkips) {
  const Points points{
      {toggle_key("/m.sv", 5, "clk_i", "top.t"), 9},
      {toggle_key("/m.sv", 6, "v_q[0]", "top.t"), 1},
      {toggle_key("/m.sv", 7, "arr[0][3]", "top.t"), 1},
      {toggle_key("/m.sv", 8, "st.a[0]", "top.t"), 0},
      {toggle_key("/s.sv", 2, "d_i[1]", "top.t.u_sub*"), 1},  // one module for u_sub, u_sub2
      {toggle_key("/s.sv", 3, "q[1]", "top.t.u_sub*"), 1},
      {toggle_key("/c.sv", 3, "in_i[0]", "top.t.u_chk"), 1},
      {line_key("/m.sv", 20, "20", "top.t"), 1}};
  const std::vector<WaveSignal> signals{
      {"top", "clk_i", 1, "wire", true},  // the root: the top's ports from outside
      {"top.t", "clk_i", 1, "wire", true},
      {"top.t", "W", 32, "parameter", false},
      {"top.t", "v_q", 4, "logic", false},
      {"top.t", "arr[0]", 8, "logic", false},  // counted array
      {"top.t", "arr[1]", 8, "logic", false},
      {"top.t", "st", 8, "logic", false},        // packed struct: "st.a[0]"
      {"top.t", "mem[0]", 200, "logic", false},  // an array over 256 bits in all
      {"top.t", "mem[1]", 200, "logic", false},
      {"top.t", "wide", 300, "logic", false},
      {"top.t", "n", 64, "longint", false},
      {"top.t", "r", 8, "real", false},
      {"top.t.g_c[0]", "sum", 43, "logic", false},
      {"top.t.u_sub", "d_i", 4, "wire", true},
      {"top.t.u_sub", "q", 4, "logic", false},
      {"top.t.u_sub2", "q", 4, "logic", false},
      {"top.t.u_sub2.g_s[1]", "gq", 2, "logic", false},
      {"top.t.u_chk", "in_i", 1, "wire", true},
      {"top.t.u_chk", "seen_q", 5, "logic", false}};  // under coverage_off
  CoverageInputs in;
  in.signals = signals;
  const CoverageSummary s = count_coverage_points(points, in);
  ASSERT_TRUE(s.signals_checked);
  std::vector<std::string> got;
  for (const UncountedSignal& u : s.not_toggled) {
    got.push_back(fmt::format("{} {} {}", u.path, u.bits, u.why));
  }
  EXPECT_EQ(got, (std::vector<std::string>{
                     "top.t.mem 400 an unpacked array wider than the toggle limit of 256 bits",
                     "top.t.wide 300 a vector wider than the toggle limit of 256 bits",
                     "top.t.n 64 longint, not logic or bit", "top.t.r 64 real",
                     "top.t.g_c[0].sum 43 in a generate or named block",
                     "top.t.u_sub2.g_s[1].gq 2 in a generate or named block",
                     "top.t.u_chk.seen_q 5 no toggle point (coverage_off?)"}));
  EXPECT_EQ(s.not_toggled_bits(), 400U + 300 + 64 + 64 + 43 + 2 + 5);
  // Without toggle data (a line-only build) nothing is checked.
  const Points lines{{line_key("/m.sv", 20, "20", "top.t"), 1}};
  EXPECT_FALSE(count_coverage_points(lines, in).signals_checked);
}

// The lcov file: a branch record per counted line point, a function record per toggle point;
// waived points left out; a line's count the smallest of the points on it.
TEST(LcovInfo, FiguresAreTheCountedOnes) {
  const testing::TempDir tmp;
  const std::string src = tmp.Write("my.sv", kSource).string();
  const Points points{{line_key(src, 3, "3", "top.t"), 5},
                      {line_key(src, 4, "4", "top.t"), 0},
                      {line_key(src, 6, "7-8", "top.t"), 2},
                      {line_key(src, 6, "", "top.t"), 0},
                      {line_key(src, 2, "2-3", "top.t", "v_line/m"), 7},
                      {toggle_key(src, 7, "q[0]", "top.t"), 4},
                      {toggle_key(src, 7, "q[1]", "top.t"), 0}};
  CoverageInputs in;
  in.user_waivers = {{"w:1", "my.sv", 4, 4, "", "", "no default"}};
  const std::string info = lcov_info(points, in);
  const CoverageSummary s = count_coverage_points(points, in);
  EXPECT_NE(info.find(fmt::format("SF:{}\n", src)), std::string::npos) << info;
  EXPECT_NE(info.find(fmt::format("BRF:{}\nBRH:{}\n", s.line_points, s.line_hit)),
            std::string::npos)
      << info;
  EXPECT_NE(info.find(fmt::format("FNF:{}\nFNH:{}\n", s.toggle_points, s.toggle_hit)),
            std::string::npos)
      << info;
  EXPECT_NE(info.find("FNDA:4,top.t.q[0]\n"), std::string::npos) << info;
  EXPECT_EQ(info.find("\nDA:4,"), std::string::npos) << "the waived point's line: " << info;
  EXPECT_NE(info.find("\nDA:3,5\n"), std::string::npos) << "min(5, 7): " << info;
  EXPECT_NE(info.find("\nDA:6,0\n"), std::string::npos) << "the implicit else: " << info;
  EXPECT_NE(info.find("\nDA:7,2\n"), std::string::npos) << info;
  EXPECT_NE(info.find("BRDA:6,0,1,0\n"), std::string::npos) << info;
}

// A plugin built from a copy of the files elsewhere (its points name that copy's paths) counts
// and reports the design's files where they are now, matched by content; an include too.
TEST(MovedSources, PointsFollowTheContent) {
  const testing::TempDir tmp;
  std::filesystem::create_directories(tmp.path() / "now" / "inc");
  std::filesystem::create_directories(tmp.path() / "plugin");
  const auto file = tmp.Write("now/my.sv", kSource);
  const auto inc = tmp.Write("now/inc/defs.svh", "`define X 1\n");
  const auto other = tmp.Write("now/other.sv", "module other; endmodule\n");
  tmp.Write("plugin/info.txt",
            fmt::format("key k\nfile {} /gone/my.sv\nfile {} {}\nincdir 0 /gone/inc\n"
                        "include {} 0 defs.svh\nwidth clk_i 1\n",
                        file_hash(file), file_hash(other), other.string(), file_hash(inc)));
  RtlDesign design;
  design.files = {file, other};
  design.include_dirs = {tmp.path() / "now" / "inc"};
  const auto moved = moved_sources(RtlPlugin{tmp.path() / "plugin" / "plugin.so", "k", ""}, design);
  EXPECT_EQ(moved, (std::map<std::string, std::string>{{"/gone/my.sv", file.string()},
                                                       {"/gone/inc/defs.svh", inc.string()}}));
  const Points points{{line_key("/gone/my.sv", 4, "4", "top.t"), 2},
                      {line_key(other.string(), 1, "1", "top.t"), 1}};
  const Points now = relocated(points, moved);
  EXPECT_EQ(now, (Points{{line_key(file.string(), 4, "4", "top.t"), 2},
                         {line_key(other.string(), 1, "1", "top.t"), 1}}));
  // A waiver's regex reads the file where it is now.
  CoverageInputs in;
  in.user_waivers = {{"w:1", "my.sv", 0, 0, "default:", "", "r"}};
  in.moved = moved;
  EXPECT_NO_THROW(check_waivers(now, in.user_waivers));
  // A file whose content changed since is not the one the plugin was built from.
  tmp.Write("now/my.sv", std::string(kSource) + "// edited\n");
  EXPECT_EQ(moved_sources(RtlPlugin{tmp.path() / "plugin" / "plugin.so", "k", ""}, design)
                .count("/gone/my.sv"),
            0U);
}

// ---- phongsim's own waivers, anchored by markers in the RTL ----

// A copy of the tree's `rel` (e.g. "rtl/common/fx_resize.sv") under `tmp`, at the same relative
// path, with `edit` applied to its text.
std::string copy_rtl(const testing::TempDir& tmp, const std::string& rel,
                     const std::function<void(std::string&)>& edit = {}) {
  std::string text = read_file(std::filesystem::path(PHONGSIM_SOURCE_DIR) / rel);
  if (edit) edit(text);
  std::filesystem::create_directories((tmp.path() / rel).parent_path());
  return tmp.Write(rel, text).string();
}

// The line of file `path` holding `code` (the test finds the code by its text, as Verilator
// would number it).
int line_of(const std::string& path, const std::string& code) {
  std::istringstream in(read_file(path));
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.find(code) != std::string::npos) return n;
  }
  ADD_FAILURE() << "no line of " << path << " holds " << code;
  return 0;
}

// `text` with `lines` inserted before its line holding `code`.
void insert_before(std::string& text, const std::string& code, const std::string& lines) {
  const auto at = text.find(code);
  ASSERT_NE(at, std::string::npos) << code;
  text.insert(text.rfind('\n', at) + 1, lines);
}

// `text` without `what` (once).
void erase_once(std::string& text, const std::string& what) {
  const auto at = text.find(what);
  ASSERT_NE(at, std::string::npos) << what;
  text.erase(at, what.size());
}

// fx_resize's saturating always_comb as Verilator keys its points (5.006, as the coverage goal
// runs record them): the block, the `wide > MaxV` arm (statements: its if line and the next),
// the `wide < MinV` arm, the final else; the two saturation arms unreached.
Points fx_resize_points(const std::string& path, const std::string& hier) {
  const int block = line_of(path, "always_comb begin"), high = line_of(path, "if (wide > MaxV)"),
            low = line_of(path, "if (wide < MinV)");
  const auto span = [](int a, int b) { return fmt::format("{}-{}", a, b); };
  return {{line_key(path, block, std::to_string(block), hier, "v_line/fx_resize"), 9},
          {line_key(path, high, span(high, high + 1), hier), 0},
          {line_key(path, low, span(low, low + 1), hier), 0},
          {line_key(path, low, span(low + 2, low + 3), hier), 9}};
}

// The waived points as "FILE-END LINES INSTANCE: REASON".
std::vector<std::string> waived_list(const CoverageSummary& s) {
  std::vector<std::string> out;
  for (const WaivedPoint& w : s.waived) {
    out.push_back(fmt::format("{} {} {}: {}", std::filesystem::path(w.file).filename().string(),
                              w.lines, w.instance, w.reason));
  }
  return out;
}

// A configuration's waivers name the RTL's markers (`// phongsim: waive saturate.low` on
// fx_resize's `wide < MinV` arm), never a line: with lines inserted above the arms, the same
// points are waived at their new lines. A marker removed, given twice, or renamed in the RTL is
// an error naming the file and the marker, not a waiver of other code or of nothing.
TEST(MarkerWaivers, FollowTheMarkedLineWhenItMoves) {
  // kb's and quad's output stage: an accumulator clamped to [0, 1] into an output that holds 1
  // saturates neither way, so both fx_resize arms of `u_value` are waived.
  CoverpointSampler sampler;
  const Clamp01Output output(sampler, fx::Format{true, 2, 12}, fx::Format{false, 1, 10},
                             fx::Round::half_even);
  ASSERT_EQ(sampler.line_waivers.size(), 2U);
  const std::string hier = "top.kb_top.u_engine.u_value.u_rq.u_resize";
  const auto count = [&](const Points& points) {
    CoverageInputs in;
    in.line_waivers = sampler.line_waivers;
    return count_coverage_points(points, in);
  };
  const testing::TempDir before;
  const std::string at = copy_rtl(before, "rtl/common/fx_resize.sv");
  const CoverageSummary s = count(fx_resize_points(at, hier));
  const int high = line_of(at, "if (wide > MaxV)"), low = line_of(at, "if (wide < MinV)");
  EXPECT_EQ(s.line_waived, 2U);
  EXPECT_EQ(s.line_points, 2U);
  EXPECT_EQ(waived_list(s),
            (std::vector<std::string>{fmt::format("fx_resize.sv {}-{} {}: {}", high, high + 1, hier,
                                                  sampler.line_waivers[0].reason),
                                      fmt::format("fx_resize.sv {}-{} {}: {}", low, low + 1, hier,
                                                  sampler.line_waivers[1].reason)}));
  // Three lines inserted above the always_comb move both arms down by three.
  const testing::TempDir after;
  const std::string moved = copy_rtl(after, "rtl/common/fx_resize.sv", [](std::string& t) {
    insert_before(t, "always_comb begin", "    // one\n    // two\n    // three\n");
  });
  ASSERT_EQ(line_of(moved, "if (wide > MaxV)"), high + 3);
  ASSERT_EQ(line_of(moved, "if (wide < MinV)"), low + 3);
  const CoverageSummary m = count(fx_resize_points(moved, hier));
  EXPECT_EQ(m.line_waived, 2U);
  EXPECT_EQ(m.line_points, s.line_points);
  EXPECT_EQ(m.line_hit, s.line_hit);
  EXPECT_EQ(waived_list(m),
            (std::vector<std::string>{fmt::format("fx_resize.sv {}-{} {}: {}", high + 3, high + 4,
                                                  hier, sampler.line_waivers[0].reason),
                                      fmt::format("fx_resize.sv {}-{} {}: {}", low + 3, low + 4,
                                                  hier, sampler.line_waivers[1].reason)}));
  // The marker removed, on a second line, or renamed: an error naming the file and the marker.
  const auto error_with = [&](const std::function<void(std::string&)>& edit) {
    const testing::TempDir tmp;
    const std::string path = copy_rtl(tmp, "rtl/common/fx_resize.sv", edit);
    std::string e = testing::ErrorOf([&] { (void)count(fx_resize_points(path, hier)); });
    const auto p = e.find(path);
    if (p != std::string::npos) e.replace(p, path.size(), "FILE");
    return e;
  };
  EXPECT_EQ(error_with([](std::string& t) {
              erase_once(t, "// phongsim: waive saturate.low");
            }).rfind("FILE: phongsim's waiver marker 'saturate.low' is on no line (", 0),
            0U);
  EXPECT_EQ(error_with([](std::string& t) {
              insert_before(t, "always_comb begin", "    // phongsim: waive saturate.high\n");
            }).rfind("FILE: phongsim's waiver marker 'saturate.high' is on several lines (", 0),
            0U);
  EXPECT_EQ(error_with([](std::string& t) {
              erase_once(t, "waive saturate.high");
              t.insert(t.find("// phongsim: ", t.find("if (wide > MaxV)")) + 13,
                       "waive saturate.higher");
            }).rfind("FILE: phongsim's waiver marker 'saturate.high' is on no line (", 0),
            0U);
}

// The user's recommended form (docs/cosim.md, "Waivers"): the same marker in their RTL, named by
// a regex; it follows the line, and a removed marker makes the waiver stale.
TEST(MarkerWaivers, UserRegexOnAMarker) {
  const testing::TempDir tmp;
  std::string text = kSource;
  insert_before(text, "default: q = lo;", "    // a comment\n");
  text.insert(text.find("default: q = lo;") + 16, "  // phongsim: waive no-default");
  const std::string src = tmp.Write("my.sv", text).string();
  const int at = line_of(src, "default: q = lo;");
  ASSERT_EQ(at, 5);  // kSource's line 4, one line down
  const Points points{{line_key(src, 3, "3", "top.t"), 5},
                      {line_key(src, at, std::to_string(at), "top.t"), 0}};
  CoverageInputs in;
  in.user_waivers = {{"w:1", "my.sv", 0, 0, "phongsim: waive no-default\\b", "", "no default"}};
  const CoverageSummary s = count_coverage_points(points, in);
  ASSERT_EQ(s.waived.size(), 1U);
  EXPECT_EQ(s.waived[0].lines, std::to_string(at));
  tmp.Write("my.sv", kSource);
  EXPECT_NE(testing::ErrorOf([&] { check_waivers(points, in.user_waivers); })
                .find("w:1: the waiver 'my.sv /phongsim: waive no-default\\b/' matches no coverage "
                      "point"),
            std::string::npos);
}

// A region, `waive-begin NAME` on its first line and `waive-end NAME` on its last: quad's walker
// waives the two narrowing compares (one-line ifs) as one region. Only points with statements
// lie on a marker's lines: their implicit elses, on the same lines and reached, are counted. The
// region follows its lines; without its end it is an error.
TEST(MarkerWaivers, RegionFollowsItsLines) {
  const LineWaiver waiver{R"(\.u_walker$)", "rtl/quad/quad_walker_core.sv", "narrow",
                          "unrolled loop"};
  const std::string hier = "top.quad_walker.u_walker";
  const auto points_of = [&](const std::string& path) {
    const int lower = line_of(path, "KindLower && 0 - q_ext[k] > lower"),
              upper = line_of(path, "KindUpper && q_ext[k] < upper");
    const auto l = [](int n) { return std::to_string(n); };
    return Points{{line_key(path, lower - 1, l(lower - 1), hier, "v_line/q"), 3},  // the for
                  {line_key(path, lower, l(lower), hier), 0},
                  {line_key(path, lower, "", hier), 7},  // its implicit else: reached
                  {line_key(path, upper, l(upper), hier), 0},
                  {line_key(path, upper, "", hier), 7},
                  {line_key(path, upper + 1, l(upper + 1), hier, "v_line/q"), 3}};
  };
  const auto count = [&](const Points& points) {
    CoverageInputs in;
    in.line_waivers = {waiver};
    return count_coverage_points(points, in);
  };
  const testing::TempDir before, after, broken;
  const std::string at = copy_rtl(before, "rtl/quad/quad_walker_core.sv");
  const CoverageSummary s = count(points_of(at));
  const int lower = line_of(at, "KindLower && 0 - q_ext[k] > lower");
  EXPECT_EQ(s.line_waived, 2U);
  EXPECT_EQ(s.line_points, 4U);
  EXPECT_EQ(s.line_hit, 4U);
  EXPECT_EQ(waived_list(s),
            (std::vector<std::string>{
                fmt::format("quad_walker_core.sv {} {}: unrolled loop", lower, hier),
                fmt::format("quad_walker_core.sv {} {}: unrolled loop", lower + 1, hier)}));
  const std::string moved = copy_rtl(after, "rtl/quad/quad_walker_core.sv", [](std::string& t) {
    insert_before(t, "always_comb begin\n    lower", "  // one\n  // two\n");
  });
  const CoverageSummary m = count(points_of(moved));
  EXPECT_EQ(m.line_waived, 2U);
  EXPECT_EQ(m.line_hit, s.line_hit);
  EXPECT_EQ(waived_list(m),
            (std::vector<std::string>{
                fmt::format("quad_walker_core.sv {} {}: unrolled loop", lower + 2, hier),
                fmt::format("quad_walker_core.sv {} {}: unrolled loop", lower + 3, hier)}));
  const std::string open = copy_rtl(broken, "rtl/quad/quad_walker_core.sv", [](std::string& t) {
    erase_once(t, "  // phongsim: waive-end narrow");
  });
  const std::string e = testing::ErrorOf([&] { (void)count(points_of(open)); });
  EXPECT_EQ(e.rfind(open + ": phongsim's waiver marker 'narrow' needs one waive-begin and one "
                           "waive-end (waive-begin on 1 line(s) ",
                    0),
            0U)
      << e;
}

}  // namespace
}  // namespace phongsim
