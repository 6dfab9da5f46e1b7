// Tests for sim/synth.*: Yosys generic and iCE40 synthesis with nextpnr of LIRP configurations,
// the content-keyed cache (in a temporary PHONGSIM_CACHE), the errors for a missing tool and a
// failing yosys run, and the logic depth of a design whose depth is known without Yosys
// (tests/synth_tb/depth_tree.sv). Needs yosys and nextpnr-ice40 (label synth); about 20 s.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "base/error.h"
#include "model/config.h"
#include "sim/explore/synth.h"
#include "sim/pipelines/registry.h"
#include "tests/error_of.h"

namespace {

namespace fs = std::filesystem;
using phongsim::Config;
using phongsim::StageDepth;
using phongsim::synthesize;
using phongsim::SynthOptions;
using phongsim::SynthResult;
using phongsim::testing::ErrorOf;

const fs::path kSourceDir = PHONGSIM_SOURCE_DIR;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A fresh directory per test, which is also the synthesis cache (PHONGSIM_CACHE).
class SynthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           fmt::format("phongsim_synth_test_{}_{}", getpid(), info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "configs");
    setenv("PHONGSIM_CACHE", (dir_ / "cache").c_str(), 1);
  }
  void TearDown() override {
    unsetenv("PHONGSIM_CACHE");
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // A configuration file in the test directory.
  fs::path Write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / "configs" / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  fs::path dir_;
};

// Synthesis of a configuration's built-in design.
SynthResult Synthesize(const Config& cfg, const SynthOptions& options, std::FILE* log) {
  return synthesize(phongsim::rtl_design(phongsim::find_pipeline(cfg.pipeline()), cfg),
                    cfg.origin(), options, log);
}

Config Lirp(const std::string& name) {
  return Config::load(kSourceDir / "configs" / "lirp" / (name + ".toml"));
}

TEST_F(SynthTest, LirpGenericAndIce40AreCachedByContent) {
  const SynthOptions both{.generic = true, .ice40 = true};
  const SynthResult r = Synthesize(Lirp("default"), both, stderr);
  EXPECT_FALSE(r.cached);
  EXPECT_GT(r.cells, 0);
  EXPECT_GT(r.transistors, r.cells);
  EXPECT_GT(r.lut4, 0);
  EXPECT_GT(r.carry, 0);
  EXPECT_GT(r.mac16, 0);  // the LIRP's three multipliers fit SB_MAC16s
  EXPECT_LE(r.mac16, 8);
  EXPECT_GT(r.ff, 0);
  EXPECT_TRUE(r.fits);
  EXPECT_GT(r.fmax_mhz, 0);
  EXPECT_EQ(r.key.size(), 64U);  // SHA-256
  const fs::path entry = dir_ / "cache" / "synth" / (r.key + ".json");
  EXPECT_TRUE(fs::exists(entry));
  EXPECT_NE(ReadFile(entry).find("\"fmax_mhz\""), std::string::npos);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "cache" / "synth")) {
    ++files;
    EXPECT_EQ(e.path().extension(), ".json") << e.path();  // no temporary left
  }
  EXPECT_EQ(files, 1);

  // Same content under another name: from the cache, without running the tools.
  const fs::path copy =
      Write("renamed.toml", ReadFile(kSourceDir / "configs" / "lirp" / "default.toml"));
  const SynthResult again = Synthesize(Config::load(copy), both, nullptr);
  EXPECT_TRUE(again.cached);
  EXPECT_EQ(again.key, r.key);
  EXPECT_EQ(again.cells, r.cells);
  EXPECT_EQ(again.transistors, r.transistors);
  EXPECT_EQ(again.lut4, r.lut4);
  EXPECT_EQ(again.carry, r.carry);
  EXPECT_EQ(again.mac16, r.mac16);
  EXPECT_EQ(again.ff, r.ff);
  EXPECT_EQ(again.fits, r.fits);
  EXPECT_EQ(again.fmax_mhz, r.fmax_mhz);
  EXPECT_GT(r.depth, 0);
  EXPECT_EQ(again.depth, r.depth);
  ASSERT_EQ(again.stages.size(), r.stages.size());
  for (std::size_t i = 0; i < r.stages.size(); ++i) {
    EXPECT_EQ(again.stages[i].to, r.stages[i].to);
    EXPECT_EQ(again.stages[i].levels, r.stages[i].levels);
    EXPECT_EQ(again.stages[i].from, r.stages[i].from);
  }
}

const StageDepth* Find(const SynthResult& r, const std::string& to, bool output) {
  for (const StageDepth& s : r.stages) {
    if (s.to == to && s.output == output) return &s;
  }
  return nullptr;
}

TEST_F(SynthTest, DepthOfAKnownDesign) {
  // Every level in tests/synth_tb/depth_tree.sv's header: a parity of 16 bits (4 levels, the
  // least two-input gates allow), an AND of 8 (3), a register in an instance (1), outputs.
  const fs::path tb = kSourceDir / "tests" / "synth_tb";
  phongsim::RtlDesign design;
  design.name = design.top = "depth_tree";
  design.files = {tb / "depth_tree_stage.sv", tb / "depth_tree.sv"};
  const SynthResult r =
      synthesize(design, "depth_tree", SynthOptions{.generic = true, .ice40 = false}, stderr);
  EXPECT_EQ(r.depth, 4);
  struct Want {
    std::string to;
    bool output;
    std::int64_t bits, levels;
    std::string from;
  };
  const Want want[] = {
      {"parity_q", false, 1, 4, "a_q"},
      {"all_q", false, 1, 3, "a_q"},
      {"u_stage.both_q", false, 1, 1, ""},
      {"mixed_o", true, 1, 1, ""},
      {"a_q", false, 16, 0, "a_i"},
      {"parity_o", true, 1, 0, "parity_q"},
      {"both_o", true, 1, 0, "u_stage.both_q"},
  };
  EXPECT_EQ(r.stages.size(), std::size(want));
  for (const Want& w : want) {
    const StageDepth* s = Find(r, w.to, w.output);
    ASSERT_NE(s, nullptr) << w.to;
    EXPECT_EQ(s->bits, w.bits) << w.to;
    EXPECT_EQ(s->levels, w.levels) << w.to;
    if (!w.from.empty()) {
      EXPECT_EQ(s->from, w.from) << w.to;
    }
  }
  // A path into both_q starts at parity_q or all_q; into mixed_o at parity_q or a_i.
  const StageDepth* both = Find(r, "u_stage.both_q", false);
  ASSERT_NE(both, nullptr);
  EXPECT_TRUE(both->from == "parity_q" || both->from == "all_q") << both->from;
  const StageDepth* mixed = Find(r, "mixed_o", true);
  ASSERT_NE(mixed, nullptr);
  EXPECT_TRUE(mixed->from == "parity_q" || mixed->from == "a_i") << mixed->from;
  // Deepest first.
  for (std::size_t i = 1; i < r.stages.size(); ++i) {
    EXPECT_GE(r.stages[i - 1].levels, r.stages[i].levels);
  }
}

TEST(LogicDepth, CombinationalLoopIsAnError) {
  // Two inverters driving each other (a netlist in write_json's shape).
  const std::string netlist = R"({"modules": {"loop": {
    "ports": {"y_o": {"direction": "output", "bits": [2]}},
    "cells": {
      "a": {"type": "$_NOT_", "port_directions": {"A": "input", "Y": "output"},
            "connections": {"A": [2], "Y": [3]}},
      "b": {"type": "$_NOT_", "port_directions": {"A": "input", "Y": "output"},
            "connections": {"A": [3], "Y": [2]}}},
    "netnames": {"y_o": {"hide_name": 0, "bits": [2]}}}}})";
  const std::string message = ErrorOf([&] { (void)phongsim::logic_depth(netlist, "loop"); });
  EXPECT_NE(message.find("combinational loop"), std::string::npos) << message;
}

TEST_F(SynthTest, NarrowerFormatsGiveFewerCells) {
  const SynthOptions generic{.generic = true, .ice40 = false};
  const SynthResult wide = Synthesize(Lirp("default"), generic, stderr);
  const fs::path narrow =
      Write("narrow.toml", ReadFile(kSourceDir / "configs" / "lirp" / "narrow.toml"));
  const SynthResult small = Synthesize(Config::load(narrow), generic, stderr);
  EXPECT_FALSE(small.cached);
  EXPECT_NE(small.key, wide.key);
  EXPECT_GT(small.cells, 0);
  EXPECT_LT(small.cells, wide.cells);
  EXPECT_LT(small.transistors, wide.transistors);
  EXPECT_EQ(small.lut4, -1);  // not asked for
  EXPECT_EQ(small.fmax_mhz, -1);
}

TEST_F(SynthTest, TooManyDspsDoesNotFit) {
  // The wide LIRP's operands (S1.15 x 1.16) are wider than a 16x16 SB_MAC16, so its three
  // products take more than the UP5K's eight: a result, not an error.
  const SynthResult r =
      Synthesize(Lirp("wide"), SynthOptions{.generic = false, .ice40 = true}, stderr);
  EXPECT_GT(r.mac16, 8);
  EXPECT_GT(r.lut4, 0);
  EXPECT_FALSE(r.fits);
  EXPECT_EQ(r.fmax_mhz, 0);
  EXPECT_EQ(r.cells, -1);  // not asked for
  EXPECT_TRUE(
      Synthesize(Lirp("wide"), SynthOptions{.generic = false, .ice40 = true}, nullptr).cached);
}

TEST_F(SynthTest, MissingToolIsNamedWithItsPackage) {
  const std::string path = getenv("PATH") != nullptr ? getenv("PATH") : "";
  setenv("PATH", (dir_ / "configs").c_str(), 1);  // no yosys there
  const std::string message =
      ErrorOf([] { (void)Synthesize(Lirp("default"), SynthOptions{}, nullptr); });
  setenv("PATH", path.c_str(), 1);
  EXPECT_NE(message.find("yosys"), std::string::npos) << message;
  EXPECT_NE(message.find("Debian package yosys"), std::string::npos) << message;
}

TEST_F(SynthTest, YosysFailureGivesItsLastLine) {
  // A parameter the RTL does not have: chparam fails.
  std::string text = ReadFile(kSourceDir / "configs" / "lirp" / "default.toml");
  text += "\n[param]\nno_such_param = 1\n";
  const fs::path bad = Write("bad.toml", text);
  const std::string message =
      ErrorOf([&] { (void)Synthesize(Config::load(bad), SynthOptions{}, nullptr); });
  EXPECT_NE(message.find("yosys synthesis of lirp_unit failed"), std::string::npos) << message;
  EXPECT_NE(message.find("NoSuchParam"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir_ / "cache" / "synth") &&
               !fs::is_empty(dir_ / "cache" / "synth"));  // nothing cached
}

}  // namespace
