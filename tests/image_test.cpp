// Image utilities: PNG through libpng (round trips, the header the spec fixes, atomic writes, read
// errors for truncated, corrupt and unsupported files), Vlasic's difference image and metrics on
// hand-computed images, text boxes, grids and plots.
#include "sim/render/image.h"

#include <gtest/gtest.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "base/error.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("image_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Bytes ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const fs::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

std::uint32_t U32(const Bytes& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}

// Deterministic pseudo-random image (an LCG; no dependence on library distributions).
Image Noise(int w, int h, std::uint32_t seed) {
  Image img(w, h);
  std::uint32_t s = seed;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      s = s * 1664525u + 1013904223u;
      img.at(x, y) = {static_cast<std::uint8_t>(s >> 24), static_cast<std::uint8_t>(s >> 16),
                      static_cast<std::uint8_t>(s >> 8)};
    }
  }
  return img;
}

Image Gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      img.at(x, y) = {static_cast<std::uint8_t>(x * 7), static_cast<std::uint8_t>(y * 3),
                      static_cast<std::uint8_t>((x + y) / 2)};
    }
  }
  return img;
}

// Error whose message contains `part`, or a test failure.
template <typename F>
void ExpectErrorContaining(F&& f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no Error thrown; expected one containing '" << part << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

// ---- Image ----

TEST(Image, ConstructsFilledAndRefusesBadSizes) {
  Image img(3, 2, {1, 2, 3});
  EXPECT_EQ(img.width(), 3);
  EXPECT_EQ(img.height(), 2);
  EXPECT_EQ(img.pixels().size(), 6u);
  for (const Rgb8& p : img.pixels()) EXPECT_EQ(p, (Rgb8{1, 2, 3}));
  img.at(2, 1) = {9, 9, 9};
  EXPECT_EQ(img.pixels()[5], (Rgb8{9, 9, 9}));  // row-major
  img.at(1, 0) = {7, 7, 7};
  EXPECT_EQ(img.pixels()[1], (Rgb8{7, 7, 7}));
  EXPECT_NE(img, Image(3, 2, {1, 2, 3}));
  EXPECT_EQ(Image(), Image(0, 0));
  EXPECT_NO_THROW(Image(32768, 0));
  EXPECT_THROW(Image(-1, 1), Error);
  EXPECT_THROW(Image(1, -1), Error);
  EXPECT_THROW(Image(32769, 1), Error);
  EXPECT_THROW(Image(1, 32769), Error);
}

// ---- PNG ----

TEST(Png, RoundTripsSeveralSizes) {
  const fs::path dir = TempDir("roundtrip");
  std::vector<Image> images = {Image(1, 1, {200, 10, 30}),
                               Noise(1, 1, 5),
                               Noise(3, 1, 1),
                               Noise(1, 4, 2),
                               Noise(7, 5, 3),
                               Gradient(33, 17),
                               Noise(257, 31, 4),
                               Gradient(200, 120)};
  for (std::size_t i = 0; i < images.size(); ++i) {
    const fs::path path = dir / ("img" + std::to_string(i) + ".png");
    write_png(images[i], path);
    EXPECT_EQ(read_png(path), images[i]) << images[i].width() << "x" << images[i].height();
  }
  // Only the PNGs: no temporary files left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()),
            static_cast<long>(images.size()));
}

TEST(Png, OverwritesAnExistingFile) {
  const fs::path path = TempDir("overwrite") / "a.png";
  write_png(Noise(5, 5, 1), path);
  write_png(Noise(4, 6, 2), path);
  EXPECT_EQ(read_png(path), Noise(4, 6, 2));
}

TEST(Png, SignatureAndHeaderFollowTheSpec) {
  const fs::path path = TempDir("header") / "h.png";
  write_png(Noise(300, 2, 7), path);
  const Bytes b = ReadBytes(path);
  ASSERT_GT(b.size(), 8u + 25u + 12u);
  // PNG spec 5.2: the signature.
  const Bytes signature = {137, 80, 78, 71, 13, 10, 26, 10};
  EXPECT_EQ(Bytes(b.begin(), b.begin() + 8), signature);
  // IHDR: length 13, type, width 300 = 0x12C, height 2, depth 8, colour type 2 (truecolour),
  // compression 0, filter method 0, no interlace.
  const Bytes ihdr = {0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0x01, 0x2C, 0, 0, 0, 2, 8, 2, 0, 0, 0};
  EXPECT_EQ(Bytes(b.begin() + 8, b.begin() + 8 + 21), ihdr);
  // ... and the file ends with the IEND chunk (spec 11.2.5; its CRC is a constant).
  const Bytes iend = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  EXPECT_EQ(Bytes(b.end() - 12, b.end()), iend);
}

TEST(Png, FailedWritesLeaveNoFile) {
  const fs::path dir = TempDir("unwritable");
  const fs::path missing = dir / "no-such-dir" / "x.png";
  ExpectErrorContaining([&] { write_png(Noise(4, 4, 1), missing); },
                        "cannot write " + missing.string());
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_FALSE(fs::exists(missing.parent_path()));

  // A directory in the way.
  fs::create_directories(dir / "d.png");
  ExpectErrorContaining([&] { write_png(Noise(4, 4, 1), dir / "d.png"); }, "cannot write");

  // PNG has no empty images: refused before anything is created.
  ExpectErrorContaining([&] { write_png(Image(0, 3), dir / "empty.png"); },
                        "cannot write " + (dir / "empty.png").string());
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
  // Nothing but the directory made above.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

// A valid PNG of another kind than 8-bit RGB, made by libpng itself: `format` is one of
// libpng's PNG_FORMAT_* values, `bytes_per_pixel` its size.
void WriteOtherPng(const fs::path& path, png_uint_32 format, int bytes_per_pixel) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 2;
  image.height = 2;
  image.format = format;
  const Bytes pixels(static_cast<std::size_t>(4 * bytes_per_pixel), 100);
  ASSERT_NE(png_image_write_to_file(&image, path.c_str(), 0, pixels.data(), 0, nullptr), 0)
      << image.message;
}

TEST(Png, ReadErrorsNameTheFile) {
  const fs::path dir = TempDir("readerr");
  ExpectErrorContaining([&] { (void)read_png(dir / "absent.png"); },
                        "cannot read " + (dir / "absent.png").string() + ": ");

  const fs::path garbage = dir / "garbage.png";
  WriteBytes(garbage, Bytes(100, 0x5a));
  ExpectErrorContaining([&] { (void)read_png(garbage); }, "cannot read " + garbage.string());
  ExpectErrorContaining([&] { (void)read_png(garbage); },
                        "cannot read " + garbage.string() + ": Not a PNG file");
  WriteBytes(garbage, {});
  ExpectErrorContaining([&] { (void)read_png(garbage); },
                        "cannot read " + garbage.string() + ": the file ends early");

  // Every truncation of a valid file before its last chunk (IEND, which libpng's reader of
  // whole images does not look at) is refused.
  const fs::path good = dir / "good.png";
  write_png(Noise(9, 4, 3), good);
  const Bytes b = ReadBytes(good);
  const fs::path cut = dir / "cut.png";
  for (std::size_t n = 0; n + 12 < b.size(); ++n) {
    WriteBytes(cut, Bytes(b.begin(), b.begin() + static_cast<long>(n)));
    ExpectErrorContaining([&] { (void)read_png(cut); },
                          "cannot read " + cut.string() + ": the file ends early");
  }

  // A flipped bit in the first IDAT's data fails its CRC.
  Bytes flipped = b;
  std::size_t idat = 8;
  while (std::string(reinterpret_cast<const char*>(&b[idat + 4]), 4) != "IDAT") {
    idat += 12 + U32(b, idat);
  }
  flipped[idat + 8 + 2] ^= 0x01;
  WriteBytes(cut, flipped);
  ExpectErrorContaining([&] { (void)read_png(cut); }, "cannot read " + cut.string() + ": ");

  // Valid PNGs of kinds the reader does not take.
  const fs::path other = dir / "other.png";
  const std::string unsupported = "cannot read " + other.string() +
                                  ": unsupported PNG format (only 8-bit RGB without transparency "
                                  "is read)";
  const std::vector<std::pair<png_uint_32, int>> others = {
      {PNG_FORMAT_GRAY, 1}, {PNG_FORMAT_RGBA, 4}, {PNG_FORMAT_LINEAR_RGB, 6}};
  for (const auto& [format, size] : others) {
    WriteOtherPng(other, format, size);
    ExpectErrorContaining([&] { (void)read_png(other); }, unsupported);
  }
}

// ---- evaluation ----

TEST(DifferenceImage, FollowsEquation62) {
  Image a(4, 1);
  Image b(4, 1);
  a.at(0, 0) = {0, 255, 10};  // |d| = 0, 255, 1
  b.at(0, 0) = {0, 0, 11};
  a.at(1, 0) = {128, 30, 200};  // |d| = 2, 30, 200
  b.at(1, 0) = {130, 0, 0};
  const Image d = difference_image(a, b);
  ASSERT_EQ(d.width(), 4);
  ASSERT_EQ(d.height(), 1);
  // 255 * (1/255)^0.1 = 146.516..., 255 * (2/255)^0.1 = 157.03...
  EXPECT_EQ(d.at(0, 0), (Rgb8{0, 255, 147}));
  EXPECT_EQ(d.at(1, 0).r, 157);
  EXPECT_EQ(d.at(1, 0).g, std::lround(255 * std::pow(30 / 255.0, 0.1)));
  EXPECT_EQ(d.at(1, 0).b, std::lround(255 * std::pow(200 / 255.0, 0.1)));
  EXPECT_EQ(d.at(2, 0), (Rgb8{0, 0, 0}));
  EXPECT_EQ(difference_image(b, a), d);  // |A - B|: symmetric
  EXPECT_THROW((void)difference_image(Image(2, 2), Image(2, 3)), Error);
}

TEST(Compare, HandComputedTwoByTwo) {
  const Image ref(2, 2, {100, 100, 100});
  Image img = ref;
  img.at(1, 0) = {110, 100, 100};  // |d| 10
  img.at(0, 1) = {100, 90, 100};   // |d| 10
  img.at(1, 1) = {100, 100, 70};   // |d| 30
  const ImageMetrics m = compare(ref, img);
  EXPECT_EQ(m.pixels, 4u);
  EXPECT_EQ(m.max_error, 30);
  EXPECT_DOUBLE_EQ(m.colour_correctness, 1.0 - 50.0 / (3 * 255 * 4));
  EXPECT_DOUBLE_EQ(m.psnr, 10 * std::log10(255.0 * 255.0 / ((100 + 100 + 900) / 12.0)));
  EXPECT_NEAR(m.psnr, 28.51, 0.01);

  // Mask: only the top row (pixels 0 and 1, row-major).
  const ImageMetrics top = compare(ref, img, {true, true, false, false});
  EXPECT_EQ(top.pixels, 2u);
  EXPECT_EQ(top.max_error, 10);
  EXPECT_DOUBLE_EQ(top.colour_correctness, 1.0 - 10.0 / (3 * 255 * 2));
  EXPECT_DOUBLE_EQ(top.psnr, 10 * std::log10(255.0 * 255.0 / (100 / 6.0)));

  // Only the unchanged pixel: identical within the mask.
  const ImageMetrics same = compare(ref, img, {true, false, false, false});
  EXPECT_EQ(same.pixels, 1u);
  EXPECT_EQ(same.max_error, 0);
  EXPECT_EQ(same.colour_correctness, 1.0);
  EXPECT_TRUE(std::isinf(same.psnr) && same.psnr > 0);

  EXPECT_EQ(compare(ref, img, {false, false, false, false}).pixels, 0u);
  EXPECT_THROW((void)compare(ref, img, {true, true, true}), Error);
  EXPECT_THROW((void)compare(ref, Image(2, 1)), Error);
}

TEST(Compare, IdenticalAndOppositeExtremes) {
  const Image a = Noise(5, 3, 1);
  const ImageMetrics same = compare(a, a);
  EXPECT_EQ(same.pixels, 15u);
  EXPECT_EQ(same.colour_correctness, 1.0);
  EXPECT_TRUE(std::isinf(same.psnr) && same.psnr > 0);
  EXPECT_EQ(same.max_error, 0);
  // Black against white: every channel off by 255, so cc 0 and PSNR 10 log10(1) = 0 dB.
  const ImageMetrics worst = compare(Image(3, 3, {0, 0, 0}), Image(3, 3, {255, 255, 255}));
  EXPECT_DOUBLE_EQ(worst.colour_correctness, 0.0);
  EXPECT_DOUBLE_EQ(worst.psnr, 0.0);
  EXPECT_EQ(worst.max_error, 255);
}

TEST(Illumination, RowFollowsEquation63) {
  Image img(3, 2, {9, 9, 9});
  img.at(0, 1) = {255, 255, 255};
  img.at(1, 1) = {0, 0, 0};
  img.at(2, 1) = {255, 0, 51};
  const std::vector<double> row = illumination_row(img, 1);
  ASSERT_EQ(row.size(), 3u);
  EXPECT_DOUBLE_EQ(row[0], 1.0);
  EXPECT_DOUBLE_EQ(row[1], 0.0);
  EXPECT_DOUBLE_EQ(row[2], 306.0 / 765.0);
  EXPECT_DOUBLE_EQ(illumination_row(img, 0)[2], 27.0 / 765.0);
  EXPECT_THROW((void)illumination_row(img, 2), Error);
  EXPECT_THROW((void)illumination_row(img, -1), Error);
}

// ---- text, blit, grid ----

struct Ink {
  int count = 0;
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;  // bounding box, inclusive
};

Ink InkOf(const Image& img, Rgb8 colour) {
  Ink ink;
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      if (img.at(x, y) != colour) continue;
      ++ink.count;
      ink.x0 = std::min(ink.x0, x);
      ink.y0 = std::min(ink.y0, y);
      ink.x1 = std::max(ink.x1, x);
      ink.y1 = std::max(ink.y1, y);
    }
  }
  return ink;
}

TEST(Text, SizesFollowTheFiveBySevenCell) {
  EXPECT_EQ(text_width(""), 0);
  EXPECT_EQ(text_width("A"), 5);
  EXPECT_EQ(text_width("AB"), 11);  // 5 + 1 gap + 5
  EXPECT_EQ(text_width("AB", 3), 33);
  EXPECT_GE(text_height(), 7);
  EXPECT_EQ(text_height(4), 4 * text_height());
  EXPECT_EQ(text_width("\xc3\xa9"), 5);  // one UTF-8 character
  EXPECT_THROW((void)text_width("A", 0), Error);
}

TEST(Text, DrawsInsideItsBoxOnly) {
  const Rgb8 ink{200, 0, 0};
  for (const int scale : {1, 2, 3}) {
    for (const std::string_view text : {"Hello, world!", "gjpqy_", "M", "|", "0.25 (x, y)"}) {
      Image img(300, 60, kWhite);
      draw_text(img, 7, 5, text, ink, scale);
      const Ink got = InkOf(img, ink);
      ASSERT_GT(got.count, 0) << text;
      EXPECT_EQ(got.count + InkOf(img, kWhite).count, 300 * 60) << "only the two colours";
      EXPECT_GE(got.x0, 7) << text;
      EXPECT_GE(got.y0, 5) << text;
      EXPECT_LT(got.x1, 7 + text_width(text, scale)) << text;
      EXPECT_LT(got.y1, 5 + text_height(scale)) << text;
    }
  }
  // 'M' spans its full width: the box is tight.
  Image m(20, 20, kWhite);
  draw_text(m, 2, 3, "M", kBlack, 2);
  const Ink got = InkOf(m, kBlack);
  EXPECT_EQ(got.x0, 2);
  EXPECT_EQ(got.x1, 2 + text_width("M", 2) - 1);
  EXPECT_EQ(got.y0, 3);
}

TEST(Text, EveryGlyphIsDistinctAndScalesByArea) {
  std::set<std::string> seen;  // glyph bitmaps as '#'/'.' strings
  for (int c = 32; c <= 126; ++c) {
    const std::string s(1, static_cast<char>(c));
    Image img(text_width(s), text_height(), kWhite);
    draw_text(img, 0, 0, s, kBlack);
    const int count = InkOf(img, kBlack).count;
    if (c == ' ') {
      EXPECT_EQ(count, 0);
    } else {
      EXPECT_GT(count, 0) << s;
    }
    std::string bitmap;
    for (const Rgb8& px : img.pixels()) bitmap += px == kBlack ? '#' : '.';
    EXPECT_TRUE(seen.insert(bitmap).second) << "glyph '" << s << "' repeats another";
    Image big(text_width(s, 3), text_height(3), kWhite);
    draw_text(big, 0, 0, s, kBlack, 3);
    EXPECT_EQ(InkOf(big, kBlack).count, 9 * count) << s;
  }
}

TEST(Text, OutOfRangeCharactersDrawAsQuestionMark) {
  Image q(40, 12, kWhite);
  draw_text(q, 1, 1, "a?b", kBlack);
  for (const std::string& odd : {std::string("a\x01"
                                             "b"),
                                 std::string("a\x7f"
                                             "b"),
                                 std::string("a\xc3\xa9"
                                             "b"),
                                 std::string("a\tb")}) {
    Image img(40, 12, kWhite);
    draw_text(img, 1, 1, odd, kBlack);
    EXPECT_EQ(img, q);
  }
}

TEST(Text, ClipsAtTheEdges) {
  Image img(10, 6, kWhite);
  draw_text(img, -3, -4, "WWWW", kBlack, 2);
  EXPECT_GT(InkOf(img, kBlack).count, 0);
  EXPECT_THROW(draw_text(img, 0, 0, "x", kBlack, 0), Error);
}

TEST(Blit, CopiesAndClips) {
  const Image src = Noise(4, 3, 2);
  Image dst(6, 5, kWhite);
  blit(dst, src, 1, 2);
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 6; ++x) {
      const bool inside = x >= 1 && x < 5 && y >= 2 && y < 5;
      EXPECT_EQ(dst.at(x, y), inside ? src.at(x - 1, y - 2) : kWhite) << x << "," << y;
    }
  }
  Image corner(3, 3, kWhite);
  blit(corner, src, -2, -1);  // only src (2..3, 1..2) lands, at (0..1, 0..1)
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 3; ++x) {
      EXPECT_EQ(corner.at(x, y), x < 2 && y < 2 ? src.at(x + 2, y + 1) : kWhite) << x << "," << y;
    }
  }
  blit(corner, src, 3, 0);  // entirely outside: nothing
  blit(corner, src, -4, -3);
  EXPECT_EQ(corner.at(2, 2), kWhite);
}

TEST(Grid, EveryCellIsShownWhole) {
  const Rgb8 red{255, 0, 0}, green{0, 255, 0}, blue{0, 0, 255};
  std::vector<std::vector<Image>> cells = {{Image(10, 10, red), Image(20, 5, green)},
                                           {Image(30, 8, blue)}};
  const Image g = grid(cells, {}, {});
  EXPECT_EQ(InkOf(g, red).count, 100);
  EXPECT_EQ(InkOf(g, green).count, 100);
  EXPECT_EQ(InkOf(g, blue).count, 240);
  EXPECT_EQ(InkOf(g, kWhite).count, g.width() * g.height() - 440);
  // The second row sits below the first, columns side by side with padding.
  EXPECT_GT(InkOf(g, blue).y0, InkOf(g, red).y1);
  EXPECT_GT(InkOf(g, green).x0, InkOf(g, red).x1);
  EXPECT_GE(g.width(), 30 + 20);
  EXPECT_GE(g.height(), 10 + 8);
  // An empty cell keeps its slot blank.
  cells[1].insert(cells[1].begin(), Image());
  const Image h = grid(cells, {}, {});
  EXPECT_EQ(InkOf(h, blue).count, 240);
  EXPECT_GT(InkOf(h, blue).x0, InkOf(h, red).x1);  // now in the second column
}

TEST(Grid, SizeAccountsForLabelsAndTitle) {
  const Rgb8 red{255, 0, 0};
  const std::vector<std::vector<Image>> cells = {{Image(10, 10, red), Image(10, 10, red)},
                                                 {Image(10, 10, red), Image(10, 10, red)}};
  const Image plain = grid(cells, {}, {});
  EXPECT_EQ(InkOf(plain, kBlack).count, 0);

  const std::string row_label = "a long row label";
  const Image rows = grid(cells, {row_label, "r2"}, {});
  EXPECT_GE(rows.width(), plain.width() + text_width(row_label));
  EXPECT_EQ(rows.height(), plain.height());
  EXPECT_LT(InkOf(rows, kBlack).x1 + 2, InkOf(rows, red).x0);  // labels left, not touching
  EXPECT_EQ(InkOf(rows, red).count, 400);

  const std::string col_label = "column label wider than its cells";
  const Image cols = grid(cells, {}, {col_label, "c2"});
  EXPECT_GE(cols.width(), plain.width() - 10 + text_width(col_label));
  EXPECT_GE(cols.height(), plain.height() + text_height());
  EXPECT_LT(InkOf(cols, kBlack).y1, InkOf(cols, red).y0);  // labels above the cells
  EXPECT_EQ(InkOf(cols, red).count, 400);

  const std::string title = "A title that is wider than the whole grid";
  const Image titled = grid(cells, {}, {}, title);
  EXPECT_GE(titled.width(), text_width(title));
  EXPECT_GE(titled.height(), plain.height() + text_height());
  EXPECT_EQ(InkOf(titled, red).count, 400);

  const Image all = grid(cells, {row_label, "r2"}, {col_label, "c2"}, title);
  EXPECT_GE(all.width(), text_width(row_label) + text_width(col_label) + 10);
  EXPECT_GE(all.height(), 20 + 2 * text_height());
  EXPECT_EQ(InkOf(all, red).count, 400);

  const Image empty = grid({}, {}, {});
  EXPECT_FALSE(empty.empty());
}

// ---- plot ----

TEST(Plot, SizeColoursAndCurvePlacement) {
  std::vector<Curve> curves = {{"top", std::vector<double>(100, 1.0)},
                               {"bottom", std::vector<double>(100, 0.0)},
                               {"short", std::vector<double>(10, 0.5)}};
  const Image p = plot_curves(curves, "scanline y = 12");
  EXPECT_EQ(p.width(), 800);
  EXPECT_EQ(p.height(), 400);
  const Image q = plot_curves(curves, "t", 300, 200);
  EXPECT_EQ(q.width(), 300);
  EXPECT_EQ(q.height(), 200);

  std::set<std::tuple<int, int, int>> colours;
  for (std::size_t i = 0; i < 8; ++i) {
    const Rgb8 c = curve_colour(i);
    EXPECT_NE(c, kWhite);
    EXPECT_NE(c, kBlack);
    colours.insert({c.r, c.g, c.b});
  }
  EXPECT_EQ(colours.size(), 8u);

  // Only the left 70% of the image: the legend swatches are at the right.
  const auto left_ink = [&](Rgb8 colour) {
    Image crop(p.width() * 7 / 10, p.height());
    blit(crop, p, 0, 0);
    return InkOf(crop, colour);
  };
  const Ink top = left_ink(curve_colour(0));
  const Ink bottom = left_ink(curve_colour(1));
  const Ink mid = left_ink(curve_colour(2));
  ASSERT_GT(top.count, 100);
  ASSERT_GT(bottom.count, 100);
  ASSERT_GT(mid.count, 10);
  EXPECT_LT(top.y1, mid.y0);  // 1 above 0.5 above 0
  EXPECT_LT(mid.y1, bottom.y0);
  EXPECT_LE(top.y1 - top.y0, 2);  // constant curves are horizontal lines
  EXPECT_GT(top.x1 - top.x0, p.width() / 3);
  EXPECT_LT(mid.x1 - mid.x0, (top.x1 - top.x0) / 5);  // 10 of 100 columns
  EXPECT_LE(mid.x0, top.x0 + 2);                      // both start at column 0
  // The legend shows each colour at the right as well.
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_GT(InkOf(p, curve_colour(i)).x1, p.width() * 7 / 10) << i;
  }
  // Text (title, ticks, legend labels) is black.
  EXPECT_GT(InkOf(p, kBlack).count, 500);
}

TEST(Plot, ClampsOutOfRangeValuesAndBreaksAtNaN) {
  const std::vector<Curve> curves = {{"one", std::vector<double>(50, 1.0)},
                                     {"above", std::vector<double>(50, 7.0)},
                                     {"below", std::vector<double>(50, -3.0)},
                                     {"zero", std::vector<double>(50, 0.0)},
                                     {"gap", {0.5, NAN, 0.5}}};
  const Image p = plot_curves(curves, "clamp");
  Image left(p.width() * 7 / 10, p.height());
  blit(left, p, 0, 0);
  // Drawn over each other: "above" hides "one" at the top, "below" is hidden by "zero".
  const Ink above = InkOf(left, curve_colour(1));
  EXPECT_GT(above.count, 100);
  EXPECT_EQ(InkOf(left, curve_colour(0)).count, 0);
  EXPECT_EQ(InkOf(left, curve_colour(2)).count, 0);
  EXPECT_GT(InkOf(left, curve_colour(3)).count, 100);
  EXPECT_LT(above.y1, InkOf(left, curve_colour(3)).y0);
  // The NaN leaves two isolated points (2x2 each), no segment between them.
  const Ink gap = InkOf(left, curve_colour(4));
  EXPECT_GT(gap.count, 0);
  EXPECT_LE(gap.count, 8);
  EXPECT_GT(gap.x1 - gap.x0, 10);
}

TEST(Plot, OddInputsAndTooSmall) {
  const std::vector<Curve> odd = {{"nan", {0.2, NAN, 0.4, 2.0, -1.0}}, {"one", {0.5}}, {"", {}}};
  const Image p = plot_curves(odd, "");
  EXPECT_EQ(p.width(), 800);
  EXPECT_GT(InkOf(p, curve_colour(1)).count, 0);
  EXPECT_EQ(plot_curves({}, "empty").width(), 800);
  EXPECT_THROW((void)plot_curves(odd, "x", 40, 30), Error);
  EXPECT_THROW((void)plot_curves(odd, "x", 800, -5), Error);
}

// ---- XY plot ----

// 8-connected blobs of exactly `colour`, left to right.
std::vector<Ink> Blobs(const Image& img, Rgb8 colour) {
  std::vector<bool> seen(img.pixels().size(), false);
  std::vector<Ink> blobs;
  const auto index = [&](int x, int y) { return static_cast<std::size_t>(y * img.width() + x); };
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      if (seen[index(x, y)] || img.at(x, y) != colour) continue;
      Ink ink;
      std::vector<std::pair<int, int>> stack = {{x, y}};
      seen[index(x, y)] = true;
      while (!stack.empty()) {
        const auto [px, py] = stack.back();
        stack.pop_back();
        ++ink.count;
        ink.x0 = std::min(ink.x0, px);
        ink.y0 = std::min(ink.y0, py);
        ink.x1 = std::max(ink.x1, px);
        ink.y1 = std::max(ink.y1, py);
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = px + dx;
            const int ny = py + dy;
            if (img.contains(nx, ny) && !seen[index(nx, ny)] && img.at(nx, ny) == colour) {
              seen[index(nx, ny)] = true;
              stack.push_back({nx, ny});
            }
          }
        }
      }
      blobs.push_back(ink);
    }
  }
  std::sort(blobs.begin(), blobs.end(), [](const Ink& a, const Ink& b) { return a.x0 < b.x0; });
  return blobs;
}

// The blobs of series i's colour that are data, not its legend entry: the legend is right of
// the plot, so its swatch is the right-most blob.
std::vector<Ink> DataBlobs(const Image& img, std::size_t i) {
  std::vector<Ink> blobs = Blobs(img, curve_colour(i));
  EXPECT_FALSE(blobs.empty()) << "series " << i << " has no legend swatch";
  if (!blobs.empty()) blobs.pop_back();
  return blobs;
}

double CentreX(const Ink& ink) { return (ink.x0 + ink.x1) / 2.0; }
double CentreY(const Ink& ink) { return (ink.y0 + ink.y1) / 2.0; }

// Where `text`, drawn in black by draw_text, appears in `img` with no other black pixel in the
// columns just left and right of it.
bool ContainsText(const Image& img, std::string_view text) {
  const int w = text_width(text);
  const int h = text_height();
  Image stamp(w, h, kWhite);
  draw_text(stamp, 0, 0, text, kBlack);
  const auto black = [&](int x, int y) { return img.contains(x, y) && img.at(x, y) == kBlack; };
  for (int y = 0; y + h <= img.height(); ++y) {
    for (int x = 0; x + w <= img.width(); ++x) {
      bool match = true;
      for (int sy = 0; sy < h && match; ++sy) {
        for (int sx = 0; sx < w && match; ++sx) {
          match = black(x + sx, y + sy) == (stamp.at(sx, sy) == kBlack);
        }
        match = match && !black(x - 1, y + sy) && !black(x + w, y + sy);
      }
      if (match) return true;
    }
  }
  return false;
}

TEST(PlotXy, SizeAndEverySeriesColour) {
  const std::vector<XySeries> series = {{"lyon", {{1200, 0.02}, {3400, 0.004}, {9000, 0.0009}}},
                                        {"kb", {{800, 0.05}, {2000, 0.01}, {40000, 2e-5}}},
                                        {"one point", {{15000, 0.001}}, false}};
  for (const bool log : {false, true}) {
    const Image p = plot_xy(series, {"area", "error", log, log}, "Pareto front");
    EXPECT_EQ(p.width(), 800);
    EXPECT_EQ(p.height(), 500);
    const Image q = plot_xy(series, {"area", "error", log, log}, "Pareto front", 320, 240);
    EXPECT_EQ(q.width(), 320);
    EXPECT_EQ(q.height(), 240);
    for (const Image* img : {&p, &q}) {
      for (std::size_t i = 0; i < series.size(); ++i) {
        EXPECT_FALSE(DataBlobs(*img, i).empty()) << i << " log " << log;
      }
      EXPECT_GT(InkOf(*img, kBlack).count, 300);  // title, ticks, labels, legend text
    }
    // Without lines every point is a marker of its own.
    std::vector<XySeries> points = series;
    for (XySeries& s : points) s.lines = false;
    const Image r = plot_xy(points, {"area", "error", log, log}, "points");
    EXPECT_EQ(DataBlobs(r, 0).size(), 3u) << log;
    EXPECT_EQ(DataBlobs(r, 1).size(), 3u) << log;
    EXPECT_EQ(DataBlobs(r, 2).size(), 1u) << log;
  }
}

// Series 0 at the minimum x and y, series 1 at the maximum, series 2 at `mid`: the maximum lands
// right of and above the minimum, far apart, and `mid` (the midpoint in axis units) halfway.
void ExpectPlacement(std::pair<double, double> lo, std::pair<double, double> hi,
                     std::pair<double, double> mid, bool log_x, bool log_y) {
  SCOPED_TRACE(testing::Message() << "x " << lo.first << ".." << hi.first << (log_x ? " log" : "")
                                  << ", y " << lo.second << ".." << hi.second
                                  << (log_y ? " log" : ""));
  const std::vector<XySeries> series = {
      {"min", {lo}, false}, {"max", {hi}, false}, {"mid", {mid}, false}};
  const Image p = plot_xy(series, {"x", "y", log_x, log_y}, "placement");
  const std::vector<Ink> a = DataBlobs(p, 0);
  const std::vector<Ink> b = DataBlobs(p, 1);
  const std::vector<Ink> m = DataBlobs(p, 2);
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_GT(CentreX(b[0]) - CentreX(a[0]), p.width() / 2);   // right of
  EXPECT_GT(CentreY(a[0]) - CentreY(b[0]), p.height() / 2);  // higher: smaller row
  EXPECT_NEAR(CentreX(m[0]), (CentreX(a[0]) + CentreX(b[0])) / 2, 2.0);
  EXPECT_NEAR(CentreY(m[0]), (CentreY(a[0]) + CentreY(b[0])) / 2, 2.0);
}

TEST(PlotXy, LargerXIsRightAndLargerYIsHigherOnLinearAxes) {
  ExpectPlacement({2, 10}, {7, 30}, {4.5, 20}, false, false);
  ExpectPlacement({-5e-3, 1e6}, {-1e-3, 3e6}, {-3e-3, 2e6}, false, false);
  ExpectPlacement({0, -250}, {12000, 250}, {6000, 0}, false, false);
}

TEST(PlotXy, LargerXIsRightAndLargerYIsHigherOnLogAxes) {
  // Geometric midpoints: on linear axes they would sit close to the minimum instead.
  ExpectPlacement({10, 1e-4}, {1e5, 1e-1}, {1e3, std::pow(10.0, -2.5)}, true, true);
  ExpectPlacement({200, 1e-3}, {800, 1.0}, {400, std::sqrt(1e-3)}, true, true);
  ExpectPlacement({1, 0.5}, {1e6, 2.5}, {1e3, 1.5}, true, false);
  ExpectPlacement({-3, 1e-9}, {5, 1e9}, {1, 1}, false, true);
}

TEST(PlotXy, NonPositiveValuesAreSkippedOnLogAxes) {
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Positive (1, 0.01) and (1000, 500); x not positive (-500, 100), (0, 200); y not positive
  // (300, 0), (600, -300); never finite (10, NaN), (inf, 5).
  const std::vector<XySeries> series = {{"odd",
                                         {{1, 0.01},
                                          {-500, 100},
                                          {0, 200},
                                          {300, 0},
                                          {600, -300},
                                          {10, kNan},
                                          {kInf, 5},
                                          {1000, 500}},
                                         false}};
  const Image loglog = plot_xy(series, {"x", "y", true, true}, "log");
  const std::vector<Ink> shown = DataBlobs(loglog, 0);
  ASSERT_EQ(shown.size(), 2u);
  // The skipped values do not stretch the range: the two points span most of the plot.
  EXPECT_GT(CentreX(shown[1]) - CentreX(shown[0]), loglog.width() / 2);
  // Only x on a log axis: (300, 0) and (600, -300) are back.
  EXPECT_EQ(DataBlobs(plot_xy(series, {"x", "y", true, false}, "log x"), 0).size(), 4u);
  // Linear: everything finite is shown; the NaN and the infinity are still skipped.
  EXPECT_EQ(DataBlobs(plot_xy(series, {"x", "y"}, "linear"), 0).size(), 6u);

  // A skipped point breaks the line; otherwise the line joins the markers into one blob.
  const std::vector<XySeries> broken = {{"broken", {{10, 10}, {-1, 5}, {100, 100}}, true}};
  EXPECT_EQ(DataBlobs(plot_xy(broken, {"x", "y", true, true}, "log"), 0).size(), 2u);
  EXPECT_EQ(DataBlobs(plot_xy(broken, {"x", "y"}, "linear"), 0).size(), 1u);

  // Nothing plottable at all on a log axis is an error; linear axes take the same points.
  const std::vector<XySeries> non_positive = {{"np", {{-1, 1}, {0, 2}}}};
  EXPECT_THROW((void)plot_xy(non_positive, {"x", "y", true, false}, "log"), Error);
  EXPECT_EQ(plot_xy(non_positive, {"x", "y"}, "linear").width(), 800);
}

TEST(PlotXy, EmptyInputAndTooSmallThrow) {
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)plot_xy({}, {}, "empty"), Error);
  EXPECT_THROW((void)plot_xy({{"none", {}}, {"", {}}}, {}, "no points"), Error);
  EXPECT_THROW((void)plot_xy({{"nan", {{kNan, 1}, {1, kNan}}}}, {}, "nan"), Error);
  const std::vector<XySeries> ok = {{"a", {{1, 2}, {3, 4}}}};
  EXPECT_EQ(plot_xy(ok, {}, "").width(), 800);
  EXPECT_THROW((void)plot_xy(ok, {}, "x", 60, 40), Error);
  EXPECT_THROW((void)plot_xy(ok, {}, "x", 800, -5), Error);
  EXPECT_THROW((void)plot_xy(ok, {}, "x", -1, 500), Error);
  // A single value on either axis still gets a range with the point inside it.
  for (const bool log : {false, true}) {
    const std::vector<XySeries> one = {{"one", {{5, 5}, {5, 5}}}};
    const Image p = plot_xy(one, {"x", "y", log, log}, "one");
    const std::vector<Ink> blobs = DataBlobs(p, 0);
    ASSERT_EQ(blobs.size(), 1u);
    EXPECT_GT(blobs[0].count, 4);  // a whole marker, not a clipped corner
    const std::vector<XySeries> zero = {{"zero", {{0, 0}}}};
    if (!log) {
      EXPECT_EQ(DataBlobs(plot_xy(zero, {}, "zero"), 0).size(), 1u);
    }
  }
}

// The rows (or columns) holding black within the given box, split into runs at blank lines.
std::vector<std::pair<int, int>> BlackRuns(const Image& img, int x0, int y0, int x1, int y1,
                                           bool columns) {
  std::vector<std::pair<int, int>> runs;
  const int n0 = columns ? x0 : y0;
  const int n1 = columns ? x1 : y1;
  for (int n = n0; n < n1; ++n) {
    bool any = false;
    for (int m = columns ? y0 : x0; m < (columns ? y1 : x1) && !any; ++m) {
      any = (columns ? img.at(n, m) : img.at(m, n)) == kBlack;
    }
    if (!any) continue;
    if (!runs.empty() && runs.back().second >= n - (columns ? 5 : 1)) {
      runs.back().second = n;  // glyphs inside one label are at most 4 blank columns apart
    } else {
      runs.push_back({n, n});
    }
  }
  return runs;
}

TEST(PlotXy, TickLabelsAreShortAndDoNotOverlap) {
  struct Case {
    std::pair<double, double> lo, hi;
    bool log_x, log_y;
    int width, height;
  };
  const std::vector<Case> cases = {
      {{0, 0}, {12345, 1}, false, false, 800, 500},
      {{1e-6, 1e-6}, {1e6, 1e6}, true, true, 800, 500},
      {{0.001, 0.001}, {0.0013, 0.0013}, false, false, 800, 500},
      {{-5e7, 1e-300}, {5e7, 1e300}, false, true, 800, 500},
      {{1e-6, 1e-6}, {1e6, 1e6}, true, true, 300, 200},
      {{0.001, 0.001}, {0.0013, 0.0013}, true, true, 300, 200},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << c.lo.first << ".." << c.hi.first << " " << c.width);
    // No title or captions: the only black below the x axis and left of the y axis is ticks and
    // tick labels.
    const Image p =
        plot_xy({{"s", {c.lo, c.hi}}}, {"", "", c.log_x, c.log_y}, "", c.width, c.height);
    // The x axis is the row with the longest black run, the y axis the column.
    int axis_row = 0, axis_col = 0, best_row = 0, best_col = 0;
    for (int y = 0; y < p.height(); ++y) {
      for (int x = 0, run = 0; x < p.width(); ++x) {
        run = p.at(x, y) == kBlack ? run + 1 : 0;
        if (run > best_row) best_row = run, axis_row = y;
      }
    }
    for (int x = 0; x < p.width(); ++x) {
      for (int y = 0, run = 0; y < p.height(); ++y) {
        run = p.at(x, y) == kBlack ? run + 1 : 0;
        if (run > best_col) best_col = run, axis_col = x;
      }
    }
    ASSERT_GT(best_row, p.width() / 2);
    ASSERT_GT(best_col, p.height() / 2);
    const int longest = text_width("1.2e+04");  // seven characters
    const auto x_labels = BlackRuns(p, 0, axis_row + 1, p.width(), p.height(), true);
    EXPECT_GE(x_labels.size(), c.width >= 800 ? 3u : 2u);
    for (const auto& [a, b] : x_labels) EXPECT_LE(b - a + 1, longest) << "x label at " << a;
    // Without the tick marks: horizontal lines that touch the y axis.
    Image left(axis_col, p.height(), kWhite);
    blit(left, p, 0, 0);
    for (int y = 0; y < left.height(); ++y) {
      for (int x = axis_col - 1; x >= 0 && left.at(x, y) == kBlack; --x) left.at(x, y) = kWhite;
    }
    const auto y_labels = BlackRuns(left, 0, 0, left.width(), left.height(), false);
    EXPECT_GE(y_labels.size(), c.height >= 500 ? 3u : 2u);
    for (const auto& [a, b] : y_labels) {
      EXPECT_LE(b - a + 1, text_height()) << "y label at " << a;
      const auto cols = BlackRuns(left, 0, a, left.width(), b + 1, true);
      ASSERT_EQ(cols.size(), 1u) << "y label at " << a;
      EXPECT_LE(cols[0].second - cols[0].first + 1, longest) << "y label at " << a;
    }
  }
}

TEST(PlotXy, TickLabelsReadAsNumbers) {
  // Some plain tick values must be labelled in one of their short spellings.
  const auto any_of = [](const Image& img, std::initializer_list<std::string_view> texts) {
    for (const std::string_view t : texts) {
      if (ContainsText(img, t)) return true;
    }
    return false;
  };
  const Image unit = plot_xy({{"s", {{0, 0}, {1, 1}}}}, {"x", "y"}, "");
  EXPECT_TRUE(any_of(unit, {"0.5"}));
  EXPECT_TRUE(any_of(unit, {"0", "0.0"}));
  const Image big = plot_xy({{"s", {{0, 0}, {12000, 12000}}}}, {"x", "y"}, "");
  EXPECT_TRUE(any_of(big, {"10000", "1e+4", "1e+04", "1e4", "1.0e+04"}));
  const Image decades = plot_xy({{"s", {{1e-3, 1e-3}, {1, 1}}}}, {"x", "y", true, true}, "");
  EXPECT_TRUE(any_of(decades, {"0.001", "1e-3", "1e-03"}));
  EXPECT_TRUE(any_of(decades, {"0.01", "1e-2", "1e-02"}));
  EXPECT_TRUE(any_of(decades, {"1", "1e+0", "1e+00", "1e0"}));
  // Decade labels on a log axis, not plain steps: 0.5 is no decade.
  EXPECT_FALSE(ContainsText(decades, "0.5"));
}

}  // namespace
}  // namespace phongsim
