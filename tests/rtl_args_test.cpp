// The RTL a user names as the RTL world names it (sim/cosim/rtl_args.h): file lists with their
// relative paths, comments, variables and nesting; +incdir+/+define+/-I/-D; packages compiled
// first whatever their files are called (rtl_files); and the one-line hint when Yosys or Icarus
// cannot read a construct (sim/cosim/portable.h).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/error.h"
#include "sim/cosim/portable.h"
#include "sim/cosim/rtl_args.h"
#include "sim/cosim/rtl_plugin.h"
#include "tests/temp_dir.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

std::string error_of(const auto& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// -F: relative to the list; nested -f: relative to the current folder; comments, quotes,
// variables, several entries a line, +incdir+ with two folders, defines in both spellings.
TEST(FileList, ReadsAsSimulatorsDo) {
  const phongsim::testing::TempDir dir;
  const fs::path root = dir.path();
  write(root / "t/src/a.sv", "");
  write(root / "t/src/b c.sv", "");
  write(root / "t/inc/h.svh", "");
  fs::create_directories(root / "t/inc2");
  write(root / "t/lists/inner.f", "../src/a.sv // a comment\n");
  setenv("PHONGSIM_TEST_ROOT", root.c_str(), 1);
  write(root / "t/lists/top.f",
        "# a comment line\n"
        "+incdir+../inc+../inc2 +define+A=1+B\n"
        "-F inner.f\n"
        "\"../src/b c.sv\"   -DC=2 -I ${PHONGSIM_TEST_ROOT}/t/inc\n"
        "../inc/h.svh\n");
  RtlSources s;
  add_file_list(root / "t/lists/top.f", true, s);
  const fs::path lists = root / "t/lists";
  EXPECT_EQ(s.files, (std::vector<fs::path>{lists / "../src/a.sv", lists / "../src/b c.sv"}));
  EXPECT_EQ(s.include_dirs, (std::vector<fs::path>{lists / "../inc", lists / "../inc2",
                                                   root / "t/inc", lists / "../inc"}));
  EXPECT_EQ(s.defines, (std::vector<std::string>{"A=1", "B", "C=2"}));
  EXPECT_EQ(s.lists, (std::vector<fs::path>{root / "t/lists/top.f", lists / "inner.f"}));

  // -f: the same entries are relative to the current folder.
  write(root / "cwd.f", "t/src/a.sv\n");
  const fs::path before = fs::current_path();
  fs::current_path(root);
  RtlSources c;
  add_file_list("cwd.f", false, c);
  fs::current_path(before);
  EXPECT_EQ(c.files, std::vector<fs::path>{"t/src/a.sv"});

  // Command-line words.
  RtlSources w;
  const std::vector<std::string> words{(root / "t/src/a.sv").string(), "+define+X", "-I",
                                       (root / "t/inc").string(), "-DY=3"};
  add_rtl_words(words, w);
  EXPECT_EQ(w.defines, (std::vector<std::string>{"X", "Y=3"}));
  EXPECT_EQ(w.include_dirs, std::vector<fs::path>{root / "t/inc"});
}

TEST(FileList, RefusesWhatItCannotRead) {
  const phongsim::testing::TempDir dir;
  const fs::path root = dir.path();
  const auto list = [&](const std::string& text) {
    write(root / "l.f", text);
    RtlSources s;
    return error_of([&] { add_file_list(root / "l.f", true, s); });
  };
  EXPECT_NE(list("-v lib.sv\n").find("l.f:1: -v: library files and folders are not read"),
            std::string::npos);
  EXPECT_NE(list("-y libdir\n").find("-y: library"), std::string::npos);
  EXPECT_NE(list("\n$PHONGSIM_NOT_SET_X/a.sv\n").find("l.f:2: $PHONGSIM_NOT_SET_X is not set"),
            std::string::npos);
  EXPECT_NE(list("-F l.f\n").find("includes itself"), std::string::npos);
  EXPECT_NE(list("+incdir+nope\n").find("no such include folder"), std::string::npos);
  EXPECT_NE(list("+libext+.v\n").find("only +incdir+ and +define+ are read"), std::string::npos);
  EXPECT_NE(list("-DX-Y=1\n").find("'X-Y' is not a macro name"), std::string::npos);
  EXPECT_NE(list("--timescale 1ns\n").find("not a file, and not an option"), std::string::npos);
  EXPECT_NE(list("\"open.sv\n").find("an unterminated"), std::string::npos);
  EXPECT_NE(list("-I\n").find("-I needs a value"), std::string::npos);
  RtlSources s;
  EXPECT_NE(error_of([&] {
              add_file_list(root / "nowhere.f", false, s);
            }).find("cannot read the file list"),
            std::string::npos);
}

// Packages first, whatever their files are called; a package after the packages it names; the
// rest in the order given.
TEST(RtlFiles, PackagesFirstInDependencyOrder) {
  const phongsim::testing::TempDir dir;
  const fs::path d = dir.path();
  write(d / "top.sv", "module top; import b::*; endmodule\n");
  write(d / "types.sv", "package b;\n  localparam int W = a::W;\nendpackage\n");
  write(d / "base.sv", "package a;\n  localparam int W = 4;\nendpackage\n");
  write(d / "leaf.sv", "module leaf; endmodule\n");
  const std::vector<fs::path> given{d / "top.sv", d / "types.sv", d / "leaf.sv", d / "base.sv"};
  EXPECT_EQ(rtl_files(given),
            (std::vector<fs::path>{d / "base.sv", d / "types.sv", d / "top.sv", d / "leaf.sv"}));
}

// The hint names the construct on the failing line, and nothing for a line without one.
TEST(PortableHint, NamesTheConstruct) {
  const phongsim::testing::TempDir dir;
  const fs::path f = dir.path() / "my.sv";
  write(f,
        "module m;\n"
        "  function automatic int g(input int x); return x; endfunction\n"
        "  wide_t v = '0;\n"
        "  assign y = wide_t'(x);\n"
        "  assign z = longint'(x);\n"
        "  assign w = x + 1;\n"
        "endmodule\n");
  const auto at = [&](int line) {
    return fmt::format("{}:{}: ERROR: syntax error", f.string(), line);
  };
  EXPECT_NE(portable_hint(at(2), "Yosys 0.23")
                .find("has a function's return, which Yosys 0.23 "
                      "does not read: instead, assign the result"),
            std::string::npos);
  EXPECT_NE(portable_hint(at(3), "Yosys 0.23").find("a declaration with an initial value"),
            std::string::npos);
  EXPECT_NE(portable_hint(at(4), "Yosys 0.23").find("a cast to a type name"), std::string::npos);
  EXPECT_NE(portable_hint(at(5), "Yosys 0.23").find("a cast to an integer type"),
            std::string::npos);
  EXPECT_EQ(portable_hint(at(6), "Yosys 0.23"), "");
  EXPECT_EQ(portable_hint("ERROR: no file named", "Yosys 0.23"), "");
}

}  // namespace
}  // namespace phongsim
