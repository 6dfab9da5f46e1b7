// Tests for the TOML configuration loader (model/config.*) and the pipeline registry's use of it
// (sim/pipelines.*): accessors on a valid file, and that every kind of error is an Error whose
// message names the file (and, where there is one, the line and key).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "tests/error_of.h"

#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.h"
#include "model/config.h"
#include "model/fixed.h"
#include "model/lirp.h"
#include "sim/pipelines/registry.h"
#include "tests/temp_dir.h"

namespace {

namespace fx = phongsim::fx;
using phongsim::Config;
using phongsim::Error;

constexpr const char* kOrigin = "configs/lirp/mine.toml";

using phongsim::testing::ErrorOf;

Config Parse(const std::string& text) { return Config::parse(text, kOrigin); }

std::string ParseError(const std::string& text) {
  return ErrorOf([&] { (void)Parse(text); });
}

// A complete lirp configuration: p on line 5, a on 6, out on 7, `extra_format` from line 8.
std::string Lirp(const std::string& p = "S1.10", const std::string& a = "1.10",
                 const std::string& out = "S1.10", const std::string& extra_format = "") {
  return fmt::format(R"(pipeline = "lirp"
description = "a test config"

[format]
p = "{}"
a = "{}"
out = "{}"
{}
[mode]
out_round = "half_even"
out_overflow = "saturate"
)",
                     p, a, out, extra_format);
}

TEST(Config, HappyPathAccessors) {
  const Config cfg = Parse(
      "# comment\n"
      "pipeline = \"lirp\"\n"
      "description = \"a test config\"\n"
      "[format]\n"
      "p = \"S1.10\"\n"
      "a = \"1.10\"\n"
      "u = \"u2.3\"\n"
      "s = \"s0.62\"\n"  // 63 bits: the widest format allowed
      "[mode]\n"
      "r1 = \"truncate\"\n"
      "r2 = \"half_up\"\n"
      "r3 = \"half_even\"\n"
      "o1 = \"wrap\"\n"
      "o2 = \"saturate\"\n"
      "[param]\n"
      "k = 3\n"
      "neg = -5\n");
  EXPECT_EQ(cfg.origin(), kOrigin);
  EXPECT_EQ(cfg.name(), "mine");  // the origin's stem
  EXPECT_EQ(cfg.pipeline(), "lirp");
  EXPECT_EQ(cfg.description(), "a test config");
  EXPECT_EQ(cfg.format("p"), (fx::Format{true, 1, 10}));
  EXPECT_EQ(cfg.format("a"), (fx::Format{false, 1, 10}));
  EXPECT_EQ(cfg.format("u"), (fx::Format{false, 2, 3}));
  EXPECT_EQ(cfg.format("s"), (fx::Format{true, 0, 62}));
  EXPECT_EQ(cfg.round("r1"), fx::Round::truncate);
  EXPECT_EQ(cfg.round("r2"), fx::Round::half_up);
  EXPECT_EQ(cfg.round("r3"), fx::Round::half_even);
  EXPECT_EQ(cfg.overflow("o1"), fx::Overflow::wrap);
  EXPECT_EQ(cfg.overflow("o2"), fx::Overflow::saturate);
  EXPECT_EQ(cfg.param("k", 0, 7), 3);
  EXPECT_EQ(cfg.param("k", 3, 3), 3);  // bounds are inclusive
  EXPECT_EQ(cfg.param("neg", -5, 0), -5);
  EXPECT_NO_THROW(cfg.check_all_used());
}

TEST(Config, NameIsTheStemOfTheOrigin) {
  EXPECT_EQ(Config::parse("pipeline = \"lirp\"\n", "wide.toml").name(), "wide");
  EXPECT_EQ(Config::parse("pipeline = \"lirp\"\n", "/a/b.c/narrow.toml").name(), "narrow");
  EXPECT_EQ(Config::parse("pipeline = \"lirp\"\n", "plain").name(), "plain");
  // Description is optional.
  EXPECT_EQ(Config::parse("pipeline = \"lirp\"\n", "plain").description(), "");
}

TEST(Config, LoadsTheDefaultFile) {
  const std::string path = PHONGSIM_SOURCE_DIR "/configs/lirp/default.toml";
  const Config cfg = Config::load(path);
  EXPECT_EQ(cfg.origin(), path);
  EXPECT_EQ(cfg.name(), "default");
  EXPECT_EQ(cfg.pipeline(), "lirp");
  EXPECT_EQ(cfg.description(),
            "Lyon Fig. 7a widths: S1.10 vectors, 1.10 factor, convergent rounding, saturate");
  const auto f = phongsim::LirpFormats::from_config(cfg);
  EXPECT_EQ(f.p, (fx::Format{true, 1, 10}));
  EXPECT_EQ(f.a, (fx::Format{false, 1, 10}));
  EXPECT_EQ(f.out, (fx::Format{true, 1, 10}));
  EXPECT_EQ(f.out_round, fx::Round::half_even);
  EXPECT_EQ(f.out_overflow, fx::Overflow::saturate);
}

TEST(Config, LoadOfAMissingFileNamesIt) {
  const std::string path = PHONGSIM_SOURCE_DIR "/configs/lirp/no_such_config.toml";
  EXPECT_EQ(ErrorOf([&] { (void)Config::load(path); }), path + ": cannot read configuration file");
}

TEST(ConfigErrors, TomlSyntaxErrorNamesOriginAndLine) {
  const std::string what = ParseError(
      "pipeline = \"lirp\"\n"
      "[format]\n"
      "p = \"S1.10\n"  // unterminated string on line 3
      "a = \"1.10\"\n");
  EXPECT_EQ(what.rfind(std::string(kOrigin) + ":3: ", 0), 0u) << what;

  const std::string header = ParseError("pipeline = \"lirp\"\n\n[format\np = \"S1.10\"\n");
  EXPECT_EQ(header.rfind(std::string(kOrigin) + ":3: ", 0), 0u) << header;

  const std::string dup = ParseError("pipeline = \"lirp\"\npipeline = \"lirp\"\n");
  EXPECT_EQ(dup.rfind(std::string(kOrigin) + ":2: ", 0), 0u) << dup;
}

TEST(ConfigErrors, MissingPipeline) {
  EXPECT_EQ(ParseError("description = \"x\"\n[format]\np = \"S1.10\"\n"),
            std::string(kOrigin) + ": missing 'pipeline = \"<name>\"' at the top");
  EXPECT_EQ(ParseError(""), std::string(kOrigin) + ": missing 'pipeline = \"<name>\"' at the top");
  // A pipeline key inside a table is not the top-level one.
  EXPECT_EQ(ParseError("[param]\npipeline = \"lirp\"\n"),
            std::string(kOrigin) + ": missing 'pipeline = \"<name>\"' at the top");
}

TEST(ConfigErrors, PipelineAndDescriptionMustBeStrings) {
  EXPECT_EQ(ParseError("pipeline = 3\n"), std::string(kOrigin) + ":1: 'pipeline' must be a string");
  EXPECT_EQ(ParseError("pipeline = \"lirp\"\n\ndescription = [1]\n"),
            std::string(kOrigin) + ":3: 'description' must be a string");
}

TEST(ConfigErrors, UnknownTopLevelKey) {
  const std::string list = " (expected pipeline, description, [format], [mode], [param], [setup])";
  EXPECT_EQ(ParseError("pipeline = \"lirp\"\nformats = 3\n"),
            std::string(kOrigin) + ":2: unknown top-level key 'formats'" + list);
  EXPECT_EQ(ParseError("pipeline = \"lirp\"\n\n[modes]\nout_round = \"half_up\"\n"),
            std::string(kOrigin) + ":3: unknown top-level key 'modes'" + list);
}

TEST(ConfigErrors, TablesMustBeTablesOfStringsOrIntegers) {
  EXPECT_EQ(ParseError("pipeline = \"lirp\"\nformat = \"S1.10\"\n"),
            std::string(kOrigin) + ":2: 'format' must be a table ([format])");
  EXPECT_EQ(ParseError("pipeline = \"lirp\"\n[format]\np = 1.5\n"),
            std::string(kOrigin) + ":3: [format] p must be a string or an integer");
  EXPECT_EQ(ParseError("pipeline = \"lirp\"\n[param]\n\nk = true\n"),
            std::string(kOrigin) + ":4: [param] k must be a string or an integer");
}

TEST(ConfigErrors, FormatValueThatIsNotAFormat) {
  const Config cfg = Parse(Lirp("S1.1O"));  // letter O, not zero
  EXPECT_EQ(ErrorOf([&] { (void)cfg.format("p"); }),
            std::string(kOrigin) +
                ":5: [format] p: 'S1.1O' is not a fixed-point format (expected n.m or Sn.m, e.g. "
                "1.10 or S1.10)");
  const Config integer = Parse("pipeline = \"lirp\"\n[format]\np = 5\n");
  EXPECT_EQ(ErrorOf([&] { (void)integer.format("p"); }),
            std::string(kOrigin) +
                ":3: [format] p: '5' is not a fixed-point format (expected n.m or Sn.m, e.g. "
                "1.10 or S1.10)");
}

TEST(ConfigErrors, FormatOver63Bits) {
  const Config cfg = Parse(Lirp("S1.62", "0.64"));
  EXPECT_EQ(ErrorOf([&] { (void)cfg.format("p"); }),
            std::string(kOrigin) +
                ":5: [format] p: format S1.62: 64 bits exceeds the model's 63-bit limit (int64_t "
                "raw values)");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.format("a"); }),
            std::string(kOrigin) +
                ":6: [format] a: format 0.64: 64 bits exceeds the model's 63-bit limit (int64_t "
                "raw values)");
}

TEST(ConfigErrors, UnknownRoundingOrOverflowMode) {
  const Config cfg = Parse(
      "pipeline = \"lirp\"\n"
      "[mode]\n"
      "out_round = \"nearest\"\n"
      "out_overflow = \"clamp\"\n"
      "swapped = \"saturate\"\n");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.round("out_round"); }),
            std::string(kOrigin) +
                ":3: [mode] out_round: unknown rounding mode 'nearest' (expected truncate, "
                "half_up or half_even)");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.overflow("out_overflow"); }),
            std::string(kOrigin) +
                ":4: [mode] out_overflow: unknown overflow mode 'clamp' (expected wrap or "
                "saturate)");
  // An overflow name is not a rounding mode.
  EXPECT_EQ(ErrorOf([&] { (void)cfg.round("swapped"); }),
            std::string(kOrigin) +
                ":5: [mode] swapped: unknown rounding mode 'saturate' (expected truncate, "
                "half_up or half_even)");
}

TEST(ConfigErrors, MissingRequiredKey) {
  const Config cfg = Parse("pipeline = \"lirp\"\n[format]\np = \"S1.10\"\n");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.format("out"); }),
            std::string(kOrigin) + ": [format] is missing 'out' (required by pipeline lirp)");
  // Whole table absent.
  EXPECT_EQ(ErrorOf([&] { (void)cfg.round("out_round"); }),
            std::string(kOrigin) + ": [mode] is missing 'out_round' (required by pipeline lirp)");
  EXPECT_EQ(
      ErrorOf([&] { (void)cfg.overflow("out_overflow"); }),
      std::string(kOrigin) + ": [mode] is missing 'out_overflow' (required by pipeline lirp)");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.param("k", 0, 1); }),
            std::string(kOrigin) + ": [param] is missing 'k' (required by pipeline lirp)");
  // The key exists, but in another table.
  EXPECT_EQ(ErrorOf([&] { (void)cfg.round("p"); }),
            std::string(kOrigin) + ": [mode] is missing 'p' (required by pipeline lirp)");
}

TEST(ConfigErrors, UnknownExtraKey) {
  const Config cfg = Parse(Lirp("S1.10", "1.10", "S1.10", "q = \"S1.10\"\n"));
  (void)cfg.format("p");
  (void)cfg.format("a");
  (void)cfg.format("out");
  (void)cfg.round("out_round");
  (void)cfg.overflow("out_overflow");
  EXPECT_EQ(ErrorOf([&] { cfg.check_all_used(); }),
            std::string(kOrigin) + ":8: [format] q: unknown key for pipeline lirp");
  // Once asked for, it is no longer unknown.
  (void)cfg.format("q");
  EXPECT_NO_THROW(cfg.check_all_used());

  // A [param] key nobody asked for is unknown as well.
  const Config p = Parse("pipeline = \"lirp\"\n[param]\nk = 3\n");
  EXPECT_EQ(ErrorOf([&] { p.check_all_used(); }),
            std::string(kOrigin) + ":3: [param] k: unknown key for pipeline lirp");
}

// Documented: "Throws Error for the first key in the file that no accessor asked for". With
// two unknown keys, the one on the earlier line must be reported. FRAMEWORK BUG (minor):
// check_all_used() walks std::maps, so it reports the alphabetically first table/key instead.
TEST(ConfigErrors, CheckAllUsedReportsTheFirstUnknownKeyInTheFile) {
  const Config cfg = Parse(
      "pipeline = \"lirp\"\n"
      "[param]\n"
      "zz = 1\n"  // line 3: first unknown key in the file
      "[format]\n"
      "aa = \"S1.10\"\n");  // line 5
  EXPECT_EQ(ErrorOf([&] { cfg.check_all_used(); }),
            std::string(kOrigin) + ":3: [param] zz: unknown key for pipeline lirp");
}

TEST(ConfigErrors, ParamOutOfRangeOrNotAnInteger) {
  const Config cfg = Parse(
      "pipeline = \"lirp\"\n"
      "[param]\n"
      "k = 9\n"
      "s = \"three\"\n"
      "n = -1\n");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.param("k", 0, 7); }),
            std::string(kOrigin) + ":3: [param] k = 9 must be an integer in [0, 7]");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.param("k", 10, 20); }),
            std::string(kOrigin) + ":3: [param] k = 9 must be an integer in [10, 20]");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.param("s", 0, 7); }),
            std::string(kOrigin) + ":4: [param] s = three must be an integer in [0, 7]");
  EXPECT_EQ(ErrorOf([&] { (void)cfg.param("n", 0, 7); }),
            std::string(kOrigin) + ":5: [param] n = -1 must be an integer in [0, 7]");
  EXPECT_EQ(cfg.param("k", 9, 9), 9);
}

TEST(ConfigModel, LirpModelFromAValidConfig) {
  const Config cfg = Parse(Lirp("S1.6", "1.4", "S0.5"));
  const auto model = phongsim::make_model(phongsim::find_pipeline("lirp"), cfg);
  ASSERT_NE(model, nullptr);
  ASSERT_EQ(model->inputs().size(), 7u);
  ASSERT_EQ(model->outputs().size(), 3u);
  EXPECT_EQ(model->inputs()[0].name, "p0_x");
  EXPECT_EQ(model->inputs()[5].name, "p1_z");
  EXPECT_EQ(model->inputs()[6].name, "a");
  EXPECT_EQ(model->inputs()[6].fmt, (fx::Format{false, 1, 4}));
  EXPECT_EQ(model->outputs()[2].name, "p_z");
  EXPECT_EQ(model->outputs()[2].fmt, (fx::Format{true, 0, 5}));
}

TEST(ConfigModel, PipelineMismatchNamesBoth) {
  const Config cfg = Parse(
      "pipeline = \"shader\"\n"
      "[format]\np = \"S1.10\"\na = \"1.10\"\nout = \"S1.10\"\n"
      "[mode]\nout_round = \"half_even\"\nout_overflow = \"saturate\"\n");
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::make_model(phongsim::find_pipeline("lirp"), cfg); }),
            std::string(kOrigin) + ": configures pipeline 'shader', not 'lirp'");
}

TEST(ConfigModel, IntermediateOver63BitsIsRefusedNamingTheFile) {
  const auto& lirp = phongsim::find_pipeline("lirp");
  // delta = S1.40 - S1.40 is S2.40; a * delta = 1.40 * S2.40 needs 1 + 3 + 80 = 84 bits. The
  // message names the file, the stage (lirp.h: "fx::Error naming the stage") and the operation.
  const std::string text = Lirp("S1.40", "1.40", "S1.10");
  const std::string prod =
      "stage prod (a * delta): 1.40 * S2.40: the exact result needs 84 bits, over the model's "
      "63-bit limit (int64_t raw values)";
  const Config cfg = Parse(text);
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::make_model(lirp, cfg); }),
            std::string(kOrigin) + ": " + prod);

  // Same from a real file: the message names its path.
  const phongsim::testing::TempDir tmp;
  const std::filesystem::path path = tmp.path() / "config_test_huge.toml";
  {
    std::ofstream out(path);
    out << text;
  }
  const Config loaded = Config::load(path);
  EXPECT_EQ(loaded.name(), "config_test_huge");
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::make_model(lirp, loaded); }),
            path.string() + ": " + prod);

  // The boundary is the last stage, p0 + prod: S1.29 / 1.29 gives prod S3.58 (62 bits) and
  // sum S4.58 (63 bits), accepted; S1.29 / 1.30 gives prod S3.59 (63) but sum S4.59 (64).
  EXPECT_NO_THROW((void)phongsim::make_model(lirp, Parse(Lirp("S1.29", "1.29", "S1.10"))));
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::make_model(lirp, Parse(Lirp("S1.29", "1.30"))); }),
            std::string(kOrigin) +
                ": stage out (p0 + prod): S1.29 + S3.59: the exact result needs 64 bits, over "
                "the model's 63-bit limit (int64_t raw values)");
  // The first stage: S62.0 - S62.0 needs S63.0, 64 bits.
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::make_model(lirp, Parse(Lirp("S62.0", "1.0"))); }),
            std::string(kOrigin) +
                ": stage delta (p1 - p0): S62.0 - S62.0: the exact result needs 64 bits, over "
                "the model's 63-bit limit (int64_t raw values)");
}

TEST(ConfigModel, LirpRefusesIncompleteOrUnknownKeys) {
  const auto& lirp = phongsim::find_pipeline("lirp");
  // Unknown extra key: refused by name and line, not silently ignored.
  EXPECT_EQ(ErrorOf([&] {
              (void)phongsim::make_model(lirp,
                                         Parse(Lirp("S1.10", "1.10", "S1.10", "q = \"S1.10\"\n")));
            }),
            std::string(kOrigin) + ":8: [format] q: unknown key for pipeline lirp");
  // Missing key.
  const Config missing = Parse("pipeline = \"lirp\"\n[format]\np = \"S1.10\"\na = \"1.10\"\n");
  EXPECT_EQ(ErrorOf([&] { (void)phongsim::make_model(lirp, missing); }),
            std::string(kOrigin) + ": [format] is missing 'out' (required by pipeline lirp)");
}

TEST(Pipelines, FindPipeline) {
  EXPECT_EQ(phongsim::find_pipeline("lirp").name, "lirp");
  EXPECT_EQ(phongsim::find_pipeline("lyon").name, "lyon");
  ASSERT_EQ(phongsim::pipelines().size(), 7u);
  EXPECT_EQ(phongsim::pipelines()[0].name, "lirp");
  EXPECT_EQ(
      ErrorOf([] { (void)phongsim::find_pipeline("nope"); }),
      "unknown pipeline 'nope' (known: lirp, lyon, kb, quad, shade_lyon, shade_quad, shade_kb)");
  EXPECT_EQ(ErrorOf([] { (void)phongsim::find_pipeline(""); }),
            "unknown pipeline '' (known: lirp, lyon, kb, quad, shade_lyon, shade_quad, shade_kb)");
}

}  // namespace
