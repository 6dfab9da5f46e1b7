// The figures scripts/plot.py draws through plot_figure (sim/render/plot.h): a PNG from small
// data files for every figure, and one-line errors with no output file for bad data.
#include "sim/render/plot.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "base/error.h"
#include "sim/render/image.h"
#include "tests/temp_dir.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;

fs::path Write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const std::string& figure, const std::vector<std::string>& args,
                    const fs::path& out) {
  try {
    plot_figure(figure, args, out);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Only these files in `dir`: no temporary or partial output left behind.
void ExpectOnly(const fs::path& dir, std::vector<std::string> names) {
  std::vector<std::string> found;
  for (const auto& e : fs::directory_iterator(dir)) found.push_back(e.path().filename().string());
  std::sort(found.begin(), found.end());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(found, names);
}

// A PNG whose size is within the given bounds (figures are sized by matplotlib).
void ExpectPng(const fs::path& path, int min_width, int min_height) {
  const Image img = read_png(path);
  EXPECT_GE(img.width(), min_width) << path;
  EXPECT_GE(img.height(), min_height) << path;
  EXPECT_LE(img.width(), 4000) << path;
  EXPECT_LE(img.height(), 4000) << path;
  // Not blank: a figure has dark ink (text, axes) on its white background.
  int dark = 0;
  for (const Rgb8& p : img.pixels()) dark += p.r + p.g + p.b < 200 ? 1 : 0;
  EXPECT_GT(dark, 500) << path;
}

TEST(Plot, ScanlineFromASmallCsv) {
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
  const fs::path csv = Write(dir / "s.csv",
                             "x,phong [float] (reference),gouraud [rtl]\n"
                             "0,0,0\n1,0.25,0.2\n2,0.5,0.4\n3,1,0.6\n4,0.5,0.5\n5,0,0\n");
  plot_figure("scanline", {"--csv", csv.string(), "--title", "tiny: row 2"}, dir / "s.png");
  ExpectPng(dir / "s.png", 600, 300);
  ExpectOnly(dir, {"s.csv", "s.png"});
}

TEST(Plot, ManySeriesAreDrawn) {
  // 35 curves: more than any one colour cycle.
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
  std::string text = "x";
  for (int c = 0; c < 35; ++c) text += fmt::format(",curve {}", c);
  text += "\n";
  for (int x = 0; x < 50; ++x) {
    text += fmt::format("{}", x);
    for (int c = 0; c < 35; ++c) text += fmt::format(",{}", (x * (c + 1)) % 50 / 50.0);
    text += "\n";
  }
  plot_figure("scanline", {"--csv", Write(dir / "m.csv", text).string()}, dir / "m.png");
  ExpectPng(dir / "m.png", 800, 400);
}

TEST(Plot, BadDataIsOneLineAndNoFile) {
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
  const fs::path out = dir / "s.png";
  const fs::path csv = dir / "s.csv";
  const std::string prefix = "cannot write " + out.string() + ": plot.py: ";
  Write(csv, "x,a\n0,0.5\n1,zero\n");
  EXPECT_EQ(ErrorOf("scanline", {"--csv", csv.string()}, out),
            prefix + csv.string() + ":3: 'zero' is not a number");
  Write(csv, "x,a\n0,0.5\n1\n");
  EXPECT_EQ(ErrorOf("scanline", {"--csv", csv.string()}, out),
            prefix + csv.string() + ":3: 1 values, but the header has 2 columns");
  Write(csv, "pixel,a\n0,0.5\n");
  EXPECT_EQ(ErrorOf("scanline", {"--csv", csv.string()}, out),
            prefix + csv.string() + ":1: expected the header 'x,<curve>,...', got 'pixel,a'");
  Write(csv, "x,a\n");
  EXPECT_EQ(ErrorOf("scanline", {"--csv", csv.string()}, out),
            prefix + csv.string() + ": no data rows");
  EXPECT_EQ(ErrorOf("scanline", {"--csv", (dir / "none.csv").string()}, out),
            prefix + "cannot read " + (dir / "none.csv").string() + ": No such file or directory");
  Write(csv, "series,label,area,max_error,pareto\nall,#0,100,0.5,2\n");
  EXPECT_EQ(ErrorOf("pareto", {"--csv", csv.string()}, out),
            prefix + csv.string() + ":2: pareto must be 0 or 1, got '2'");
  // Usage errors end in argparse's one-line complaint.
  EXPECT_EQ(ErrorOf("histogram", {}, out).rfind("cannot write " + out.string() + ": ", 0), 0u);
  ExpectOnly(dir, {"s.csv"});
}

TEST(Plot, ParetoFrontAndLabels) {
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
  const fs::path csv = Write(dir / "p.csv",
                             "series,label,area,max_error,pareto\n"
                             "lyon/default,#0 d=S1.9,281264,0.19,0\n"
                             "lyon/default,#1 d=S1.10,285336,0.17,0\n"
                             "lyon/fig8_k2,#2 d=S1.9,268816,0.16,0\n"
                             "lyon/fig8_k2,#3 d=S1.10,267598,0.13,1\n");
  plot_figure("pareto",
              {"--csv", csv.string(), "--title", "t", "--x-label", "area: transistors", "--y-label",
               "max |error|"},
              dir / "p.png");
  ExpectPng(dir / "p.png", 600, 300);
}

TEST(Plot, GridOfImages) {
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
  Image a(40, 30, {200, 40, 40});
  Image b(40, 30, {0, 0, 0});
  b.at(10, 10) = {255, 255, 255};
  write_png(a, dir / "a.png");
  write_png(b, dir / "b.png");
  plot_figure("grid",
              {"--title", "scene", "--columns", "image", "difference", "--row",
               "phong [float] (reference)", (dir / "a.png").string(), "-", "--row", "gouraud [rtl]",
               (dir / "a.png").string(), (dir / "b.png").string()},
              dir / "g.png");
  ExpectPng(dir / "g.png", 2 * 40, 2 * 30);
  EXPECT_EQ(ErrorOf("grid",
                    {"--columns", "image", "--row", "x", (dir / "a.png").string(),
                     (dir / "b.png").string()},
                    dir / "g2.png"),
            "cannot write " + (dir / "g2.png").string() +
                ": plot.py: grid row 'x' has 2 images for 1 columns");
  EXPECT_FALSE(fs::exists(dir / "g2.png"));
}

}  // namespace
}  // namespace phongsim
