// Images for the renderer and its reports: an 8-bit RGB image, PNG output and input (libpng),
// and the difference image and metrics of Vlasic's evaluation (eqs. 6.1-6.3). Figures made of
// images and data (grids, plots) are drawn by scripts/plot.py (sim/render/plot.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <vector>

#include "base/output_file.h"

namespace phongsim {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8&) const = default;
};

inline constexpr Rgb8 kBlack{0, 0, 0};
inline constexpr Rgb8 kWhite{255, 255, 255};

// 8-bit RGB, row-major, y grows downward.
class Image {
 public:
  static constexpr int kMaxSize = 32768;

  Image() = default;
  Image(int width, int height, Rgb8 fill = {});  // Error for negative or > kMaxSize sizes

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  [[nodiscard]] bool empty() const { return pixels_.empty(); }
  [[nodiscard]] bool contains(int x, int y) const {
    return x >= 0 && y >= 0 && x < width_ && y < height_;
  }

  // Unchecked in release builds (assert otherwise): callers clip.
  Rgb8& at(int x, int y);
  [[nodiscard]] const Rgb8& at(int x, int y) const;

  [[nodiscard]] const std::vector<Rgb8>& pixels() const { return pixels_; }

  bool operator==(const Image&) const = default;

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Rgb8> pixels_;
};

// Writes an 8-bit RGB PNG through libpng, atomically through OutputFile: nothing appears at
// `path` on failure. Error "cannot write <path>: ..." (an empty image is refused up front).
void write_png(const Image& img, const std::filesystem::path& path);
// The same into an output already open; committing it is the caller's.
void write_png(const Image& img, OutputFile& out);
// Reads an 8-bit RGB PNG (as write_png makes; interlaced too) through libpng. Error
// "cannot read <path>: ..." for anything else (grey, palette, alpha, 16-bit), for files cut
// short before their final IEND chunk, corrupt files and images larger than Image::kMaxSize.
// Values are sRGB: libpng converts a file whose gAMA chunk says otherwise (write_png's files,
// tagged sRGB, and untagged ones are read as they are).
Image read_png(const std::filesystem::path& path);

// Vlasic eq. 6.2 difference image: per channel 255 * (|A - B| / 255)^(1/10), rounded to nearest,
// so that small errors stay visible. Error if sizes differ.
Image difference_image(const Image& reference, const Image& img);

struct ImageMetrics {
  double colour_correctness = 1;  // Vlasic eq. 6.1: 1 - sum(|dR|+|dG|+|dB|) / (3 * 255 * N)
  double psnr = std::numeric_limits<double>::infinity();  // 10 log10(255^2 / MSE); inf if equal
  int max_error = 0;                                      // largest |d| of any channel
  std::size_t pixels = 0;                                 // N
};

// Metrics of `img` against `reference` over the pixels where `mask` (row-major, true = object
// pixel) is set; an empty mask means all pixels. No pixels selected gives the defaults (N = 0).
// Error if sizes differ or the mask has the wrong length.
ImageMetrics compare(const Image& reference, const Image& img, const std::vector<bool>& mask = {});

// Vlasic eq. 6.3 illumination I(x, y) = (R + G + B) / (3 * 255) along row y, for every x.
std::vector<double> illumination_row(const Image& img, int y);

}  // namespace phongsim
