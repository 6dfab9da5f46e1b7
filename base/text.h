// Text helpers shared by every reader of line-oriented files (CSV vectors, tool logs, meshes):
// one trim and one CSV splitter for the whole tree.
#pragma once

#include <fmt/format.h>

#include <string>
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

// `s` as one word a POSIX shell reads back unchanged (for the commands phongsim prints to be
// pasted): as it is when it holds only letters, digits and _@%+=:,./-; else in single quotes;
// with control characters (a newline in a file name) as bash's $'...' (printf %q's rules).
[[nodiscard]] inline std::string shell_quoted(std::string_view s) {
  constexpr std::string_view kPlain =
      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_@%+=:,./-";
  if (!s.empty() && s.find_first_not_of(kPlain) == std::string_view::npos) return std::string(s);
  bool control = false;
  for (const char c : s) control = control || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  std::string q;
  if (!control) {
    q = "'";
    for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }
  q = "$'";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\\' || c == '\'') {
      q += '\\';
      q += c;
    } else if (c == '\n') {
      q += "\\n";
    } else if (c == '\t') {
      q += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      q += fmt::format("\\x{:02x}", u);
    } else {
      q += c;
    }
  }
  return q + "'";
}

}  // namespace phongsim
