// What a verdict rests on, piece by piece (issue 39): the SHA-256 content hash, file stamps that
// change with every write, Verilator's record of what it read, where an `include is found (and
// when another file would shadow it), the allowlist of Verilator flags, the names and locks of
// temporaries, and reproduce lines that a shell reads back unchanged. The whole path is tried
// against real RTL by tests/adversarial_test.sh.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "base/error.h"
#include "base/file_util.h"
#include "base/process.h"
#include "base/temporaries.h"
#include "base/text.h"
#include "sim/cosim/rtl_flags.h"
#include "sim/cosim/rtl_sources.h"
#include "tests/temp_dir.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// SHA-256 as sha256sum prints it (FIPS 180-2's "abc"), and fields that cannot run together.
TEST(ContentHash, IsSha256) {
  const phongsim::testing::TempDir dir;
  write(dir.path() / "abc", "abc");
  EXPECT_EQ(file_hash(dir.path() / "abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  ContentHash a, b;
  a.add("ab");
  a.add("c");
  b.add("a");
  b.add("bc");
  EXPECT_NE(a.hex(), b.hex());
  EXPECT_EQ(a.hex().size(), 64U);
}

// Any write moves a file's stamp, even one that leaves its size and content as they were.
TEST(FileStamp, ChangesWithEveryWrite) {
  const phongsim::testing::TempDir dir;
  const fs::path f = dir.path() / "a.sv";
  write(f, "module a; endmodule\n");
  const HashedFile before = hash_file(f);
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  write(f, "module a; endmodule\n");  // the same bytes again
  const HashedFile after = hash_file(f);
  EXPECT_EQ(before.hash, after.hash);
  EXPECT_NE(before.stamp, after.stamp);
  EXPECT_THROW((void)hash_file(dir.path() / "missing.sv"), Error);
}

// Verilator's own list of what it read (run for real), with the stamps it saw: the design's
// files and what they include, as absolute paths; its own executable left out.
TEST(VerilatorRead, ListsEveryFileItReadWithItsStamp) {
  const phongsim::testing::TempDir dir;
  fs::create_directories(dir.path() / "rtl" / "inc");
  write(dir.path() / "rtl" / "inc" / "w.svh", "localparam int W = 4;\n");
  write(dir.path() / "rtl" / "top.sv",
        "module top(input logic [3:0] a, output logic [3:0] b);\n`include \"inc/w.svh\"\n"
        "assign b = a + W[3:0];\nendmodule\n");
  const std::vector<fs::path> files{dir.path() / "rtl" / "top.sv"};
  const std::vector<fs::path> dirs = rtl_include_dirs({}, files);
  ASSERT_EQ(dirs, std::vector<fs::path>{dir.path() / "rtl"});
  fs::create_directories(dir.path() / "run");
  const ProcessResult r =
      run_process({"verilator", "--cc", "-Wno-fatal", "-Mdir", (dir.path() / "obj").string(),
                   "-I" + dirs[0].string(), files[0].string()},
                  {}, dir.path() / "run");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto read = verilator_read(dir.path() / "obj", "Vtop", dir.path() / "run");
  ASSERT_EQ(read.size(), 2U);
  const HashedFile top = hash_file(files[0]);
  const HashedFile inc = hash_file(dir.path() / "rtl" / "inc" / "w.svh");
  EXPECT_EQ(read.at(top.path), top.stamp);
  EXPECT_EQ(read.at(inc.path), inc.stamp);
  EXPECT_THROW((void)verilator_read(dir.path() / "nowhere", "Vtop", dir.path()), Error);
}

// An include is recorded by folder index and relative path, so that another checkout finds its
// own copy; a file of the same name in an earlier folder (which Verilator would read instead)
// makes the record unusable.
TEST(Includes, ResolveInTheirFolderUnlessShadowed) {
  const phongsim::testing::TempDir dir;
  const fs::path a = dir.path() / "a", b = dir.path() / "b";
  fs::create_directories(a);
  fs::create_directories(b / "sub");
  write(a / "x.sv", "");
  write(b / "y.sv", "");
  write(b / "sub" / "w.svh", "localparam int W = 1;\n");
  const std::vector<fs::path> dirs =
      rtl_include_dirs({}, std::vector<fs::path>{a / "x.sv", b / "y.sv"});
  const IncludedFile inc = locate_include(hash_file(b / "sub" / "w.svh"), dirs);
  EXPECT_EQ(inc.dir, 1);
  EXPECT_EQ(inc.rel, fs::path("sub") / "w.svh");
  EXPECT_EQ(resolve_include(inc, dirs), b / "sub" / "w.svh");
  // Another copy of the tree: its own file.
  const std::vector<fs::path> moved{dir.path() / "c", dir.path() / "d"};
  EXPECT_EQ(resolve_include(inc, moved), moved[1] / "sub" / "w.svh");
  // Shadowed, also by the name Verilator tries with .v or .sv appended.
  fs::create_directories(a / "sub");
  write(a / "sub" / "w.svh.sv", "");
  EXPECT_EQ(resolve_include(inc, dirs), std::nullopt);
  // Outside every folder: by its absolute path.
  write(dir.path() / "abs.svh", "");
  const IncludedFile abs = locate_include(hash_file(dir.path() / "abs.svh"), dirs);
  EXPECT_EQ(abs.dir, -1);
  EXPECT_EQ(resolve_include(abs, moved), dir.path() / "abs.svh");
}

// $PHONGSIM_VERILATOR_FLAGS: what only changes speed is taken, one dash or two; anything that
// could change the design, the X semantics or what is compiled is refused naming it.
TEST(VerilatorFlags, AllowlistOnly) {
  EXPECT_EQ(verilator_extra_flags(""), std::vector<std::string>{});
  EXPECT_EQ(verilator_extra_flags("-O2 --threads 2 -CFLAGS -march=native -Wno-WIDTH -fno-gate"),
            (std::vector<std::string>{"-O2", "--threads", "2", "-CFLAGS", "-march=native",
                                      "-Wno-WIDTH", "-fno-gate"}));
  for (const char* bad : {"-GOutRound=0",
                          "--GOutRound=0",
                          "-top-module x",
                          "--top x",
                          "x.cpp",
                          "x.sv",
                          "-x-initial 0",
                          "--x-assign unique",
                          "-DFOO",
                          "--DFOO",
                          "+define+FOO",
                          "-I/tmp",
                          "+incdir+/tmp",
                          "-f args",
                          "--f args",
                          "-F args",
                          "--exe",
                          "-y /tmp",
                          "-v a.sv",
                          "--no-assert",
                          "-CFLAGS -DFOO",
                          "-CFLAGS -include",
                          "-CFLAGS -ffast-math",
                          "-CFLAGS -fplugin=x.so",
                          "-LDFLAGS -lfoo",
                          "-LDFLAGS x.o",
                          "--threads=2",
                          "--threads",
                          "--threads two",
                          "-pvalue+X=1",
                          "--prefix V",
                          "-CFLAGS",
                          "--lib-create x"}) {
    SCOPED_TRACE(bad);
    try {
      (void)verilator_extra_flags(bad);
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("PHONGSIM_VERILATOR_FLAGS: "), std::string::npos);
      EXPECT_NE(std::string(e.what()).find(" is refused: "), std::string::npos) << e.what();
    }
  }
}

// Temporaries are known by name and owned by their lock: a locked one stays, an unlocked one old
// enough goes, and nothing named otherwise is touched.
TEST(Temporaries, NamesAndLocks) {
  EXPECT_TRUE(is_temporary_name("r.json.phongsim-tmp-Ab12Cd"));
  EXPECT_TRUE(is_temporary_name("build.phongsim-tmp-000000"));
  EXPECT_TRUE(is_temporary_name("phongsim-synth-xY9z01"));
  EXPECT_FALSE(is_temporary_name("r.json.phongsim-tmp-Ab12C"));    // 5 random characters
  EXPECT_FALSE(is_temporary_name("r.json.phongsim-tmp-Ab12Cd7"));  // 7
  EXPECT_FALSE(is_temporary_name("r.json.tmp.12345"));             // the old scheme: a user's
  EXPECT_FALSE(is_temporary_name("phongsim-cli.abcdef"));
  EXPECT_FALSE(is_temporary_name("phongsim-notours-abcdef"));

  const phongsim::testing::TempDir dir;
  const fs::path out = dir.path() / "r.json";
  std::optional<OwnedTemp> owned;
  owned.emplace(temp_prefix_beside(out), OwnedTemp::Kind::file);
  EXPECT_TRUE(is_temporary_name(owned->path().filename().string()));
  write(dir.path() / "r.json.phongsim-tmp-oldone", "{");
  write(dir.path() / "r.json.tmp.4242", "{");
  std::this_thread::sleep_for(std::chrono::milliseconds(2100));  // older than the grace
  sweep_stale_siblings(out);
  EXPECT_TRUE(fs::exists(owned->path()));  // locked: its owner lives
  EXPECT_FALSE(fs::exists(dir.path() / "r.json.phongsim-tmp-oldone"));
  EXPECT_TRUE(fs::exists(dir.path() / "r.json.tmp.4242"));
  const fs::path kept = owned->path();
  owned.reset();
  EXPECT_FALSE(fs::exists(kept));  // removed with its owner
}

// A printed command pastes back into a shell as the same words.
TEST(ShellQuoted, ReadsBackUnchanged) {
  EXPECT_EQ(shell_quoted("configs/lirp/default.toml"), "configs/lirp/default.toml");
  EXPECT_EQ(shell_quoted("a b"), "'a b'");
  EXPECT_EQ(shell_quoted("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_quoted(""), "''");
  EXPECT_EQ(shell_quoted("a\nb"), "$'a\\nb'");
  for (const std::string word : {"we ird/c$onfig.toml", "it's", "a\nb\tc'd\\e", "$(touch x)", "*",
                                 "-", "~", "a;b|c&d", "\"q\""}) {
    SCOPED_TRACE(word);
    const ProcessResult r = run_process({"bash", "-c", "printf %s " + shell_quoted(word)});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.out, word);
  }
}

}  // namespace
}  // namespace phongsim
