// Text helpers shared by every reader of line-oriented files (CSV vectors, tool logs, meshes):
// one trim and one CSV splitter for the whole tree.
#pragma once

#include <string_view>
#include <vector>

namespace phongsim {

// `s` without leading and trailing whitespace (space, tab, CR, LF, form feed, vertical tab).
[[nodiscard]] constexpr std::string_view trim(std::string_view s) {
  constexpr std::string_view kSpace = " \t\r\n\f\v";
  const auto first = s.find_first_not_of(kSpace);
  if (first == std::string_view::npos) return {};
  return s.substr(first, s.find_last_not_of(kSpace) - first + 1);
}

// The cells of one CSV line, split at every comma and each trimmed: "a, b," gives {"a", "b", ""},
// "" gives {""}. No quoting: phongsim's CSV files hold names and numbers only.
[[nodiscard]] inline std::vector<std::string_view> split_csv(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    cells.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string_view::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace phongsim
