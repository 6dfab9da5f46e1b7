// Image utilities for the renderer and its reports: an 8-bit RGB image, PNG output and input
// (libpng), bitmap text, labelled grids, the
// difference image and metrics of Vlasic's evaluation (eqs. 6.1-6.3), and scanline plots.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

// Fills the rectangle [x, x+w) x [y, y+h), clipped to the image.
void fill_rect(Image& img, int x, int y, int w, int h, Rgb8 colour);

// Writes an 8-bit RGB PNG through libpng, atomically through OutputFile: nothing appears at
// `path` on failure. Error "cannot write <path>: ..." (an empty image is refused up front).
void write_png(const Image& img, const std::filesystem::path& path);
// Reads an 8-bit RGB PNG (as write_png makes; interlaced too) through libpng. Error
// "cannot read <path>: ..." for anything else (grey, palette, alpha, 16-bit), for truncated or
// corrupt files and for images larger than Image::kMaxSize.
Image read_png(const std::filesystem::path& path);

// Bitmap text in an embedded 5x7 font (plus one descender row) covering printable ASCII 32..126,
// scaled by an integer factor >= 1. (x, y) is the top-left of the text box; a character advances
// 6 * scale pixels. Anything outside 32..126 is drawn as '?' (a UTF-8 sequence counts as one
// character). Clipped to the image; one line only.
void draw_text(Image& img, int x, int y, std::string_view text, Rgb8 colour, int scale = 1);
// The box draw_text may touch: no trailing gap after the last character; 0 for empty text.
[[nodiscard]] int text_width(std::string_view text, int scale = 1);
[[nodiscard]] int text_height(int scale = 1);

// Copies src with its top-left at (x, y) in dst, clipped.
void blit(Image& dst, const Image& src, int x, int y);

// A labelled grid: cells[r][c] centred in their slots (rows may have different cell counts and
// sizes; empty Images are blank), row labels left of each row, column labels above each column,
// optional title (empty = none). White background, black text, a few pixels of padding.
Image grid(const std::vector<std::vector<Image>>& cells, const std::vector<std::string>& row_labels,
           const std::vector<std::string>& col_labels, std::string_view title = {});

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

struct Curve {
  std::string label;
  std::vector<double> values;
};

// The colour plot_curves gives curve i and plot_xy series i (a fixed palette of 10 distinct
// colours, repeating).
[[nodiscard]] Rgb8 curve_colour(std::size_t i);

// A line plot of scanline illumination curves (eq. 6.3): x axis pixel column 0..n-1 (n the
// longest curve), y axis 0..1 (values outside are clamped, NaNs break the line), tick labels,
// one polyline per curve in curve_colour(i), a legend to the right, and a title. Error if the
// size leaves no room for the plot.
Image plot_curves(const std::vector<Curve>& curves, std::string_view title, int width = 800,
                  int height = 400);

struct XySeries {
  std::string label;
  std::vector<std::pair<double, double>> points;  // (x, y)
  bool lines = true;  // join the points with lines in the given order (a skipped point breaks it)
};

struct XyAxes {
  std::string x_label, y_label;       // captions below the x axis and above the y axis
  bool log_x = false, log_y = false;  // log10 axes: non-positive values are skipped on them
};

// A scatter/line plot, e.g. of Pareto fronts (error against area). Each axis spans its data
// (finite values; positive ones on a log axis), padded by 5% on both sides (a single value gets
// +-10% of itself, or +-1 for zero; a decade either way on a log axis). Ticks at 1-2-5 steps (on
// log axes decades, or 1-2-5 within decades, or plain steps when the range is under a decade),
// as dense as their labels allow without crowding; labels are short ("12000", "0.5", "1e-3",
// "1.2e+7"). Points whose x or y cannot be shown are skipped. Series i is drawn in
// curve_colour(i) as markers (filled squares for even i, crosses for odd i), joined by 2-pixel
// lines when `lines`; a legend to the right, the title above, same frame as plot_curves. Error
// if no series has a point that can be shown, or the size leaves no room for the plot.
Image plot_xy(const std::vector<XySeries>& series, const XyAxes& axes, std::string_view title,
              int width = 800, int height = 500);

}  // namespace phongsim
