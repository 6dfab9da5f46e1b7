// Verilator's lint output as findings (sim/cosim/lint_findings.h), on text Verilator 5.006
// printed for `verilator --lint-only -Wall` over small broken designs (each test names the
// design), and those findings as GCC-style lines and GitHub Actions annotations.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "sim/cosim/lint_findings.h"
#include "tests/temp_dir.h"

namespace phongsim {

void PrintTo(const LintFinding& f, std::ostream* os) { *os << gcc_line(f); }

namespace {

namespace fs = std::filesystem;

constexpr auto W = LintSeverity::warning;
constexpr auto E = LintSeverity::error;

std::vector<LintFinding> parse(std::string_view text) { return parse_lint_findings(text, "/work"); }

// w.sv: an 8-bit signal into a 4-bit output, an unused input, an unused signal, unused bits.
constexpr std::string_view kWarnings =
    R"txt(%Warning-WIDTH: w.sv:9:14: Operator ASSIGNW expects 4 bits on the Assign RHS, but Assign RHS's VARREF 'bar' generates 8 bits.
                         : ... In instance w
    9 |   assign y_o = bar;
      |              ^
                ... For warning description see https://verilator.org/warn/WIDTH?v=5.006
                ... Use "/* verilator lint_off WIDTH */" and lint_on around source to disable this message.
%Warning-UNUSEDSIGNAL: w.sv:2:22: Signal is not used: 'clk_i'
                                : ... In instance w
    2 |   input  logic       clk_i,
      |                      ^~~~~
%Warning-UNUSEDSIGNAL: w.sv:6:15: Signal is not driven, nor used: 'foo'
                                : ... In instance w
    6 |   logic [7:0] foo;
      |               ^~~
%Warning-UNUSEDSIGNAL: w.sv:7:15: Bits of signal are not used: 'bar'[7:4]
                                : ... In instance w
    7 |   logic [7:0] bar;
      |               ^~~
%Error: Exiting due to 4 warning(s)
)txt";

TEST(LintFindings, WarningsWithTheirLocationRuleAndMessageNotTheSummary) {
  const std::vector<LintFinding> want{
      {"w.sv", 9, 14, "WIDTH", W,
       "Operator ASSIGNW expects 4 bits on the Assign RHS, but Assign RHS's VARREF 'bar' "
       "generates 8 bits."},
      {"w.sv", 2, 22, "UNUSEDSIGNAL", W, "Signal is not used: 'clk_i'"},
      {"w.sv", 6, 15, "UNUSEDSIGNAL", W, "Signal is not driven, nor used: 'foo'"},
      {"w.sv", 7, 15, "UNUSEDSIGNAL", W, "Bits of signal are not used: 'bar'[7:4]"},
  };
  EXPECT_EQ(parse(kWarnings), want);
}

TEST(LintFindings, PlainErrorsHaveNoRule) {
  // e.sv: an undeclared signal.
  constexpr std::string_view text =
      R"txt(%Error: e.sv:5:22: Can't find definition of variable: 'undeclared_q'
    5 |   assign y_o = a_i + undeclared_q;
      |                      ^~~~~~~~~~~~
%Error: Exiting due to 1 error(s)
)txt";
  const std::vector<LintFinding> want{
      {"e.sv", 5, 22, std::nullopt, E, "Can't find definition of variable: 'undeclared_q'"}};
  EXPECT_EQ(parse(text), want);
}

TEST(LintFindings, ErrorsWithACode) {
  // uns.sv: a delay and a fork without --timing.
  constexpr std::string_view text =
      R"txt(%Error-NEEDTIMINGOPT: uns.sv:10:5: Use --timing or --no-timing to specify how delays should be handled
                                 : ... In instance uns
   10 |     #1 $display("x");
      |     ^
                      ... For error description see https://verilator.org/warn/NEEDTIMINGOPT?v=5.006
%Error-NEEDTIMINGOPT: uns.sv:11:12: Use --timing or --no-timing to specify how forks should be handled
                                  : ... In instance uns
   11 |     fork : f
      |            ^
%Error: Exiting due to 2 error(s)
)txt";
  const std::vector<LintFinding> want{
      {"uns.sv", 10, 5, "NEEDTIMINGOPT", E,
       "Use --timing or --no-timing to specify how delays should be handled"},
      {"uns.sv", 11, 12, "NEEDTIMINGOPT", E,
       "Use --timing or --no-timing to specify how forks should be handled"},
  };
  EXPECT_EQ(parse(text), want);
}

TEST(LintFindings, UnsupportedBetweenPlainErrorsAndLinesAfterTheSummary) {
  // u.sv: a checker, which Verilator 5.006 does not read.
  constexpr std::string_view text =
      R"txt(%Error-UNSUPPORTED: u.sv:5:3: Unsupported: SystemVerilog 2009 reserved word not implemented: 'checker'
    5 |   checker chk (logic x);
      |   ^~~~~~~
                    ... For error description see https://verilator.org/warn/UNSUPPORTED?v=5.006
%Error: u.sv:5:15: syntax error, unexpected '(', expecting IDENTIFIER or randomize
    5 |   checker chk (logic x);
      |               ^
%Error-UNSUPPORTED: u.sv:6:3: Unsupported: SystemVerilog 2009 reserved word not implemented: 'endchecker'
    6 |   endchecker
      |   ^~~~~~~~~~
%Error: Exiting due to 3 error(s)
        ... See the manual at https://verilator.org/verilator_doc.html for more assistance.
)txt";
  const std::vector<LintFinding> want{
      {"u.sv", 5, 3, "UNSUPPORTED", E,
       "Unsupported: SystemVerilog 2009 reserved word not implemented: 'checker'"},
      {"u.sv", 5, 15, std::nullopt, E,
       "syntax error, unexpected '(', expecting IDENTIFIER or randomize"},
      {"u.sv", 6, 3, "UNSUPPORTED", E,
       "Unsupported: SystemVerilog 2009 reserved word not implemented: 'endchecker'"},
  };
  EXPECT_EQ(parse(text), want);
}

TEST(LintFindings, ErrorsWithoutALocation) {
  // --top-module nope over w.sv.
  constexpr std::string_view top =
      R"txt(%Error: Specified --top-module 'nope' was not found in design.
%Error: Exiting due to 1 error(s)
)txt";
  EXPECT_EQ(parse(top),
            std::vector<LintFinding>({{std::nullopt, std::nullopt, std::nullopt, std::nullopt, E,
                                       "Specified --top-module 'nope' was not found "
                                       "in design."}}));
  // A file that is not there: its path is in the message, not a location.
  constexpr std::string_view missing =
      R"txt(%Error: Cannot find file containing module: /tmp/lintcap/missing.sv
%Error: This may be because there's no search path specified with -I<dir>.
        ... Looked in:
             /tmp/lintcap/missing.sv
             /tmp/lintcap/missing.sv.v
             /tmp/lintcap/missing.sv.sv
             obj_dir//tmp/lintcap/missing.sv
             obj_dir//tmp/lintcap/missing.sv.v
             obj_dir//tmp/lintcap/missing.sv.sv
%Error: Exiting due to 2 error(s)
)txt";
  const std::vector<LintFinding> want{
      {std::nullopt, std::nullopt, std::nullopt, std::nullopt, E,
       "Cannot find file containing module: /tmp/lintcap/missing.sv"},
      {std::nullopt, std::nullopt, std::nullopt, std::nullopt, E,
       "This may be because there's no search path specified with -I<dir>."},
  };
  EXPECT_EQ(parse(missing), want);
}

TEST(LintFindings, CannotContinueIsNoFinding) {
  // syn.sv: a missing semicolon.
  constexpr std::string_view text =
      R"txt(%Error: syn.sv:6:1: syntax error, unexpected endmodule, expecting ',' or ';'
    6 | endmodule
      | ^~~~~~~~~
%Error: Cannot continue
)txt";
  const std::vector<LintFinding> want{{"syn.sv", 6, 1, std::nullopt, E,
                                       "syntax error, unexpected endmodule, expecting ',' or ';'"}};
  EXPECT_EQ(parse(text), want);
}

TEST(LintFindings, ContinuationLinesThatNameLocationsBelongToTheFindingAbove) {
  // i2.sv includes inc/defs2.svh, which declares a signal nothing uses: the finding is in the
  // header; the "In file included from" note is no finding of its own.
  constexpr std::string_view included =
      R"txt(%Warning-UNUSEDSIGNAL: inc/defs2.svh:1:9: Signal is not driven, nor used: 'stray_in_header'
                                        : ... In instance i2
    1 |   logic stray_in_header;
      |         ^~~~~~~~~~~~~~~
                       i2.sv:4:2: ... note: In file included from i2.sv
                       ... For warning description see https://verilator.org/warn/UNUSEDSIGNAL?v=5.006
                       ... Use "/* verilator lint_off UNUSEDSIGNAL */" and lint_on around source to disable this message.
%Error: Exiting due to 1 warning(s)
)txt";
  EXPECT_EQ(parse(included),
            std::vector<LintFinding>({{"inc/defs2.svh", 1, 9, "UNUSEDSIGNAL", W,
                                       "Signal is not driven, nor used: 'stray_in_header'"}}));
  // loop.sv: a combinational loop, its example path one location a line.
  constexpr std::string_view loop =
      R"txt(%Warning-UNOPTFLAT: loop.sv:5:15: Signal unoptimizable: Circular combinational logic: 'loop.x'
    5 |   logic [1:0] x;
      |               ^
                    ... For warning description see https://verilator.org/warn/UNOPTFLAT?v=5.006
                    ... Use "/* verilator lint_off UNOPTFLAT */" and lint_on around source to disable this message.
                    loop.sv:5:15:      Example path: loop.x
                    loop.sv:6:24:      Example path: ASSIGNW
                    loop.sv:5:15:      Example path: loop.x
%Error: Exiting due to 1 warning(s)
)txt";
  EXPECT_EQ(parse(loop),
            std::vector<LintFinding>({{"loop.sv", 5, 15, "UNOPTFLAT", W,
                                       "Signal unoptimizable: Circular combinational logic: "
                                       "'loop.x'"}}));
  // multi.sv: two modules, no --top-module.
  constexpr std::string_view multi =
      R"txt(%Warning-DECLFILENAME: multi.sv:7:8: Filename 'multi' does not match MODULE name: 'second'
    7 | module second (
      |        ^~~~~~
                       ... For warning description see https://verilator.org/warn/DECLFILENAME?v=5.006
                       ... Use "/* verilator lint_off DECLFILENAME */" and lint_on around source to disable this message.
%Warning-MULTITOP: multi.sv:7:8: Multiple top level modules
                               : ... Suggest see manual; fix the duplicates, or use --top-module to select top.
                               : ... Top module 'multi'
    1 | module multi (
      |        ^~~~~
                               : ... Top module 'second'
    7 | module second (
      |        ^~~~~~
%Error: Exiting due to 2 warning(s)
)txt";
  const std::vector<LintFinding> want{
      {"multi.sv", 7, 8, "DECLFILENAME", W,
       "Filename 'multi' does not match MODULE name: 'second'"},
      {"multi.sv", 7, 8, "MULTITOP", W, "Multiple top level modules"},
  };
  EXPECT_EQ(parse(multi), want);
}

TEST(LintFindings, InternalErrorsKeepTheDesignsLocation) {
  // u2.sv: a property Verilator 5.006 cannot parse.
  constexpr std::string_view text =
      R"txt(%Error: u2.sv:8:30: syntax error, unexpected ##, expecting TYPE-IDENTIFIER
    8 |     @(posedge clk_i) a_i |-> ##[1:$] y_o;
      |                              ^~
%Error: Internal Error: u2.sv:1:8: ../V3ParseSym.h:124: Symbols suggest ending PROPERTY 'p' but parser thinks ending MODULE 'u2'
    1 | module u2 (
      |        ^~
)txt";
  const std::vector<LintFinding> want{
      {"u2.sv", 8, 30, std::nullopt, E, "syntax error, unexpected ##, expecting TYPE-IDENTIFIER"},
      {"u2.sv", 1, 8, std::nullopt, E,
       "Internal Error: ../V3ParseSym.h:124: Symbols suggest ending PROPERTY 'p' but parser "
       "thinks ending MODULE 'u2'"},
  };
  EXPECT_EQ(parse(text), want);
}

// `phongsim lint lirp --rtl lirp_stray.sv --top my_lirp` in /tmp/lintcap: a copy of
// examples/your-rtl/my_lirp.sv with `logic stray_q;` added as line 75 (phongsim gives Verilator
// the file's absolute path).
constexpr std::string_view kStray =
    R"txt(%Warning-DECLFILENAME: /tmp/lintcap/lirp_stray.sv:16:8: Filename 'lirp_stray' does not match MODULE name: 'my_lirp'
   16 | module my_lirp #(
      |        ^~~~~~~
                       ... For warning description see https://verilator.org/warn/DECLFILENAME?v=5.006
                       ... Use "/* verilator lint_off DECLFILENAME */" and lint_on around source to disable this message.
%Warning-UNUSEDSIGNAL: /tmp/lintcap/lirp_stray.sv:75:15: Signal is not driven, nor used: 'stray_q'
                                                       : ... In instance my_lirp
   75 |   logic       stray_q;
      |               ^~~~~~~
%Error: Exiting due to 2 warning(s)
)txt";

TEST(LintFindings, FilesUnderTheCurrentFolderAreRelativeOthersAsGiven) {
  const auto files = [](const fs::path& cwd) {
    std::vector<std::string> out;
    for (const LintFinding& f : parse_lint_findings(kStray, cwd)) out.push_back(f.file.value());
    return out;
  };
  using Files = std::vector<std::string>;
  EXPECT_EQ(files("/tmp/lintcap"), Files({"lirp_stray.sv", "lirp_stray.sv"}));
  EXPECT_EQ(files("/tmp/lintcap/"), Files({"lirp_stray.sv", "lirp_stray.sv"}));
  EXPECT_EQ(files("/tmp"), Files({"lintcap/lirp_stray.sv", "lintcap/lirp_stray.sv"}));
  const Files absolute{"/tmp/lintcap/lirp_stray.sv", "/tmp/lintcap/lirp_stray.sv"};
  EXPECT_EQ(files("/tmp/lintcap/sub"), absolute);
  EXPECT_EQ(files("/tmp/lint"), absolute);
  EXPECT_EQ(files("/work"), absolute);
}

TEST(LintFindings, RelativeFilesOutsideTheCurrentFolderAreMadeAbsolute) {
  // The same design from a folder below it: `phongsim lint lirp --rtl ../my_lirp.sv --top
  // my_lirp` in /tmp/lintcap/cli/sub (the file's name my_lirp.sv there).
  constexpr std::string_view text =
      R"txt(%Warning-UNUSEDSIGNAL: ../my_lirp.sv:75:15: Signal is not driven, nor used: 'stray_q'
                                          : ... In instance my_lirp
   75 |   logic       stray_q;
      |               ^~~~~~~
                       ... For warning description see https://verilator.org/warn/UNUSEDSIGNAL?v=5.006
                       ... Use "/* verilator lint_off UNUSEDSIGNAL */" and lint_on around source to disable this message.
%Error: Exiting due to 1 warning(s)
)txt";
  const std::vector<LintFinding> in_sub = parse_lint_findings(text, "/tmp/lintcap/cli/sub");
  ASSERT_EQ(in_sub.size(), 1U);
  EXPECT_EQ(in_sub[0].file, "/tmp/lintcap/cli/my_lirp.sv");
  EXPECT_EQ(in_sub[0].line, 75);
  // The path is taken against the current folder: from one deeper, another file.
  const std::vector<LintFinding> deeper = parse_lint_findings(text, "/tmp/lintcap/cli/sub/deeper");
  ASSERT_EQ(deeper.size(), 1U);
  EXPECT_EQ(deeper[0].file, "/tmp/lintcap/cli/sub/my_lirp.sv");
}

TEST(LintFindings, FilesUnderTheCurrentFolderThroughASymbolicLink) {
  // The same text with the folder a symbolic link to the current one (as a checkout under a
  // linked home folder is named).
  const phongsim::testing::TempDir dir;
  fs::create_directories(dir.path() / "real");
  fs::create_directory_symlink(dir.path() / "real", dir.path() / "link");
  std::string text(kStray);
  for (std::size_t at; (at = text.find("/tmp/lintcap")) != std::string::npos;) {
    text.replace(at, 12, (dir.path() / "link").string());
  }
  const std::vector<LintFinding> found = parse_lint_findings(text, dir.path() / "real");
  ASSERT_EQ(found.size(), 2U);
  EXPECT_EQ(found[1].file, "lirp_stray.sv");
}

TEST(LintFindings, GithubAnnotationAndGccLineOfAFinding) {
  const std::vector<LintFinding> found = parse_lint_findings(kStray, "/tmp/lintcap");
  ASSERT_EQ(found.size(), 2U);
  EXPECT_EQ(github_line(found[1]),
            "::warning file=lirp_stray.sv,line=75,col=15,title=UNUSEDSIGNAL::Signal is not "
            "driven, nor used: 'stray_q'");
  EXPECT_EQ(gcc_line(found[1]),
            "lirp_stray.sv:75:15: warning: Signal is not driven, nor used: 'stray_q' "
            "[UNUSEDSIGNAL]");
  EXPECT_EQ(github_line(found[0]),
            "::warning file=lirp_stray.sv,line=16,col=8,title=DECLFILENAME::Filename "
            "'lirp_stray' does not match MODULE name: 'my_lirp'");
}

TEST(LintFindings, ErrorsAndFindingsWithoutALocationOrRule) {
  const std::vector<LintFinding> plain =
      parse("%Error: e.sv:5:22: Can't find definition of variable: 'undeclared_q'\n");
  ASSERT_EQ(plain.size(), 1U);
  EXPECT_EQ(github_line(plain[0]),
            "::error file=e.sv,line=5,col=22::Can't find definition of variable: 'undeclared_q'");
  EXPECT_EQ(gcc_line(plain[0]),
            "e.sv:5:22: error: Can't find definition of variable: 'undeclared_q'");
  const std::vector<LintFinding> top =
      parse("%Error: Specified --top-module 'nope' was not found in design.\n");
  ASSERT_EQ(top.size(), 1U);
  EXPECT_EQ(github_line(top[0]), "::error::Specified --top-module 'nope' was not found in design.");
  EXPECT_EQ(gcc_line(top[0]), "error: Specified --top-module 'nope' was not found in design.");
  const LintFinding no_column{"x.sv", 3, std::nullopt, "WIDTH", W, "m"};
  EXPECT_EQ(github_line(no_column), "::warning file=x.sv,line=3,title=WIDTH::m");
  EXPECT_EQ(gcc_line(no_column), "x.sv:3: warning: m [WIDTH]");
}

TEST(LintFindings, GithubEscapes) {
  // GitHub's workflow commands: %, CR and LF escaped in the message; also : and , in properties.
  const LintFinding f{"a,b:c%.sv", 1, 2, "WIDTH", E, "50% of 'x', a: b\r\nnext"};
  EXPECT_EQ(github_line(f),
            "::error file=a%2Cb%3Ac%25.sv,line=1,col=2,title=WIDTH::50%25 of 'x', a: b%0D%0Anext");
}

}  // namespace
}  // namespace phongsim
