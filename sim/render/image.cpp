#include "sim/render/image.h"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string_view>
#include <vector>

#include "base/error.h"
#include "base/output_file.h"

namespace phongsim {

Image::Image(int width, int height, Rgb8 fill) {
  if (width < 0 || height < 0 || width > kMaxSize || height > kMaxSize) {
    throw Error(fmt::format("image size {}x{} is out of range (0..{})", width, height, kMaxSize));
  }
  width_ = width;
  height_ = height;
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

Rgb8& Image::at(int x, int y) {
  assert(contains(x, y));
  return pixels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                 static_cast<std::size_t>(x)];
}

const Rgb8& Image::at(int x, int y) const {
  assert(contains(x, y));
  return pixels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                 static_cast<std::size_t>(x)];
}

void fill_rect(Image& img, int x, int y, int w, int h, Rgb8 colour) {
  const int x0 = std::max(x, 0);
  const int y0 = std::max(y, 0);
  const int x1 = static_cast<int>(std::min<long>(static_cast<long>(x) + w, img.width()));
  const int y1 = static_cast<int>(std::min<long>(static_cast<long>(y) + h, img.height()));
  for (int yy = y0; yy < y1; ++yy) {
    for (int xx = x0; xx < x1; ++xx) img.at(xx, yy) = colour;
  }
}

// ---- PNG (libpng's simplified API: no setjmp, errors in png_image::message) ----

namespace {

static_assert(sizeof(Rgb8) == 3, "Image pixels are handed to libpng as packed RGB bytes");

// Frees libpng's state however the caller leaves.
struct PngImage {
  png_image image{};
  PngImage() { image.version = PNG_IMAGE_VERSION; }
  ~PngImage() { png_image_free(&image); }
  PngImage(const PngImage&) = delete;
  PngImage& operator=(const PngImage&) = delete;
};

}  // namespace

void write_png(const Image& img, const std::filesystem::path& path) {
  // PNG has no empty images; refuse before anything touches the file system.
  if (img.empty()) {
    throw Error(fmt::format("cannot write {}: the image is empty ({}x{})", path.string(),
                            img.width(), img.height()));
  }
  OutputFile out(path);
  PngImage png;
  png.image.width = static_cast<png_uint_32>(img.width());
  png.image.height = static_cast<png_uint_32>(img.height());
  png.image.format = PNG_FORMAT_RGB;
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(img.pixels().data());
  if (png_image_write_to_stdio(&png.image, out.get(), 0, bytes, 0, nullptr) == 0) {
    throw Error(fmt::format("cannot write {}: {}", path.string(), png.image.message));
  }
  out.commit();
}

Image read_png(const std::filesystem::path& path) {
  const auto fail = [&](std::string_view why) {
    return Error(fmt::format("cannot read {}: {}", path.string(), why));
  };
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) throw fail(std::strerror(errno));
  // libpng says "Read Error" for any failed read: name the cause where the stream knows it.
  const auto png_failure = [&](const png_image& image) {
    if (std::feof(file.get())) return fail("the file ends early (truncated or empty)");
    if (std::ferror(file.get())) return fail(std::strerror(errno));
    return fail(image.message);
  };
  PngImage png;
  if (png_image_begin_read_from_stdio(&png.image, file.get()) == 0) throw png_failure(png.image);
  const png_uint_32 width = png.image.width;
  const png_uint_32 height = png.image.height;
  if (width > Image::kMaxSize || height > Image::kMaxSize) {
    throw fail(
        fmt::format("image size {}x{} is out of range (1..{})", width, height, Image::kMaxSize));
  }
  if (png.image.format != PNG_FORMAT_RGB) {
    throw fail("unsupported PNG format (only 8-bit RGB without transparency is read)");
  }
  std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png.image));
  if (png_image_finish_read(&png.image, nullptr, bytes.data(), 0, nullptr) == 0) {
    throw png_failure(png.image);
  }
  Image img(static_cast<int>(width), static_cast<int>(height));
  const std::uint8_t* p = bytes.data();
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x, p += 3) img.at(x, y) = {p[0], p[1], p[2]};
  }
  return img;
}

// ---- text ----

namespace {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 8;  // 7 rows above the baseline, 1 descender row
constexpr int kAdvance = kGlyphWidth + 1;

// Printable ASCII 32..126, one glyph per entry: 8 rows of 5 bits, top row in the high bits,
// leftmost pixel the high bit of its row (the ' separators split the rows).
constexpr std::array<std::uint64_t, 95> kFont{
    0b00000'00000'00000'00000'00000'00000'00000'00000,  // space
    0b00100'00100'00100'00100'00100'00000'00100'00000,  // !
    0b01010'01010'01010'00000'00000'00000'00000'00000,  // "
    0b01010'01010'11111'01010'11111'01010'01010'00000,  // #
    0b00100'01111'10100'01110'00101'11110'00100'00000,  // $
    0b11000'11001'00010'00100'01000'10011'00011'00000,  // %
    0b01100'10010'10100'01000'10101'10010'01101'00000,  // &
    0b00100'00100'01000'00000'00000'00000'00000'00000,  // '
    0b00010'00100'01000'01000'01000'00100'00010'00000,  // (
    0b01000'00100'00010'00010'00010'00100'01000'00000,  // )
    0b00000'00100'10101'01110'10101'00100'00000'00000,  // *
    0b00000'00100'00100'11111'00100'00100'00000'00000,  // +
    0b00000'00000'00000'00000'00000'01100'00100'01000,  // ,
    0b00000'00000'00000'11111'00000'00000'00000'00000,  // -
    0b00000'00000'00000'00000'00000'01100'01100'00000,  // .
    0b00000'00001'00010'00100'01000'10000'00000'00000,  // /
    0b01110'10001'10011'10101'11001'10001'01110'00000,  // 0
    0b00100'01100'00100'00100'00100'00100'01110'00000,  // 1
    0b01110'10001'00001'00010'00100'01000'11111'00000,  // 2
    0b11111'00010'00100'00010'00001'10001'01110'00000,  // 3
    0b00010'00110'01010'10010'11111'00010'00010'00000,  // 4
    0b11111'10000'11110'00001'00001'10001'01110'00000,  // 5
    0b00110'01000'10000'11110'10001'10001'01110'00000,  // 6
    0b11111'00001'00010'00100'01000'01000'01000'00000,  // 7
    0b01110'10001'10001'01110'10001'10001'01110'00000,  // 8
    0b01110'10001'10001'01111'00001'00010'01100'00000,  // 9
    0b00000'01100'01100'00000'01100'01100'00000'00000,  // :
    0b00000'01100'01100'00000'01100'00100'01000'00000,  // ;
    0b00010'00100'01000'10000'01000'00100'00010'00000,  // <
    0b00000'00000'11111'00000'11111'00000'00000'00000,  // =
    0b01000'00100'00010'00001'00010'00100'01000'00000,  // >
    0b01110'10001'00001'00010'00100'00000'00100'00000,  // ?
    0b01110'10001'00001'01101'10101'10101'01110'00000,  // @
    0b01110'10001'10001'11111'10001'10001'10001'00000,  // A
    0b11110'10001'10001'11110'10001'10001'11110'00000,  // B
    0b01110'10001'10000'10000'10000'10001'01110'00000,  // C
    0b11100'10010'10001'10001'10001'10010'11100'00000,  // D
    0b11111'10000'10000'11110'10000'10000'11111'00000,  // E
    0b11111'10000'10000'11110'10000'10000'10000'00000,  // F
    0b01110'10001'10000'10111'10001'10001'01111'00000,  // G
    0b10001'10001'10001'11111'10001'10001'10001'00000,  // H
    0b01110'00100'00100'00100'00100'00100'01110'00000,  // I
    0b00111'00010'00010'00010'00010'10010'01100'00000,  // J
    0b10001'10010'10100'11000'10100'10010'10001'00000,  // K
    0b10000'10000'10000'10000'10000'10000'11111'00000,  // L
    0b10001'11011'10101'10101'10001'10001'10001'00000,  // M
    0b10001'10001'11001'10101'10011'10001'10001'00000,  // N
    0b01110'10001'10001'10001'10001'10001'01110'00000,  // O
    0b11110'10001'10001'11110'10000'10000'10000'00000,  // P
    0b01110'10001'10001'10001'10101'10010'01101'00000,  // Q
    0b11110'10001'10001'11110'10100'10010'10001'00000,  // R
    0b01111'10000'10000'01110'00001'00001'11110'00000,  // S
    0b11111'00100'00100'00100'00100'00100'00100'00000,  // T
    0b10001'10001'10001'10001'10001'10001'01110'00000,  // U
    0b10001'10001'10001'10001'10001'01010'00100'00000,  // V
    0b10001'10001'10001'10101'10101'10101'01010'00000,  // W
    0b10001'10001'01010'00100'01010'10001'10001'00000,  // X
    0b10001'10001'01010'00100'00100'00100'00100'00000,  // Y
    0b11111'00001'00010'00100'01000'10000'11111'00000,  // Z
    0b01110'01000'01000'01000'01000'01000'01110'00000,  // [
    0b00000'10000'01000'00100'00010'00001'00000'00000,  // backslash
    0b01110'00010'00010'00010'00010'00010'01110'00000,  // ]
    0b00100'01010'10001'00000'00000'00000'00000'00000,  // ^
    0b00000'00000'00000'00000'00000'00000'00000'11111,  // _
    0b01000'00100'00010'00000'00000'00000'00000'00000,  // `
    0b00000'00000'01110'00001'01111'10001'01111'00000,  // a
    0b10000'10000'10110'11001'10001'10001'11110'00000,  // b
    0b00000'00000'01110'10000'10000'10001'01110'00000,  // c
    0b00001'00001'01101'10011'10001'10001'01111'00000,  // d
    0b00000'00000'01110'10001'11111'10000'01110'00000,  // e
    0b00110'01001'01000'11100'01000'01000'01000'00000,  // f
    0b00000'00000'01111'10001'10001'01111'00001'01110,  // g
    0b10000'10000'10110'11001'10001'10001'10001'00000,  // h
    0b00100'00000'01100'00100'00100'00100'01110'00000,  // i
    0b00010'00000'00110'00010'00010'00010'10010'01100,  // j
    0b10000'10000'10010'10100'11000'10100'10010'00000,  // k
    0b01100'00100'00100'00100'00100'00100'01110'00000,  // l
    0b00000'00000'11010'10101'10101'10001'10001'00000,  // m
    0b00000'00000'10110'11001'10001'10001'10001'00000,  // n
    0b00000'00000'01110'10001'10001'10001'01110'00000,  // o
    0b00000'00000'11110'10001'10001'11110'10000'10000,  // p
    0b00000'00000'01111'10001'10001'01111'00001'00001,  // q
    0b00000'00000'10110'11001'10000'10000'10000'00000,  // r
    0b00000'00000'01111'10000'01110'00001'11110'00000,  // s
    0b01000'01000'11100'01000'01000'01001'00110'00000,  // t
    0b00000'00000'10001'10001'10001'10011'01101'00000,  // u
    0b00000'00000'10001'10001'10001'01010'00100'00000,  // v
    0b00000'00000'10001'10001'10101'10101'01010'00000,  // w
    0b00000'00000'10001'01010'00100'01010'10001'00000,  // x
    0b00000'00000'10001'10001'10001'01111'00001'01110,  // y
    0b00000'00000'11111'00010'00100'01000'11111'00000,  // z
    0b00010'00100'00100'01000'00100'00100'00010'00000,  // {
    0b00100'00100'00100'00100'00100'00100'00100'00000,  // |
    0b01000'00100'00100'00010'00100'00100'01000'00000,  // }
    0b00000'00000'01000'10101'00010'00000'00000'00000,  // ~
};

// Calls f(glyph index) for each character of `text`: printable ASCII maps to its glyph, a UTF-8
// sequence (lead byte plus continuation bytes) and any other byte to '?'.
template <typename F>
void for_each_glyph(std::string_view text, F&& f) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x80 && c < 0xc0) continue;  // UTF-8 continuation byte
    f(c >= 32 && c <= 126 ? c - 32 : '?' - 32);
  }
}

void check_scale(int scale) {
  if (scale < 1) throw Error(fmt::format("text scale {} is not a positive integer", scale));
}

}  // namespace

void draw_text(Image& img, int x, int y, std::string_view text, Rgb8 colour, int scale) {
  check_scale(scale);
  int pen = x;
  for_each_glyph(text, [&](int glyph) {
    const std::uint64_t bits = kFont[static_cast<std::size_t>(glyph)];
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        const int bit = (kGlyphHeight - 1 - row) * kGlyphWidth + (kGlyphWidth - 1 - col);
        if ((bits >> bit) & 1) {
          fill_rect(img, pen + col * scale, y + row * scale, scale, scale, colour);
        }
      }
    }
    pen += kAdvance * scale;
  });
}

int text_width(std::string_view text, int scale) {
  check_scale(scale);
  int n = 0;
  for_each_glyph(text, [&](int) { ++n; });
  return n == 0 ? 0 : (n * kAdvance - 1) * scale;
}

int text_height(int scale) {
  check_scale(scale);
  return kGlyphHeight * scale;
}

void blit(Image& dst, const Image& src, int x, int y) {
  const int x0 = std::max(0, -x);
  const int y0 = std::max(0, -y);
  const int x1 = static_cast<int>(std::min<long>(src.width(), static_cast<long>(dst.width()) - x));
  const int y1 =
      static_cast<int>(std::min<long>(src.height(), static_cast<long>(dst.height()) - y));
  for (int sy = y0; sy < y1; ++sy) {
    for (int sx = x0; sx < x1; ++sx) dst.at(x + sx, y + sy) = src.at(sx, sy);
  }
}

// ---- grid ----

Image grid(const std::vector<std::vector<Image>>& cells, const std::vector<std::string>& row_labels,
           const std::vector<std::string>& col_labels, std::string_view title) {
  constexpr int kPad = 4;
  constexpr int kTitleScale = 2;
  const std::size_t rows = std::max(cells.size(), row_labels.size());
  std::size_t cols = col_labels.size();
  for (const auto& row : cells) cols = std::max(cols, row.size());
  const auto cell = [&](std::size_t r, std::size_t c) -> const Image* {
    return r < cells.size() && c < cells[r].size() ? &cells[r][c] : nullptr;
  };

  // Slot sizes: the largest cell of each column / row, widened to fit its label.
  std::vector<int> col_w(cols, 0);
  std::vector<int> row_h(rows, 0);
  for (std::size_t c = 0; c < cols; ++c) {
    if (c < col_labels.size()) col_w[c] = text_width(col_labels[c]);
  }
  int label_w = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    if (r < row_labels.size() && !row_labels[r].empty()) {
      label_w = std::max(label_w, text_width(row_labels[r]));
      row_h[r] = text_height();
    }
    for (std::size_t c = 0; c < cols; ++c) {
      if (const Image* im = cell(r, c)) {
        col_w[c] = std::max(col_w[c], im->width());
        row_h[r] = std::max(row_h[r], im->height());
      }
    }
  }
  const bool has_col_labels =
      std::any_of(col_labels.begin(), col_labels.end(), [](const auto& s) { return !s.empty(); });

  int y = kPad;
  const int title_y = y;
  if (!title.empty()) y += text_height(kTitleScale) + kPad;
  const int col_label_y = y;
  if (has_col_labels) y += text_height() + kPad;
  const int cells_y = y;
  const int cells_x = kPad + (label_w > 0 ? label_w + kPad : 0);

  long width = cells_x;
  for (const int w : col_w) width += w + kPad;
  if (cols == 0) width += kPad;
  width = std::max<long>(width, text_width(title, kTitleScale) + 2 * kPad);
  long height = cells_y;
  for (const int h : row_h) height += h + kPad;
  if (rows == 0) height += kPad;
  if (width > Image::kMaxSize || height > Image::kMaxSize) {
    throw Error(fmt::format("grid of {}x{} pixels is too large", width, height));
  }

  Image out(static_cast<int>(width), static_cast<int>(height), kWhite);
  if (!title.empty()) {
    draw_text(out, (out.width() - text_width(title, kTitleScale)) / 2, title_y, title, kBlack,
              kTitleScale);
  }
  int x = cells_x;
  for (std::size_t c = 0; c < cols; ++c) {
    if (c < col_labels.size()) {
      draw_text(out, x + (col_w[c] - text_width(col_labels[c])) / 2, col_label_y, col_labels[c],
                kBlack);
    }
    x += col_w[c] + kPad;
  }
  y = cells_y;
  for (std::size_t r = 0; r < rows; ++r) {
    if (r < row_labels.size()) {
      draw_text(out, kPad, y + (row_h[r] - text_height()) / 2, row_labels[r], kBlack);
    }
    x = cells_x;
    for (std::size_t c = 0; c < cols; ++c) {
      if (const Image* im = cell(r, c)) {
        blit(out, *im, x + (col_w[c] - im->width()) / 2, y + (row_h[r] - im->height()) / 2);
      }
      x += col_w[c] + kPad;
    }
    y += row_h[r] + kPad;
  }
  return out;
}

// ---- evaluation (Vlasic ch. 6) ----

namespace {

void check_same_size(const Image& reference, const Image& img, std::string_view what) {
  if (reference.width() != img.width() || reference.height() != img.height()) {
    throw Error(fmt::format("{}: image sizes differ ({}x{} vs {}x{})", what, reference.width(),
                            reference.height(), img.width(), img.height()));
  }
}

}  // namespace

Image difference_image(const Image& reference, const Image& img) {
  check_same_size(reference, img, "difference image");
  std::array<std::uint8_t, 256> lut{};
  for (int d = 0; d < 256; ++d) {
    lut[static_cast<std::size_t>(d)] =
        static_cast<std::uint8_t>(std::lround(255.0 * std::pow(d / 255.0, 0.1)));
  }
  const auto diff = [&](std::uint8_t a, std::uint8_t b) {
    return lut[static_cast<std::size_t>(std::abs(int{a} - int{b}))];
  };
  Image out(img.width(), img.height());
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      const Rgb8 a = reference.at(x, y);
      const Rgb8 b = img.at(x, y);
      out.at(x, y) = {diff(a.r, b.r), diff(a.g, b.g), diff(a.b, b.b)};
    }
  }
  return out;
}

ImageMetrics compare(const Image& reference, const Image& img, const std::vector<bool>& mask) {
  check_same_size(reference, img, "compare");
  const auto& ref = reference.pixels();
  const auto& got = img.pixels();
  if (!mask.empty() && mask.size() != got.size()) {
    throw Error(fmt::format("compare: the mask has {} entries for a {}x{} image", mask.size(),
                            img.width(), img.height()));
  }
  ImageMetrics m;
  std::uint64_t abs_sum = 0;
  std::uint64_t sq_sum = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++m.pixels;
    for (const int d :
         {int{ref[i].r} - got[i].r, int{ref[i].g} - got[i].g, int{ref[i].b} - got[i].b}) {
      abs_sum += static_cast<std::uint64_t>(std::abs(d));
      sq_sum += static_cast<std::uint64_t>(d * d);
      m.max_error = std::max(m.max_error, std::abs(d));
    }
  }
  if (m.pixels == 0) return m;
  const double channels = 3.0 * static_cast<double>(m.pixels);
  m.colour_correctness = 1.0 - static_cast<double>(abs_sum) / (255.0 * channels);
  if (sq_sum > 0) {
    const double mse = static_cast<double>(sq_sum) / channels;
    m.psnr = 10.0 * std::log10(255.0 * 255.0 / mse);
  }
  return m;
}

std::vector<double> illumination_row(const Image& img, int y) {
  if (y < 0 || y >= img.height()) {
    throw Error(
        fmt::format("illumination row {} is outside the image (height {})", y, img.height()));
  }
  std::vector<double> out(static_cast<std::size_t>(img.width()));
  for (int x = 0; x < img.width(); ++x) {
    const Rgb8 p = img.at(x, y);
    out[static_cast<std::size_t>(x)] = (p.r + p.g + p.b) / (3.0 * 255.0);
  }
  return out;
}

// ---- plot ----

Rgb8 curve_colour(std::size_t i) {
  // Tableau's 10 categorical colours: distinct, and none close to the black/grey of the axes.
  static constexpr std::array<Rgb8, 10> kPalette{{{31, 119, 180},
                                                  {255, 127, 14},
                                                  {44, 160, 44},
                                                  {214, 39, 40},
                                                  {148, 103, 189},
                                                  {140, 86, 75},
                                                  {227, 119, 194},
                                                  {188, 189, 34},
                                                  {23, 190, 207},
                                                  {127, 127, 127}}};
  return kPalette[i % kPalette.size()];
}

namespace {

// Lines are two pixels thick so colours stay recognisable; clipped to `clip`.
struct Rect {
  int x0, y0, x1, y1;  // inclusive
};

void plot_point(Image& img, int x, int y, Rgb8 colour, const Rect& clip) {
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const int px = x + dx;
      const int py = y - dy;
      if (px >= clip.x0 && px <= clip.x1 && py >= clip.y0 && py <= clip.y1) {
        img.at(px, py) = colour;
      }
    }
  }
}

void plot_line(Image& img, int x0, int y0, int x1, int y1, Rgb8 colour, const Rect& clip) {
  // Bresenham: every step moves one pixel along the major axis.
  const int dx = std::abs(x1 - x0);
  const int dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1;
  const int sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    plot_point(img, x0, y0, colour, clip);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

// A step of 1, 2 or 5 times a power of ten, at least `raw` and at least 1 (columns are integers).
long nice_step(double raw) {
  long step = 1;
  for (;;) {
    for (const long m : {1L, 2L, 5L}) {
      if (static_cast<double>(step * m) >= raw) return step * m;
    }
    step *= 10;
  }
}

constexpr int kPlotPad = 8;
constexpr int kTick = 4;
constexpr int kSwatch = 12;
constexpr Rgb8 kGridLine{225, 225, 225};

struct PlotTick {
  int pos = 0;  // pixel column on the x axis, row on the y axis
  std::string label;
};

// The furniture plot_curves and plot_xy share: the title centred on top, the y caption above the
// y axis, y tick labels left of the plot area, x tick labels and the x caption below it, and the
// legend right of it. The rows are fixed first, so that the y ticks can be chosen for the
// area's height; the columns follow once the widest y tick label is known.
class PlotFrame {
 public:
  PlotFrame(int width, int height, std::string_view title)
      : width_(width), height_(height), title_(title) {
    title_scale_ = text_width(title, 2) + 2 * kPlotPad <= width ? 2 : 1;
    const int th = text_height();
    area_.y0 = kPlotPad + (title.empty() ? 0 : text_height(title_scale_) + kPlotPad) + th + 4;
    area_.y1 = height - 1 - kPlotPad - th - 4 - th - kTick - 2;
    if (height > Image::kMaxSize || area_.y1 - area_.y0 < kMinArea) no_room();
  }

  // Error if the width leaves no room for the plot area.
  void set_columns(int y_label_width, const std::vector<std::string>& legend) {
    int legend_text = 0;
    for (const std::string& label : legend) legend_text = std::max(legend_text, text_width(label));
    const int legend_w = legend.empty() ? 0 : kSwatch + 4 + legend_text + kPlotPad;
    area_.x0 = kPlotPad + y_label_width + kTick + 2;
    area_.x1 = width_ - 1 - kPlotPad - legend_w;
    if (width_ > Image::kMaxSize || area_.x1 - area_.x0 < kMinArea) no_room();
  }

  // Inclusive bounds; the columns only after set_columns.
  [[nodiscard]] const Rect& area() const { return area_; }

  // A white image with the title, captions, gridlines, ticks, tick labels and axes.
  [[nodiscard]] Image draw(std::string_view x_caption, std::string_view y_caption,
                           const std::vector<PlotTick>& x_ticks,
                           const std::vector<PlotTick>& y_ticks) const {
    const int th = text_height();
    const int pw = area_.x1 - area_.x0;
    const int ph = area_.y1 - area_.y0;
    Image img(width_, height_, kWhite);
    if (!title_.empty()) {
      draw_text(img, (width_ - text_width(title_, title_scale_)) / 2, kPlotPad, title_, kBlack,
                title_scale_);
    }
    draw_text(img, std::max(0, area_.x0 - text_width(y_caption) / 2), area_.y0 - th - 4, y_caption,
              kBlack);
    for (const PlotTick& t : y_ticks) {
      fill_rect(img, area_.x0, t.pos, pw + 1, 1, kGridLine);
      fill_rect(img, area_.x0 - kTick, t.pos, kTick, 1, kBlack);
      draw_text(img, area_.x0 - kTick - 2 - text_width(t.label), t.pos - th / 2 + 1, t.label,
                kBlack);
    }
    for (const PlotTick& t : x_ticks) {
      fill_rect(img, t.pos, area_.y0, 1, ph + 1, kGridLine);
      fill_rect(img, t.pos, area_.y1 + 1, 1, kTick, kBlack);
      const int w = text_width(t.label);
      draw_text(img, std::clamp(t.pos - w / 2, 0, std::max(0, width_ - w)), area_.y1 + kTick + 2,
                t.label, kBlack);
    }
    draw_text(img, area_.x0 + (pw - text_width(x_caption)) / 2, area_.y1 + kTick + 2 + th + 4,
              x_caption, kBlack);
    // Axes last among the furniture so gridlines do not cut them.
    fill_rect(img, area_.x0, area_.y0, 1, ph + 1, kBlack);
    fill_rect(img, area_.x0, area_.y1, pw + 1, 1, kBlack);
    return img;
  }

  // One entry per line right of the plot area: swatch(img, box, i) draws entry i's swatch in
  // `box`, then its label follows in black.
  template <typename Swatch>
  void draw_legend(Image& img, const std::vector<std::string>& labels, Swatch&& swatch) const {
    const int th = text_height();
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const int ly = area_.y0 + static_cast<int>(i) * (th + 4);
      const int lx = area_.x1 + kPlotPad;
      swatch(img, Rect{lx, ly, lx + kSwatch - 1, ly + th - 2}, i);
      draw_text(img, lx + kSwatch + 4, ly, labels[i], kBlack);
    }
  }

 private:
  static constexpr int kMinArea = 20;

  [[noreturn]] void no_room() const {
    throw Error(fmt::format("plot size {}x{} leaves no room for the plot", width_, height_));
  }

  int width_;
  int height_;
  std::string_view title_;
  int title_scale_ = 1;
  Rect area_{};
};

int widest_label(const std::vector<PlotTick>& ticks) {
  int w = 0;
  for (const PlotTick& t : ticks) w = std::max(w, text_width(t.label));
  return w;
}

// ---- plot_xy's axes ----

// One axis of plot_xy: its range in axis units (log10 of the value on a log axis), mapped
// linearly onto the pixels from p0 (at lo) to p1 (at hi); p1 < p0 for the y axis.
struct XyScale {
  bool log = false;
  double lo = 0;
  double hi = 1;
  int p0 = 0;
  int p1 = 1;

  [[nodiscard]] bool shows(double v) const { return std::isfinite(v) && (!log || v > 0); }
  [[nodiscard]] double unit(double v) const { return log ? std::log10(v) : v; }
  [[nodiscard]] double at(double v) const {
    return p0 + (unit(v) - lo) / (hi - lo) * static_cast<double>(p1 - p0);
  }
  [[nodiscard]] int pixel(double v) const { return static_cast<int>(std::lround(at(v))); }
};

// The range of the values `scale` shows, padded by 5% each side; false if there are none.
bool fit_range(XyScale& scale, const std::vector<double>& values, std::string_view name) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const double v : values) {
    if (!scale.shows(v)) continue;
    lo = std::min(lo, scale.unit(v));
    hi = std::max(hi, scale.unit(v));
  }
  if (lo > hi) return false;
  // Differences below double's resolution cannot be labelled: treat them as one value.
  if (hi - lo <= 1e-9 * std::max(std::abs(lo), std::abs(hi))) {
    const double mid = lo + (hi - lo) / 2;
    const double half = scale.log ? 1.0 : mid == 0 ? 1.0 : std::abs(mid) / 10;
    lo = mid - half;
    hi = mid + half;
  }
  const double pad = (hi - lo) / 20;
  scale.lo = lo - pad;
  scale.hi = hi + pad;
  if (!std::isfinite(scale.hi - scale.lo)) {
    throw Error(fmt::format("plot_xy: the {} values span too wide a range to plot", name));
  }
  return true;
}

// The decimal exponent of v's leading digit (v != 0).
int leading_exponent(double v) { return static_cast<int>(std::floor(std::log10(std::abs(v)))); }

// v in plain notation, with digits down to 10^exp: "12000", "0.5", "0.001".
std::string plain_label(double v, int exp) { return fmt::format("{:.{}f}", v, std::max(0, -exp)); }

// v in scientific notation, with digits down to 10^exp and no trailing zeros or exponent
// padding: "1.2e+4", "1e-3".
std::string scientific_label(double v, int exp) {
  if (v == 0) return "0";
  const std::string s = fmt::format("{:.{}e}", v, std::max(0, leading_exponent(v) - exp));
  const std::size_t e = s.find('e');
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') != std::string::npos) {
    while (mantissa.back() == '0') mantissa.pop_back();
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  std::string digits = s.substr(e + 2);
  while (digits.size() > 1 && digits.front() == '0') digits.erase(digits.begin());
  return mantissa + "e" + s[e + 1] + digits;
}

// A candidate set of ticks: values and, for each, the exponent of the last digit its label
// needs.
struct TickSet {
  std::vector<double> values;
  std::vector<int> exps;
};

constexpr int kMaxTicks = 15;

// Multiples of 1, 2 and 5 times powers of ten in [lo, hi], finest first.
void add_linear_ticks(double lo, double hi, std::vector<TickSet>& out) {
  if (!std::isfinite(hi - lo) || !(hi > lo)) return;
  const int top = leading_exponent(hi - lo);
  for (int e = top - 2; e <= top + 1; ++e) {
    for (const int m : {1, 2, 5}) {
      const double step = m * std::pow(10.0, e);
      const double k0 = std::ceil(lo / step - 1e-9);
      const double k1 = std::floor(hi / step + 1e-9);
      if (!(k1 >= k0 && k1 - k0 < kMaxTicks) || std::abs(k0) > 1e15 || std::abs(k1) > 1e15) {
        continue;
      }
      TickSet set;
      for (int i = 0; i <= static_cast<int>(k1 - k0); ++i) {
        set.values.push_back((k0 + i) * step);
        set.exps.push_back(e);
      }
      out.push_back(std::move(set));
    }
  }
}

// Log axis (lo, hi in decades): every d-th decade for d = 1, 2, 5, 10, ..., then 1-2-5 in
// every decade, then plain steps for ranges too short for either.
std::vector<TickSet> log_tick_sets(double lo, double hi) {
  std::vector<TickSet> out;
  // Decades whose powers of ten are finite, normal doubles.
  const int first = std::max(-307, static_cast<int>(std::ceil(lo - 1e-9)));
  const int last = std::min(308, static_cast<int>(std::floor(hi + 1e-9)));
  for (int base = 1; base <= 100; base *= 10) {
    for (const int m : {1, 2, 5}) {
      const int d = m * base;
      TickSet set;
      for (int k = first; k <= last; ++k) {
        if (k % d != 0) continue;
        set.values.push_back(std::pow(10.0, k));
        set.exps.push_back(k);
      }
      if (!set.values.empty() && set.values.size() <= kMaxTicks) out.push_back(std::move(set));
    }
  }
  if (hi - lo < kMaxTicks / 3.0) {
    TickSet set;
    for (int k = first - 1; k <= last; ++k) {
      for (const int m : {1, 2, 5}) {
        const double t = k + std::log10(static_cast<double>(m));
        if (t < lo - 1e-9 || t > hi + 1e-9 || k < -307 || k > 307) continue;
        set.values.push_back(m * std::pow(10.0, k));
        set.exps.push_back(k);
      }
    }
    if (!set.values.empty()) out.push_back(std::move(set));
  }
  if (hi - lo < 1) add_linear_ticks(std::pow(10.0, lo), std::pow(10.0, hi), out);
  return out;
}

// Labels for a tick set: plain unless that is longer than 6 characters and than scientific.
std::vector<std::string> tick_labels(const TickSet& set) {
  std::vector<std::string> plain;
  std::vector<std::string> sci;
  std::size_t plain_len = 0;
  std::size_t sci_len = 0;
  for (std::size_t i = 0; i < set.values.size(); ++i) {
    plain.push_back(plain_label(set.values[i], set.exps[i]));
    sci.push_back(scientific_label(set.values[i], set.exps[i]));
    plain_len = std::max(plain_len, plain.back().size());
    sci_len = std::max(sci_len, sci.back().size());
  }
  return plain_len <= 6 || plain_len <= sci_len ? plain : sci;
}

// The first set (in the given order of preference) whose labels have room, preferring sets of
// at least three ticks, then two, then one; none if nothing fits. x labels need their half
// widths plus a gap between neighbouring centres, y labels a minimum row spacing.
std::vector<PlotTick> choose_ticks(const std::vector<TickSet>& sets, const XyScale& scale,
                                   bool horizontal) {
  std::vector<std::vector<PlotTick>> fitting;
  for (const TickSet& set : sets) {
    const std::vector<std::string> labels = tick_labels(set);
    std::vector<PlotTick> ticks;
    for (std::size_t i = 0; i < labels.size(); ++i) {
      ticks.push_back({scale.pixel(set.values[i]), labels[i]});
    }
    std::sort(ticks.begin(), ticks.end(),
              [](const PlotTick& a, const PlotTick& b) { return a.pos < b.pos; });
    bool fits = true;
    for (std::size_t i = 1; i < ticks.size() && fits; ++i) {
      const int gap = ticks[i].pos - ticks[i - 1].pos;
      const int need =
          horizontal
              ? std::max(40,
                         (text_width(ticks[i].label) + text_width(ticks[i - 1].label) + 1) / 2 + 12)
              : 3 * text_height() + 6;
      fits = gap >= need;
    }
    if (fits) fitting.push_back(std::move(ticks));
  }
  for (const std::size_t least : {3u, 2u, 1u}) {
    for (auto& ticks : fitting) {
      if (ticks.size() >= least) return std::move(ticks);
    }
  }
  return {};
}

std::vector<PlotTick> xy_ticks(const XyScale& scale, bool horizontal) {
  std::vector<TickSet> sets;
  if (scale.log) {
    sets = log_tick_sets(scale.lo, scale.hi);
  } else {
    add_linear_ticks(scale.lo, scale.hi, sets);
  }
  return choose_ticks(sets, scale, horizontal);
}

// Filled 5x5 squares for even series, crosses 7 high (two pixels wide) for odd ones, centred
// on (x, y).
void draw_marker(Image& img, int x, int y, std::size_t series, Rgb8 colour, const Rect& clip) {
  const auto set = [&](int px, int py) {
    if (px >= clip.x0 && px <= clip.x1 && py >= clip.y0 && py <= clip.y1) img.at(px, py) = colour;
  };
  for (int a = -3; a <= 3; ++a) {
    if (series % 2 == 0) {
      for (int b = -2; b <= 2; ++b) {
        if (std::abs(a) <= 2) set(x + a, y + b);
      }
    } else {
      for (const int dx : {0, 1}) {
        set(x + a + dx, y + a);
        set(x + a + dx, y - a);
      }
    }
  }
}

}  // namespace

Image plot_curves(const std::vector<Curve>& curves, std::string_view title, int width, int height) {
  std::size_t n = 0;
  std::vector<std::string> labels;
  for (const Curve& c : curves) {
    n = std::max(n, c.values.size());
    labels.push_back(c.label);
  }
  PlotFrame frame(width, height, title);
  const int y1 = frame.area().y1;
  const int ph = y1 - frame.area().y0;
  const auto to_py = [&](double v) {
    return y1 - static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * ph));
  };
  // y: gridlines and labels every 0.2.
  std::vector<PlotTick> y_ticks;
  for (int i = 0; i <= 5; ++i) {
    y_ticks.push_back({to_py(i / 5.0), fmt::format("{:g}", i / 5.0)});
  }
  frame.set_columns(widest_label(y_ticks), labels);

  const Rect& area = frame.area();
  const int pw = area.x1 - area.x0;
  const double x_max = n > 1 ? static_cast<double>(n - 1) : 1.0;
  const auto to_px = [&](double x) {
    return area.x0 + static_cast<int>(std::lround(x / x_max * pw));
  };
  // x: a 1-2-5 step wide enough that neighbouring labels do not touch.
  const int widest = text_width(fmt::format("{}", static_cast<long>(x_max)));
  long step = nice_step(x_max / 10.0);
  while (static_cast<double>(step) / x_max * pw < widest + 8) step = nice_step(step + 1.0);
  std::vector<PlotTick> x_ticks;
  for (long x = 0; static_cast<double>(x) <= x_max; x += step) {
    x_ticks.push_back({to_px(static_cast<double>(x)), fmt::format("{}", x)});
  }
  Image img = frame.draw("pixel x", "I(x, y)", x_ticks, y_ticks);

  for (std::size_t i = 0; i < curves.size(); ++i) {
    const Rgb8 colour = curve_colour(i);
    const auto& v = curves[i].values;
    bool have_prev = false;
    int prev_x = 0;
    int prev_y = 0;
    for (std::size_t x = 0; x < v.size(); ++x) {
      if (std::isnan(v[x])) {
        have_prev = false;
        continue;
      }
      const int px = to_px(static_cast<double>(x));
      const int py = to_py(v[x]);
      if (have_prev) {
        plot_line(img, prev_x, prev_y, px, py, colour, area);
      } else {
        plot_point(img, px, py, colour, area);
      }
      have_prev = true;
      prev_x = px;
      prev_y = py;
    }
  }
  frame.draw_legend(img, labels, [](Image& out, const Rect& box, std::size_t i) {
    fill_rect(out, box.x0, box.y0, box.x1 - box.x0 + 1, box.y1 - box.y0 + 1, curve_colour(i));
  });
  return img;
}

Image plot_xy(const std::vector<XySeries>& series, const XyAxes& axes, std::string_view title,
              int width, int height) {
  XyScale xs{.log = axes.log_x};
  XyScale ys{.log = axes.log_y};
  std::vector<double> xv;
  std::vector<double> yv;
  std::vector<std::string> labels;
  for (const XySeries& s : series) {
    labels.push_back(s.label);
    for (const auto& [x, y] : s.points) {
      if (xs.shows(x) && ys.shows(y)) {
        xv.push_back(x);
        yv.push_back(y);
      }
    }
  }
  if (!fit_range(xs, xv, "x") || !fit_range(ys, yv, "y")) {
    throw Error(fmt::format("plot_xy: no point to plot (finite{})",
                            axes.log_x || axes.log_y ? ", and positive on a log axis" : ""));
  }

  PlotFrame frame(width, height, title);
  ys.p0 = frame.area().y1;
  ys.p1 = frame.area().y0;
  const std::vector<PlotTick> y_ticks = xy_ticks(ys, false);
  frame.set_columns(widest_label(y_ticks), labels);
  const Rect& area = frame.area();
  xs.p0 = area.x0;
  xs.p1 = area.x1;
  const std::vector<PlotTick> x_ticks = xy_ticks(xs, true);
  Image img = frame.draw(axes.x_label, axes.y_label, x_ticks, y_ticks);

  // All lines first, so that no line hides a marker.
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (!series[i].lines) continue;
    bool have_prev = false;
    int prev_x = 0;
    int prev_y = 0;
    for (const auto& [x, y] : series[i].points) {
      if (!xs.shows(x) || !ys.shows(y)) {
        have_prev = false;
        continue;
      }
      const int px = xs.pixel(x);
      const int py = ys.pixel(y);
      if (have_prev) plot_line(img, prev_x, prev_y, px, py, curve_colour(i), area);
      have_prev = true;
      prev_x = px;
      prev_y = py;
    }
  }
  for (std::size_t i = 0; i < series.size(); ++i) {
    for (const auto& [x, y] : series[i].points) {
      if (xs.shows(x) && ys.shows(y)) {
        draw_marker(img, xs.pixel(x), ys.pixel(y), i, curve_colour(i), area);
      }
    }
  }
  frame.draw_legend(img, labels, [&](Image& out, const Rect& box, std::size_t i) {
    const int cx = (box.x0 + box.x1) / 2;
    const int cy = (box.y0 + box.y1) / 2;
    const Rect whole{0, 0, out.width() - 1, out.height() - 1};
    if (series[i].lines) plot_line(out, box.x0, cy, box.x1 - 1, cy, curve_colour(i), whole);
    draw_marker(out, cx, cy, i, curve_colour(i), whole);
  });
  return img;
}

}  // namespace phongsim
