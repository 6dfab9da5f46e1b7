// What `phongsim analyze` prints, kept twice: as the text report (printed as it is made) and as
// tables of values for its JSON (docs/json.md). A pipeline's analysis (sim/pipelines) prints its
// text with print() and declares each table it prints with table() and row().
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace phongsim {

using ReportCell = std::variant<std::string, double, std::int64_t>;

struct ReportTable {
  std::string title;
  std::vector<std::string> columns;  // keys for JSON: lower_snake_case, unique in the table
  std::vector<std::vector<ReportCell>> rows;
};

class AnalysisReport {
 public:
  explicit AnalysisReport(std::FILE* text) : text_(text) {}

  template <class... T>
  void print(fmt::format_string<T...> format, T&&... args) {
    fmt::print(text_, format, std::forward<T>(args)...);
  }
  void table(std::string title, std::vector<std::string> columns) {
    tables_.push_back({std::move(title), std::move(columns), {}});
  }
  void row(std::vector<ReportCell> cells) { tables_.back().rows.push_back(std::move(cells)); }
  [[nodiscard]] const std::vector<ReportTable>& tables() const { return tables_; }

 private:
  std::FILE* text_;
  std::vector<ReportTable> tables_;
};

}  // namespace phongsim
