// The two tables of a forward-differencing pipeline's analysis (kb, quad): drift by size and
// guard bits, and the guard bits a drift of at most 1/2 output LSB needs, measured against the
// analytic bound. Printed as text and declared as tables for JSON alike (sim/cosim/report.h).
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/cosim/report.h"

namespace phongsim {

// drift(size, g): the measured drift in output LSBs. Rows: `sizes`, first column `key` printed
// `width` wide; columns: G = each of `guards`.
inline void drift_table(AnalysisReport& out, std::string title, std::string_view key, int width,
                        std::span<const int> sizes, std::span<const int> guards,
                        const std::function<double(int, int)>& drift) {
  out.print("  {:>{}}", key, width);
  std::vector<std::string> columns{std::string(key)};
  for (const int g : guards) {
    out.print(" {:>9}", fmt::format("G={}", g));
    columns.push_back(fmt::format("g{}", g));
  }
  out.print("\n");
  out.table(std::move(title), std::move(columns));
  for (const int size : sizes) {
    out.print("  {:>{}}", size, width);
    std::vector<ReportCell> cells{static_cast<std::int64_t>(size)};
    for (const int g : guards) {
      const double d = drift(size, g);
      out.print(" {:>9.4f}", d);
      cells.emplace_back(d);
    }
    out.print("\n");
    out.row(std::move(cells));
  }
}

// Per size: analytic(size), and the smallest G (up to 40) whose drift is at most 1/2 LSB.
inline void guard_bits_table(AnalysisReport& out, std::string title, std::string_view key,
                             int width, std::span<const int> sizes,
                             const std::function<int(int)>& analytic,
                             const std::function<double(int, int)>& drift) {
  out.print("  {:>{}} {:>9} {:>9}\n", key, width, "analytic", "measured");
  out.table(std::move(title), {std::string(key), "analytic", "measured"});
  for (const int size : sizes) {
    int measured = 0;
    while (measured < 40 && drift(size, measured) > 0.5) ++measured;
    out.print("  {:>{}} {:>9} {:>9}\n", size, width, analytic(size), measured);
    out.row({static_cast<std::int64_t>(size), static_cast<std::int64_t>(analytic(size)),
             static_cast<std::int64_t>(measured)});
  }
}

}  // namespace phongsim
