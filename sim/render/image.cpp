#include "sim/render/image.h"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cassert>
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
  write_png(img, out);
  out.commit();
}

void write_png(const Image& img, OutputFile& out) {
  if (img.empty()) {
    throw Error(fmt::format("cannot write {}: the image is empty ({}x{})", out.path().string(),
                            img.width(), img.height()));
  }
  PngImage png;
  png.image.width = static_cast<png_uint_32>(img.width());
  png.image.height = static_cast<png_uint_32>(img.height());
  png.image.format = PNG_FORMAT_RGB;
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(img.pixels().data());
  if (png_image_write_to_stdio(&png.image, out.get(), 0, bytes, 0, nullptr) == 0) {
    throw Error(fmt::format("cannot write {}: {}", out.path().string(), png.image.message));
  }
  if (std::fflush(out.get()) != 0) {
    throw Error(fmt::format("cannot write {}: {}", out.path().string(), std::strerror(errno)));
  }
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

}  // namespace phongsim
