// Image utilities: PNG through libpng (round trips, the header the spec fixes, atomic writes, read
// errors for truncated, corrupt and unsupported files), and Vlasic's difference image and
// metrics on hand-computed images.
#include "sim/render/image.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "tests/temp_dir.h"

namespace phongsim {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;

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
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
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
  const testing::TempDir tmp;
  const fs::path path = tmp.path() / "a.png";
  write_png(Noise(5, 5, 1), path);
  write_png(Noise(4, 6, 2), path);
  EXPECT_EQ(read_png(path), Noise(4, 6, 2));
}

TEST(Png, SignatureAndHeaderFollowTheSpec) {
  const testing::TempDir tmp;
  const fs::path path = tmp.path() / "h.png";
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
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
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
  const testing::TempDir tmp;
  const fs::path& dir = tmp.path();
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

}  // namespace
}  // namespace phongsim
