// The renderer's files (sim/render/render.h: write_render_outputs, metrics_markdown): images,
// difference images, the scanline data and both figures, the metrics tables.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/output_file.h"
#include "base/temporaries.h"
#include "sim/render/plot.h"
#include "sim/render/render.h"

namespace phongsim {

namespace fs = std::filesystem;

std::string metrics_markdown(const RenderResult& r) {
  std::string s =
      "| method | backend | colour correctness (eq. 6.1) | PSNR (dB) | max error | pixels |";
  std::string rule = "|---|---|---|---|---|---|";
  for (const auto& region : r.regions) {
    s += fmt::format(" cc {} |", region.first);
    rule += "---|";
  }
  s += "\n" + rule + "\n";
  for (const MethodResult& m : r.results) {
    s += fmt::format(
        "| {} | {} | {:.4f} | {} | {} | {} |", m.method, backend_name(m.backend),
        m.metrics.colour_correctness,
        std::isinf(m.metrics.psnr) ? std::string("inf") : fmt::format("{:.2f}", m.metrics.psnr),
        m.metrics.max_error, m.metrics.pixels);
    for (const ImageMetrics& rm : m.region_metrics)
      s += fmt::format(" {:.4f} |", rm.colour_correctness);
    s += "\n";
  }
  return s;
}

std::string render_set_name(const RenderResult& r) { return "render " + r.scene; }

std::vector<fs::path> write_render_outputs(const RenderResult& r, OutputSet& set) {
  const int row = r.scanline;
  std::vector<fs::path> written;
  const auto name = [&](std::string_view suffix) {
    return fs::path(fmt::format("{}_{}", r.scene, suffix));
  };
  // Each file is written to its temporary first; scripts/plot.py reads the images from there.
  const auto add = [&](std::string_view suffix) -> OutputFile& {
    written.push_back(name(suffix));
    return set.add(name(suffix));
  };
  // The reference is a row and a curve of its own unless a float rendering of the same method
  // (the same image) is among the results: that one is then marked as the reference.
  const auto is_reference = [&](const MethodResult& m) {
    return m.method == r.reference.method && m.backend == Backend::float_ref &&
           m.image == r.reference.image;
  };
  const bool reference_listed = std::any_of(r.results.begin(), r.results.end(), is_reference);
  const auto plain_label = [](const MethodResult& m) {
    return fmt::format("{} [{}]", m.method, backend_name(m.backend));
  };
  const auto label = [&](const MethodResult& m) {
    return plain_label(m) + (is_reference(m) ? " (reference)" : "");
  };
  // Grid (scripts/plot.py grid): one row per method, image and difference; the reference's image
  // goes to a temporary directory for it.
  const TempDir scratch("out");
  const fs::path reference_png = scratch.path() / "reference.png";
  std::vector<std::string> grid{"--title", r.scene + r.settings, "--columns", "image",
                                fmt::format("difference from {} (eq. 6.2)", r.reference.method)};
  if (!reference_listed) {
    write_png(r.reference.image, reference_png);
    grid.insert(grid.end(),
                {"--row", plain_label(r.reference) + " (reference)", reference_png.string(), "-"});
  }
  // Scanline (scripts/plot.py scanline): eq. 6.3 along the row, one column per curve.
  std::vector<std::string> names;
  std::vector<std::vector<double>> curves;
  if (!reference_listed) {
    names.push_back(plain_label(r.reference) + " (reference)");
    curves.push_back(illumination_row(r.reference.image, row));
  }
  for (const MethodResult& m : r.results) {
    const Image diff = difference_image(r.reference.image, m.image);
    OutputFile& image = add(m.method + ".png");
    write_png(m.image, image);
    OutputFile& difference = add(m.method + "_diff.png");
    write_png(diff, difference);
    grid.insert(grid.end(),
                {"--row", label(m), image.temp_path().string(), difference.temp_path().string()});
    names.push_back(label(m));
    curves.push_back(illumination_row(m.image, row));
  }
  OutputFile& scanline_csv = add("scanline.csv");
  std::string data = "x";
  for (const std::string& n : names) data += "," + n;
  data += "\n";
  for (std::size_t x = 0; x < curves.front().size(); ++x) {
    data += fmt::format("{}", x);
    for (const auto& c : curves) data += fmt::format(",{:.6f}", c[x]);
    data += "\n";
  }
  std::fputs(data.c_str(), scanline_csv.get());
  std::fflush(scanline_csv.get());
  plot_figure("grid", grid, add("grid.png"));
  plot_figure("scanline",
              {"--csv", scanline_csv.temp_path().string(), "--title",
               fmt::format("{}: illumination along row {} (eq. 6.3){}", r.scene, row, r.settings)},
              add("scanline.png"));

  // Per triangle (scripts/plot.py cost): the walker's cycles against the pixels it covers.
  std::string cost = "method,backend,triangle,pixels,cycles,setup_cycles,empty_row_cycles\n";
  bool walked = false;
  for (const MethodResult& m : r.results) {
    if (!m.frame) continue;
    for (const auto& [triangle, c] : m.frame->triangles) {
      cost += fmt::format("{},{},{},{},{},{},{}\n", m.method, backend_name(m.backend), triangle,
                          c.outputs, c.cycles, c.setup_cycles, c.empty_row_cycles);
      walked = true;
    }
  }
  if (walked) {
    OutputFile& cost_csv = add("triangle_cycles.csv");
    std::fputs(cost.c_str(), cost_csv.get());
    std::fflush(cost_csv.get());
    plot_figure("cost",
                {"--csv", cost_csv.temp_path().string(), "--title",
                 fmt::format("{}: clocks per triangle on the quadratic walker", r.scene)},
                add("triangle_cycles.png"));
  }

  OutputFile& csv = add("metrics.csv");
  std::string text =
      "method,backend,colour_correctness,psnr_db,max_error,pixels,seconds,cpu_seconds";
  for (const auto& region : r.regions) text += ",cc_" + region.first;
  text += "\n";
  for (const MethodResult& m : r.results) {
    text += fmt::format("{},{},{:.6f},{:.4f},{},{},{:.6f},{:.6f}", m.method,
                        backend_name(m.backend), m.metrics.colour_correctness, m.metrics.psnr,
                        m.metrics.max_error, m.metrics.pixels, m.seconds, m.cpu_seconds);
    for (const ImageMetrics& rm : m.region_metrics) {
      text += fmt::format(",{:.6f}", rm.colour_correctness);
    }
    text += "\n";
  }
  std::fputs(text.c_str(), csv.get());
  OutputFile& md = add("metrics.md");
  std::fputs(fmt::format("Scene {}, reference {} (float){}\n\n{}", r.scene, r.reference.method,
                         r.settings, metrics_markdown(r))
                 .c_str(),
             md.get());
  return written;
}

}  // namespace phongsim
