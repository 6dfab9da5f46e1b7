// Figures drawn by matplotlib: phongsim writes the data (CSV files, the images themselves) and
// one script, scripts/plot.py, draws every figure from it — the render grid and scanline plot
// (docs/render.md) and the sweep's Pareto plot (docs/exploration.md).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "base/output_file.h"

namespace phongsim {

// Runs `<python_program()> scripts/plot.py <figure> <args...> --out <temporary>` (no shell;
// base/paths.h, base/process.h) and moves the PNG to `out` once the script succeeds, so nothing
// appears at `out` otherwise. Error "cannot write <out>: <the script's last line>" when Python
// cannot start, matplotlib is missing or the data is bad. scripts/plot.py documents the figures
// and their arguments.
void plot_figure(std::string_view figure, const std::vector<std::string>& args,
                 const std::filesystem::path& out);

// The same into an output already open (the figure goes to its temporary file; committing it
// is the caller's, e.g. with the other files of an OutputSet).
void plot_figure(std::string_view figure, const std::vector<std::string>& args, OutputFile& out);

}  // namespace phongsim
