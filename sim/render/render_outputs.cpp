// The renderer's files (sim/render/render.h: write_render_outputs, metrics_markdown): images,
// difference images, the scanline data and both figures, the metrics tables.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "base/error.h"
#include "base/output_file.h"
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

std::vector<fs::path> write_render_outputs(const RenderResult& r, const fs::path& dir) {
  const int row = r.scanline;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(fmt::format("cannot create {}: {}", dir.string(), ec.message()));
  { OutputFile probe(dir / ".phongsim-write-test"); }  // unwritable: fail before any output

  std::vector<fs::path> written;
  const auto path = [&](std::string_view suffix) {
    return dir / fmt::format("{}_{}", r.scene, suffix);
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
  // goes to a temporary file for it.
  const fs::path reference_png =
      dir / fmt::format(".{}_reference.tmp.{}.png", r.scene, static_cast<long>(getpid()));
  struct Remove {
    fs::path p;
    ~Remove() {
      std::error_code e;
      fs::remove(p, e);
    }
  } remove_reference{reference_png};
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
    write_png(m.image, path(m.method + ".png"));
    write_png(diff, path(m.method + "_diff.png"));
    written.push_back(path(m.method + ".png"));
    written.push_back(path(m.method + "_diff.png"));
    grid.insert(grid.end(), {"--row", label(m), path(m.method + ".png").string(),
                             path(m.method + "_diff.png").string()});
    names.push_back(label(m));
    curves.push_back(illumination_row(m.image, row));
  }
  OutputFile scanline_csv(path("scanline.csv"));
  std::string data = "x";
  for (const std::string& n : names) data += "," + n;
  data += "\n";
  for (std::size_t x = 0; x < curves.front().size(); ++x) {
    data += fmt::format("{}", x);
    for (const auto& c : curves) data += fmt::format(",{:.6f}", c[x]);
    data += "\n";
  }
  std::fputs(data.c_str(), scanline_csv.get());
  scanline_csv.commit();
  written.push_back(path("scanline.csv"));
  plot_figure("grid", grid, path("grid.png"));
  written.push_back(path("grid.png"));
  plot_figure("scanline",
              {"--csv", path("scanline.csv").string(), "--title",
               fmt::format("{}: illumination along row {} (eq. 6.3){}", r.scene, row, r.settings)},
              path("scanline.png"));
  written.push_back(path("scanline.png"));

  OutputFile csv(path("metrics.csv"));
  std::string text =
      "method,backend,colour_correctness,psnr_db,max_error,pixels,seconds,cpu_seconds\n";
  for (const MethodResult& m : r.results) {
    text += fmt::format("{},{},{:.6f},{:.4f},{},{},{:.6f},{:.6f}\n", m.method,
                        backend_name(m.backend), m.metrics.colour_correctness, m.metrics.psnr,
                        m.metrics.max_error, m.metrics.pixels, m.seconds, m.cpu_seconds);
  }
  std::fputs(text.c_str(), csv.get());
  csv.commit();
  written.push_back(path("metrics.csv"));
  OutputFile md(path("metrics.md"));
  std::fputs(fmt::format("Scene {}, reference {} (float){}\n\n{}", r.scene, r.reference.method,
                         r.settings, metrics_markdown(r))
                 .c_str(),
             md.get());
  md.commit();
  written.push_back(path("metrics.md"));
  return written;
}

}  // namespace phongsim
