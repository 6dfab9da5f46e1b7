#include "sim/cosim/portable.h"

#include <fmt/format.h>

#include <array>
#include <regex>
#include <sstream>

#include "base/file_util.h"

namespace phongsim {
namespace {

struct Construct {
  const char* pattern;  // on the source line
  const char* what;
  const char* instead;  // an imperative: what to write
};

// In the order they are tried: the first that matches the line is named.
const std::array<Construct, 7> kConstructs = {{
    {R"(\breturn\b)", "a function's return",
     "assign the result to the function's name (f = value;)"},
    {R"(\b(longint|int|shortint|byte|integer)\s*'\s*\()", "a cast to an integer type",
     "write a size cast, 64'(x), with $signed() where the sign matters"},
    {R"(\b[A-Za-z_]\w*\s*'\s*\()", "a cast to a type name",
     "write a size cast, W'(x), with $signed() where the sign matters"},
    {R"(^\s*(logic|bit|reg|int|integer|[A-Za-z_]\w*_t)\b[^;()]*\w\s*=[^=])",
     "a declaration with an initial value (in a function or a task)",
     "declare the variable, then assign it"},
    {R"('\{)", "an assignment pattern '{...}", "assign each element, or use a concatenation"},
    {R"(\bint\s+unsigned\b)", "an int unsigned declaration", "write bit [31:0]"},
    {R"(\bimport\b[^;]*::)", "a package import", "write the package's names as pkg::name"},
}};

}  // namespace

std::string portable_hint(std::string_view tool_output, std::string_view tool) {
  // Yosys: "file.sv:49: ERROR: ..."; Icarus: "file.sv:49: error: ..." or "file.sv:49: sorry: ...".
  static const std::regex located(R"(([^\s:]+\.s?v[h]?):(\d+):)");
  std::match_results<std::string_view::const_iterator> m;
  if (!std::regex_search(tool_output.begin(), tool_output.end(), m, located)) return "";
  const std::string file = m[1].str();
  const int number = std::stoi(m[2].str());
  std::istringstream lines(read_file(file));
  std::string line;
  for (int i = 0; i < number && std::getline(lines, line); ++i) {
  }
  for (const Construct& c : kConstructs) {
    if (std::regex_search(line, std::regex(c.pattern))) {
      return fmt::format(
          "; {}:{} has {}, which {} does not read: instead, {} (docs/your-rtl.md, \"The "
          "portable subset\")",
          file, number, c.what, tool, c.instead);
    }
  }
  return "";
}

}  // namespace phongsim
