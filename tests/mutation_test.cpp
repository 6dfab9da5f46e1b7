// Mutation: every registry mutant (a deliberate one-line RTL bug) must be caught. Each is applied
// to a copy of rtl/ and co-simulated the way a user compares their own RTL, `phongsim cosim
// --rtl`, under random source and sink stalls. Caught means: exit 1, a first-failure report with
// a reproduce command and a waveform of the cycles before the failure; and that reproduce
// command, run as printed, fails the same way. A verification that cannot fail proves nothing.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "base/file_util.h"
#include "base/paths.h"
#include "base/process.h"
#include "sim/pipelines/registry.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;

struct Item {
  const PipelineInfo* pipeline;
  const Mutant* mutant;
};

void PrintTo(const Item& it, std::ostream* os) { *os << it.mutant->name; }

std::vector<Item> Items() {
  std::vector<Item> items;
  for (const PipelineInfo& p : pipelines()) {
    for (const Mutant& m : p.mutants) items.push_back({&p, &m});
  }
  return items;
}

std::size_t Count(const std::string& text, std::string_view what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The first line of the failure report ("MISMATCH at cycle 123, vector 45 ...").
std::string FirstFailure(const std::string& out) {
  static const std::regex first(
      R"(^(MISMATCH|UNEXPECTED OUTPUT|DEADLOCK|HANDSHAKE VIOLATION|RTL ASSERTION)[^\n]*)",
      std::regex::multiline);
  std::smatch m;
  return std::regex_search(out, m, first) ? m.str() : "";
}

class MutationTest : public ::testing::TestWithParam<Item> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("phongsim-mutant-{}-{}", getpid(), GetParam().mutant->name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path dir_;
};

TEST_P(MutationTest, IsCaughtAndReproduces) {
  const PipelineInfo& p = *GetParam().pipeline;
  const Mutant& m = *GetParam().mutant;
  SCOPED_TRACE(fmt::format("mutant {} ({}): {}", m.name, m.file, m.breaks));

  // The mutated copy of rtl/.
  fs::copy(data_root() / "rtl", dir_ / "rtl", fs::copy_options::recursive);
  const fs::path file = dir_ / m.file;
  std::string text = read_file(file);
  ASSERT_EQ(Count(text, m.from), 1U) << "the mutant's text must occur exactly once in " << m.file
                                     << " (update the mutant in sim/pipelines/)";
  text.replace(text.find(m.from), m.from.size(), m.to);
  std::ofstream(file, std::ios::binary) << text;

  const fs::path phongsim = phongsim_program();
  const fs::path config = data_root() / "configs" / p.name / (std::string(m.config) + ".toml");
  std::vector<std::string> argv{phongsim.string(), "cosim", "--config", config.string(), "--rtl"};
  for (const auto f : p.rtl_files) argv.push_back((dir_ / f).string());
  const fs::path trace = dir_ / "fail.fst";
  for (const char* a :
       {"--vectors", "20000", "--seed", "7", "--source-idle", "random:0.3", "--backpressure",
        "random:0.5", "--timeout", "2000", "--trace-window", "200"}) {
    argv.emplace_back(a);
  }
  argv.insert(argv.end(), {"--trace", trace.string()});
  const ProcessResult r = run_process(argv);
  ASSERT_EQ(r.exit_code, 1) << r.out;
  const std::string failure = FirstFailure(r.out);
  ASSERT_FALSE(failure.empty()) << r.out;
  EXPECT_NE(r.out.find("waveform of cycles"), std::string::npos) << r.out;
  if (!m.report.empty()) {  // seen by an RTL assertion, not by comparing outputs
    EXPECT_TRUE(failure.starts_with("RTL ASSERTION")) << r.out;
    EXPECT_NE(r.out.find(m.report), std::string::npos) << r.out;
  }
  ASSERT_TRUE(fs::exists(trace) && fs::file_size(trace) > 0);

  // The printed reproduce command, run as printed (through a shell, as a user pastes it): it
  // begins with the program as it was run.
  static const std::regex repro(R"(reproduce: ([^\n]*))");
  std::smatch rm;
  ASSERT_TRUE(std::regex_search(r.out, rm, repro)) << r.out;
  EXPECT_TRUE(rm[1].str().starts_with(phongsim.string() + " cosim ")) << rm[1];
  EXPECT_NE(rm[1].str().find("--rtl "), std::string::npos) << "the command must name the RTL";
  const ProcessResult again = run_process({"/bin/sh", "-c", rm[1].str()});
  EXPECT_EQ(again.exit_code, 1) << again.out;
  EXPECT_EQ(FirstFailure(again.out), failure) << again.out;
}

std::string Name(const ::testing::TestParamInfo<Item>& info) {
  std::string n(info.param.mutant->name);
  for (char& c : n) {
    if (c == '-') c = '_';
  }
  return n;
}

INSTANTIATE_TEST_SUITE_P(Registry, MutationTest, ::testing::ValuesIn(Items()), Name);

}  // namespace
}  // namespace phongsim
