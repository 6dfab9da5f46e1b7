#include "sim/cosim/coverage.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <regex>
#include <vector>

#include "base/error.h"
#include "base/process.h"

namespace phongsim {
namespace fs = std::filesystem;

double CoverageSummary::line_percent() const {
  return line_points == 0 ? 0.0 : 100.0 * static_cast<double>(line_hit) / line_points;
}

double CoverageSummary::toggle_percent() const {
  return toggle_points == 0 ? 0.0 : 100.0 * static_cast<double>(toggle_hit) / toggle_points;
}

std::string coverage_prefix(const fs::path& dir) {
  const fs::path data = dir / "data";
  std::error_code ec;
  fs::create_directories(data, ec);
  if (ec) throw Error(fmt::format("cannot create {}: {}", data.string(), ec.message()));
  const auto now = std::chrono::duration_cast<std::chrono::microseconds>(
                       std::chrono::system_clock::now().time_since_epoch())
                       .count();
  return (data / fmt::format("{}-{}-", now, getpid())).string();
}

namespace {

// A point's field `name` from its key ("\x01name\x02value\x01..."), or "".
std::string field(const std::string& key, std::string_view name) {
  const std::string mark = fmt::format("\x01{}\x02", name);
  const auto at = key.find(mark);
  if (at == std::string::npos) return "";
  const auto start = at + mark.size();
  return key.substr(start, key.find('\x01', start) - start);
}

// Adds every point of one coverage.dat ("C '<key>' <count>" lines) to `points`.
void read_points(const fs::path& file, std::map<std::string, std::uint64_t>& points) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read {}", file.string()));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("C '", 0) != 0) continue;
    const auto end = line.rfind('\'');
    if (end <= 2) throw Error(fmt::format("{}: not a Verilator coverage file", file.string()));
    points[line.substr(3, end - 3)] += std::stoull(line.substr(end + 1));
  }
}

// The waiver that leaves the point with key `key` out, or null.
const LineWaiver* waiver_of(const std::string& key, std::span<const LineWaiver> waivers,
                            const std::vector<std::regex>& res) {
  const std::string file = field(key, "f");
  // The first line of the statements the point counts ("S=80-81": an if's arm; "l" is the if's
  // own line, the same for its else arm, which may have no statements of its own and no S:
  // never waived).
  const std::string span = field(key, "S");
  int line = 0;
  try {
    line = std::stoi(span);
  } catch (const std::exception&) {
    return nullptr;
  }
  for (std::size_t i = 0; i < waivers.size(); ++i) {
    const LineWaiver& w = waivers[i];
    if (line >= w.first_line && line <= w.last_line && file.size() >= w.file.size() &&
        file.compare(file.size() - w.file.size(), w.file.size(), w.file) == 0 &&
        std::regex_search(field(key, "h"), res[i])) {
      return &w;
    }
  }
  return nullptr;
}

std::string first_lines(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  return s.empty() ? "no output" : s;
}

}  // namespace

CoverageSummary count_coverage_points(const std::map<std::string, std::uint64_t>& points,
                                      std::span<const LineWaiver> waivers) {
  CoverageSummary s;
  std::vector<std::regex> res;
  for (const LineWaiver& w : waivers) res.emplace_back(w.hier);
  for (const auto& [key, count] : points) {
    const std::string page = field(key, "page");
    if (page.rfind("v_toggle", 0) == 0) {
      ++s.toggle_points;
      s.toggle_hit += count > 0 ? 1 : 0;
    } else if (page.rfind("v_line", 0) == 0 || page.rfind("v_branch", 0) == 0) {
      if (const LineWaiver* w = waiver_of(key, waivers, res)) {
        if (count > 0) {
          throw Error(fmt::format("{} line {} in {} is waived ({}) but was reached",
                                  field(key, "f"), field(key, "l"), field(key, "h"), w->reason));
        }
        ++s.line_waived;
        s.waived.push_back({field(key, "f"), field(key, "S"), field(key, "h"), w->reason});
        continue;
      }
      ++s.line_points;
      s.line_hit += count > 0 ? 1 : 0;
    }
  }
  return s;
}

CoverageSummary merge_coverage(const fs::path& dir, std::span<const LineWaiver> waivers) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "data", ec)) {
    if (e.path().extension() == ".dat") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw Error(fmt::format("{}: no coverage data", (dir / "data").string()));
  std::map<std::string, std::uint64_t> points;
  for (const auto& f : files) read_points(f, points);
  CoverageSummary s = count_coverage_points(points, waivers);
  s.files = files.size();
  const std::string info = (dir / "coverage.info").string();
  std::vector<std::string> merge{"verilator_coverage", "--write-info", info};
  merge.insert(merge.end(), files.begin(), files.end());
  if (const ProcessResult r = run_process(merge); r.exit_code != 0) {
    throw Error(fmt::format("verilator_coverage failed: {}", first_lines(r.out)));
  }
  const fs::path html = dir / "html";
  fs::remove_all(html, ec);
  if (const ProcessResult r =
          run_process({"genhtml", "--quiet", "--output-directory", html.string(), info});
      r.exit_code != 0) {
    throw Error(
        fmt::format("genhtml failed (scripts/setup.sh installs lcov): {}", first_lines(r.out)));
  }
  return s;
}

}  // namespace phongsim
