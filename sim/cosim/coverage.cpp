#include "sim/cosim/coverage.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "base/error.h"
#include "base/file_util.h"
#include "base/process.h"
#include "base/temporaries.h"
#include "base/text.h"
#include "sim/cosim/rtl_sources.h"

namespace phongsim {
namespace fs = std::filesystem;

double CoverageSummary::line_percent() const {
  return line_points == 0 ? 0.0 : 100.0 * static_cast<double>(line_hit) / line_points;
}

double CoverageSummary::toggle_percent() const {
  return toggle_points == 0 ? 0.0 : 100.0 * static_cast<double>(toggle_hit) / toggle_points;
}

std::uint64_t CoverageSummary::not_toggled_bits() const {
  std::uint64_t bits = 0;
  for (const UncountedSignal& s : not_toggled) bits += s.bits;
  return bits;
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

LineWaiver fx_resize_saturation_waiver(std::string hier, std::string_view side,
                                       std::string reason) {
  if (side != "high" && side != "low") {
    throw Error(fmt::format("fx_resize saturates high or low, not '{}'", side));
  }
  return {std::move(hier), "rtl/common/fx_resize.sv", fmt::format("saturate.{}", side),
          std::move(reason)};
}

// ---- the user's waivers ----

std::string UserWaiver::where() const {
  std::string s = file;
  if (first_line > 0) {
    s += fmt::format(":{}", first_line);
    if (last_line != first_line) s += fmt::format("-{}", last_line);
  }
  if (!pattern.empty()) s += fmt::format(" /{}/", pattern);
  if (!instance.empty()) s += " @" + instance;
  return s;
}

namespace {

// `text` compiled as an ECMAScript regex; Error "ORIGIN: WHAT /text/ is not a regular
// expression: ..." otherwise.
std::regex compiled(const std::string& text, const std::string& origin, std::string_view what) {
  try {
    return std::regex(text);
  } catch (const std::regex_error& e) {
    throw Error(
        fmt::format("{}: {} /{}/ is not a regular expression: {}", origin, what, text, e.what()));
  }
}

// A line number of a waiver ("61"), or nothing.
std::optional<int> line_number(std::string_view s) {
  if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string_view::npos) {
    return std::nullopt;
  }
  const int n = std::stoi(std::string(s));
  return n > 0 ? std::optional<int>(n) : std::nullopt;
}

UserWaiver parse_waiver(std::string_view line, const std::string& origin) {
  UserWaiver w;
  w.origin = origin;
  const auto fail = [&](const std::string& what) {
    throw Error(fmt::format("{}: {}", origin, what));
  };
  std::string_view rest = trim(line);
  const auto word_end = [](std::string_view s) {
    const auto e = s.find_first_of(" \t");
    return e == std::string_view::npos ? s.size() : e;
  };
  // SOURCE[:LINE[-LAST]]
  std::string_view source = rest.substr(0, word_end(rest));
  rest = trim(rest.substr(source.size()));
  if (const auto colon = source.rfind(':'); colon != std::string_view::npos) {
    const std::string_view range = source.substr(colon + 1);
    const auto dash = range.find('-');
    const auto first = line_number(range.substr(0, dash));
    const auto last = dash == std::string_view::npos ? first : line_number(range.substr(dash + 1));
    if (!first || !last || *last < *first) {
      fail(
          fmt::format("'{}' is not SOURCE:LINE or SOURCE:LINE-LAST (lines from 1, LAST not "
                      "before LINE)",
                      source));
    }
    w.first_line = *first;
    w.last_line = *last;
    source = source.substr(0, colon);
  }
  if (source.starts_with("./")) source.remove_prefix(2);
  if (source.empty() || source.starts_with("/") || source.starts_with("@")) {
    fail(
        "a waiver starts with the source file it waives points of (its name or its path's "
        "end): SOURCE[:LINE[-LAST]] [/REGEX/] [@INSTANCE] REASON");
  }
  w.file = std::string(source);
  // /REGEX/
  if (rest.starts_with("/")) {
    if (w.first_line > 0) fail("give lines (SOURCE:LINE) or a /REGEX/, not both");
    std::size_t i = 1;
    bool closed = false;
    for (; i < rest.size(); ++i) {
      if (rest[i] == '\\' && i + 1 < rest.size() && rest[i + 1] == '/') {
        w.pattern += '/';
        ++i;
      } else if (rest[i] == '/') {
        closed = true;
        break;
      } else {
        w.pattern += rest[i];
      }
    }
    if (!closed) fail("the /REGEX/ has no closing '/' (write \\/ for a '/' in it)");
    if (w.pattern.empty()) fail("an empty /REGEX/ matches every line; give lines or a pattern");
    (void)compiled(w.pattern, origin, "the pattern");
    rest = trim(rest.substr(i + 1));
  }
  // @INSTANCE
  if (rest.starts_with("@")) {
    const std::string_view inst = rest.substr(0, word_end(rest));
    w.instance = std::string(inst.substr(1));
    if (w.instance.empty()) fail("an empty @INSTANCE: give a regex of the instance hierarchy");
    (void)compiled(w.instance, origin, "the instance");
    rest = trim(rest.substr(inst.size()));
  }
  if (rest.empty()) fail("a waiver needs a reason (why the points cannot be reached)");
  w.reason = std::string(rest);
  return w;
}

}  // namespace

std::vector<UserWaiver> read_waivers(const fs::path& file) {
  std::istringstream in(read_file(file, "waiver file"));
  std::vector<UserWaiver> waivers;
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    const std::string_view t = trim(line);
    if (t.empty() || t.starts_with("#")) continue;
    waivers.push_back(parse_waiver(t, fmt::format("{}:{}", file.string(), n)));
  }
  return waivers;
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

bool is_toggle(const std::string& key) { return field(key, "page").rfind("v_toggle", 0) == 0; }

bool is_line(const std::string& key) {
  const std::string page = field(key, "page");
  return page.rfind("v_line", 0) == 0 || page.rfind("v_branch", 0) == 0;
}

// The lines a line point lies on: its statements' (S, "52,66-67,69"), or its own line (l) when
// it has none (an if's implicit else).
std::vector<int> point_lines(const std::string& key) {
  std::vector<int> lines;
  std::istringstream in(field(key, "S"));
  for (std::string part; std::getline(in, part, ',');) {
    const auto dash = part.find('-');
    const auto first = line_number(part.substr(0, dash));
    const auto last = dash == std::string::npos ? first : line_number(part.substr(dash + 1));
    if (!first || !last) continue;
    for (int l = *first; l <= *last && l - *first < 100000; ++l) lines.push_back(l);
  }
  if (lines.empty()) {
    if (const auto l = line_number(field(key, "l"))) lines.push_back(*l);
  }
  return lines;
}

// Whether Verilator's file path `path` is `file` or ends in "/" + `file`.
bool names_file(const std::string& path, const std::string& file) {
  if (path == file) return true;
  return path.size() > file.size() && path[path.size() - file.size() - 1] == '/' &&
         path.compare(path.size() - file.size(), file.size(), file) == 0;
}

// A regex that matches `text` literally.
std::string regex_literal(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (std::string_view(R"(\^$.|?*+()[]{}/)").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

// The lines of `lines` (the text of source file `path`) that phongsim's marker `name` marks:
// the line holding `phongsim: waive NAME`, or the lines from the one holding `phongsim:
// waive-begin NAME` to the one holding `phongsim: waive-end NAME`. Error naming the file and
// the marker when it is missing, on two lines, or a region is not closed.
std::set<int> marked_lines(const std::vector<std::string>& lines, const std::string& path,
                           const std::string& name) {
  const std::regex re("phongsim:[ \\t]*waive(-begin|-end)?[ \\t]+" + regex_literal(name) +
                      "(?![\\w.-])");
  std::vector<int> at[3];  // the lines of `waive`, `waive-begin` and `waive-end`
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::smatch m;
    if (!std::regex_search(lines[i], m, re)) continue;
    at[m[1].str() == "-begin" ? 1 : m[1].str() == "-end" ? 2 : 0].push_back(int(i) + 1);
  }
  const auto fail = [&](const std::string& what) {
    throw Error(fmt::format(
        "{}: phongsim's waiver marker '{}' {} (a line waiver names the RTL's `// phongsim: "
        "waive {}` on the waived line, or `waive-begin {}` ... `waive-end {}` around a region, "
        "exactly once: put it back on the line its waiver means, or fix the waiver)",
        path, name, what, name, name, name));
  };
  const auto where = [](const std::vector<int>& l) {
    return fmt::format("{}", fmt::join(l, ", "));
  };
  const std::size_t one = at[0].size(), begin = at[1].size(), end = at[2].size();
  if (one + begin + end == 0) fail("is on no line");
  if (one > 1) fail("is on several lines (" + where(at[0]) + ")");
  if (one == 1 && begin + end > 0) fail("marks a line and a region");
  if (one == 1) return {at[0][0]};
  if (begin != 1 || end != 1) {
    fail(
        fmt::format("needs one waive-begin and one waive-end (waive-begin on {} line(s) {}, "
                    "waive-end on {} line(s) {})",
                    begin, where(at[1]), end, where(at[2])));
  }
  if (at[2][0] < at[1][0]) fail("ends its region before it begins");
  std::set<int> out;
  for (int l = at[1][0]; l <= at[2][0]; ++l) out.insert(l);
  return out;
}

// Every waiver, phongsim's own (LineWaiver, first) and the user's (UserWaiver), matched by one
// rule: a waiver names lines of a source file (LINE..LAST, the lines a regex matches, the lines
// the RTL's marker marks, or the whole file) and leaves out the points of matching instances
// that lie on them; what each user's waiver matched, for the stale check.
class WaiverMatcher {
 public:
  struct Compiled {
    UserWaiver w;        // phongsim's as one: origin "", no lines nor pattern, instance `hier`
    std::string marker;  // phongsim's: the RTL's marker; "": a user's waiver
    std::optional<std::regex> pattern, instance;
    std::set<std::string> files;        // Verilator paths of points in SOURCE
    bool pattern_matched_line = false;  // the pattern matched a line of one of them
    bool on_lines = false;              // a point lay on its lines (any instance)
    std::uint64_t points = 0;           // points it left out
  };

  WaiverMatcher(std::span<const LineWaiver> builtin, std::span<const UserWaiver> user) {
    for (const LineWaiver& b : builtin) {
      Compiled c;
      c.w = {"", b.file, 0, 0, "", b.hier, b.reason};
      c.marker = b.marker;
      c.instance = compiled(b.hier, "phongsim's waiver of " + b.file, "the instance");
      waivers_.push_back(std::move(c));
    }
    for (const UserWaiver& w : user) {
      Compiled c;
      c.w = w;
      if (!w.pattern.empty()) c.pattern = compiled(w.pattern, w.origin, "the pattern");
      if (!w.instance.empty()) c.instance = compiled(w.instance, w.origin, "the instance");
      waivers_.push_back(std::move(c));
    }
  }

  // The first waiver that leaves out the line point `key`, or null. Every waiver that matches
  // counts the point (two waivers of one point are not stale).
  const UserWaiver* waiver_of(const std::string& key) {
    const std::string path = field(key, "f");
    std::optional<std::vector<int>> lines;
    const UserWaiver* first = nullptr;
    for (std::size_t i = 0; i < waivers_.size(); ++i) {
      Compiled& c = waivers_[i];
      if (!names_file(path, c.w.file)) continue;
      c.files.insert(path);
      if (!lines) lines = point_lines(key);
      bool on = false;
      if (c.pattern || !c.marker.empty()) {
        const std::set<int>& match = lines_of(i, path);
        // phongsim's markers leave out statements only: an if's implicit else lies on the if's
        // line, where a one-line `if (...) x = y;` carries the marker of its unreachable arm.
        on = (c.marker.empty() || !field(key, "S").empty()) &&
             std::any_of(lines->begin(), lines->end(), [&](int l) { return match.contains(l); });
      } else if (c.w.first_line > 0) {
        on = std::any_of(lines->begin(), lines->end(),
                         [&](int l) { return l >= c.w.first_line && l <= c.w.last_line; });
      } else {
        on = true;
      }
      if (!on) continue;
      c.on_lines = true;
      if (c.instance && !std::regex_search(field(key, "h"), *c.instance)) continue;
      ++c.points;
      if (first == nullptr) first = &c.w;
    }
    return first;
  }

  // Error for the first of the user's waivers that left out no point, saying why. (phongsim's
  // own need not match: a configuration waives each arm its formats rule out, and a module
  // Verilator made one of for several instances has its points under a shared name.)
  void check_used() const {
    for (const Compiled& c : waivers_) {
      if (c.points > 0 || !c.marker.empty()) continue;
      const UserWaiver& w = c.w;
      std::string why;
      if (c.files.empty()) {
        why = fmt::format("no line or branch point is in a source file {}", w.file);
      } else if (c.pattern && !c.pattern_matched_line) {
        why = fmt::format("/{}/ matches no line of {}", w.pattern, *c.files.begin());
      } else if (!c.on_lines) {
        why = fmt::format(
            "no line or branch point lies on {} (a waiver leaves out those, not "
            "a signal's toggles)",
            w.where());
      } else {
        why = fmt::format("no instance matching @{} has a point on those lines", w.instance);
      }
      throw Error(fmt::format(
          "{}: the waiver '{}' matches no coverage point ({}; a stale waiver would waive "
          "other code: fix or remove it)",
          w.origin, w.where(), why));
    }
  }

 private:
  // The lines of `path` waiver i's pattern or marker names (the file read once).
  const std::set<int>& lines_of(std::size_t i, const std::string& path) {
    const auto k = std::make_pair(i, path);
    if (const auto it = lines_.find(k); it != lines_.end()) return it->second;
    Compiled& c = waivers_[i];
    auto text = sources_.find(path);
    if (text == sources_.end()) {
      std::error_code ec;
      if (!fs::is_regular_file(path, ec)) {
        throw Error(c.marker.empty()
                        ? fmt::format("{}: cannot read {} to match /{}/ in it", c.w.origin, path,
                                      c.w.pattern)
                        : fmt::format("cannot read {} to find phongsim's waiver marker '{}' in it",
                                      path, c.marker));
      }
      std::vector<std::string> lines;
      std::istringstream in(read_file(path, "source file"));
      for (std::string line; std::getline(in, line);) lines.push_back(std::move(line));
      text = sources_.emplace(path, std::move(lines)).first;
    }
    std::set<int>& lines = lines_[k];
    if (!c.marker.empty()) {
      lines = marked_lines(text->second, path, c.marker);
      return lines;
    }
    for (std::size_t n = 0; n < text->second.size(); ++n) {
      if (std::regex_search(text->second[n], *c.pattern)) lines.insert(int(n) + 1);
    }
    if (!lines.empty()) c.pattern_matched_line = true;
    return lines;
  }

  std::vector<Compiled> waivers_;
  std::map<std::string, std::vector<std::string>> sources_;             // path -> lines
  std::map<std::pair<std::size_t, std::string>, std::set<int>> lines_;  // (waiver, path)
};

// Whether `text` matches the glob `pattern` ('*': any characters), as Verilator names the
// instances of a module it made one of ("top.t.u_sub*").
bool glob_match(std::string_view pattern, std::string_view text) {
  std::size_t p = 0, t = 0, star = std::string_view::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && pattern[p] == '*') {
      star = p++;
      mark = t;
    } else if (p < pattern.size() && pattern[p] == text[t]) {
      ++p;
      ++t;
    } else if (star != std::string_view::npos) {
      p = star + 1;
      t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

// A signal's name up to its first index or member ("arr_q" of "arr_q[2]", "st_q" of "st_q.a[0]").
std::string base_name(const std::string& name) { return name.substr(0, name.find_first_of("[.")); }

// The design's signals without toggle points: the waveform's variables (the top's ports seen
// from outside, at the root, and parameters left out; an unpacked array's elements as one)
// whose name no toggle point of a matching instance has. A scope is a module's instance when
// it has a port or a counted signal; else it is a generate or named block, whose signals
// Verilator 5.006 counts no toggles of.
std::vector<UncountedSignal> uncounted_signals(const std::map<std::string, std::uint64_t>& points,
                                               std::span<const WaveSignal> signals) {
  constexpr std::uint64_t kToggleLimit = 256;            // Verilator's --coverage-max-width default
  std::map<std::string, std::set<std::string>> toggled;  // signal base name -> instance globs
  for (const auto& [key, count] : points) {
    if (is_toggle(key)) toggled[base_name(field(key, "o"))].insert(field(key, "h"));
  }
  struct Found {
    std::string scope, base, type;
    std::uint64_t bits = 0;
    bool array = false;
    bool counted = false;
  };
  std::vector<Found> found;
  std::map<std::string, std::size_t> index;  // path -> found
  std::set<std::string> instances;           // scopes with a port or a counted signal
  for (const WaveSignal& s : signals) {
    if (s.type == "parameter" || s.type == "real_parameter") continue;
    if (s.scope.find('.') == std::string::npos) continue;  // the root: the top's ports, annotations
    if (s.port) instances.insert(s.scope);
    const std::string base = s.name.substr(0, s.name.find('['));
    const std::string path = s.scope + "." + base;
    if (const auto it = index.find(path); it != index.end()) {
      Found& f = found[it->second];
      if (s.name != base) {  // another element of the array
        f.bits += s.bits;
        f.array = true;
      }
      continue;
    }
    index[path] = found.size();
    Found f{s.scope, base, s.type, s.bits, s.name != base, false};
    if (const auto it = toggled.find(base); it != toggled.end()) {
      f.counted = std::any_of(it->second.begin(), it->second.end(),
                              [&](const std::string& h) { return glob_match(h, s.scope); });
    }
    if (f.counted) instances.insert(s.scope);
    found.push_back(std::move(f));
  }
  std::vector<UncountedSignal> out;
  for (const Found& f : found) {
    if (f.counted) continue;
    std::string why;
    static const std::set<std::string> kNumbers = {"integer", "int",  "longint", "shortint",
                                                   "byte",    "time", "string",  "event"};
    std::uint64_t bits = f.bits;
    if (f.type == "real" || f.type == "shortreal" || f.type == "realtime") {
      why = "real";
      bits = 64;  // an FST real's length is its bytes
    } else if (kNumbers.contains(f.type)) {
      why = f.type + ", not logic or bit";
    } else if (f.bits > kToggleLimit) {
      why = fmt::format("{} wider than the toggle limit of {} bits",
                        f.array ? "an unpacked array" : "a vector", kToggleLimit);
    } else if (!instances.contains(f.scope)) {
      why = "in a generate or named block";
    } else {
      why = "no toggle point (coverage_off?)";
    }
    out.push_back({f.scope + "." + f.base, bits, why});
  }
  return out;
}

// The counting, and which points it left out (their keys), for lcov_info.
CoverageSummary count(const std::map<std::string, std::uint64_t>& points,
                      const CoverageInputs& inputs, std::set<std::string>* waived_keys) {
  CoverageSummary s;
  WaiverMatcher matcher(inputs.line_waivers, inputs.user_waivers);
  for (const auto& [key, count] : points) {
    if (is_toggle(key)) {
      ++s.toggle_points;
      s.toggle_hit += count > 0 ? 1 : 0;
      continue;
    }
    if (!is_line(key)) continue;
    std::string reason, waiver;
    bool waived = false;
    if (const UserWaiver* w = matcher.waiver_of(key)) {
      reason = w->reason;
      waiver = w->origin;  // "" for phongsim's own
      waived = true;
    }
    if (waived) {
      if (count > 0) {
        throw Error(fmt::format("{}{} line {} in {} is waived ({}) but was reached",
                                waiver.empty() ? "" : waiver + ": ", field(key, "f"),
                                field(key, "l"), field(key, "h"), reason));
      }
      ++s.line_waived;
      const std::string span = field(key, "S");
      s.waived.push_back({field(key, "f"), span.empty() ? field(key, "l") : span, field(key, "h"),
                          reason, waiver});
      if (waived_keys != nullptr) waived_keys->insert(key);
      continue;
    }
    ++s.line_points;
    s.line_hit += count > 0 ? 1 : 0;
  }
  matcher.check_used();
  if (!inputs.signals.empty() && s.toggles_measured()) {
    s.signals_checked = true;
    s.not_toggled = uncounted_signals(points, inputs.signals);
  }
  return s;
}

std::string lcov_of(const std::map<std::string, std::uint64_t>& points,
                    const std::set<std::string>& waived) {
  struct Source {
    std::map<int, std::uint64_t> lines;  // DA: the smallest count of the points on a line
    std::map<int, std::vector<std::uint64_t>> branches;                          // BRDA, per line
    std::vector<std::pair<int, std::pair<std::string, std::uint64_t>>> toggles;  // FN, FNDA
  };
  std::map<std::string, Source> sources;
  for (const auto& [key, count] : points) {
    if (waived.contains(key)) continue;
    const std::string file = field(key, "f");
    const int l = line_number(field(key, "l")).value_or(0);
    if (file.empty() || l == 0) continue;
    if (is_toggle(key)) {
      sources[file].toggles.push_back({l, {field(key, "h") + "." + field(key, "o"), count}});
    } else if (is_line(key)) {
      Source& s = sources[file];
      s.branches[l].push_back(count);
      for (const int line : point_lines(key)) {
        const auto [it, fresh] = s.lines.try_emplace(line, count);
        if (!fresh) it->second = std::min(it->second, count);
      }
    }
  }
  std::string out = "TN:phongsim\n";
  for (const auto& [file, s] : sources) {
    out += fmt::format("SF:{}\n", file);
    std::uint64_t hit = 0;
    for (const auto& [l, t] : s.toggles) out += fmt::format("FN:{},{}\n", l, t.first);
    for (const auto& [l, t] : s.toggles) {
      out += fmt::format("FNDA:{},{}\n", t.second, t.first);
      hit += t.second > 0 ? 1 : 0;
    }
    out += fmt::format("FNF:{}\nFNH:{}\n", s.toggles.size(), hit);
    std::uint64_t branches = 0;
    hit = 0;
    for (const auto& [l, counts] : s.branches) {
      for (std::size_t i = 0; i < counts.size(); ++i) {
        out += fmt::format("BRDA:{},0,{},{}\n", l, i, counts[i]);
        ++branches;
        hit += counts[i] > 0 ? 1 : 0;
      }
    }
    out += fmt::format("BRF:{}\nBRH:{}\n", branches, hit);
    hit = 0;
    for (const auto& [l, c] : s.lines) {
      out += fmt::format("DA:{},{}\n", l, c);
      hit += c > 0 ? 1 : 0;
    }
    out += fmt::format("LF:{}\nLH:{}\nend_of_record\n", s.lines.size(), hit);
  }
  return out;
}

std::string first_lines(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  return s.empty() ? "no output" : s;
}

}  // namespace

DesignProbe probe_design(const std::function<DutPtr(const std::string&)>& make) {
  const TempDir dir("probe");
  const fs::path fst = dir.path() / "signals.fst";
  {
    const DutPtr dut = make((dir.path() / "probe-").string());
    dut->open_trace(fst.string());
    dut->reset();
    dut->settle();
    dut->close_trace();
  }  // its counts written
  DesignProbe p;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir.path(), ec)) {
    if (e.path().extension() == ".dat") read_points(e.path(), p.points);
  }
  p.signals = waveform_signals(fst);
  return p;
}

std::map<std::string, std::string> moved_sources(const RtlPlugin& plugin, const RtlDesign& design) {
  std::map<std::string, std::string> moved;
  std::istringstream in(read_file(plugin.path.parent_path() / "info.txt"));
  std::vector<fs::path> now;  // the design's files now, as Verilator is given them
  for (const fs::path& f : design.files) now.push_back(fs::absolute(f).lexically_normal());
  std::map<fs::path, std::string> hashes;  // of the files now, as needed
  const auto hash_of = [&](const fs::path& f) -> const std::string& {
    auto it = hashes.find(f);
    if (it == hashes.end()) {
      std::error_code ec;
      it = hashes.emplace(f, fs::is_regular_file(f, ec) ? file_hash(f) : "").first;
    }
    return it->second;
  };
  std::map<int, fs::path> incdirs;  // the record's include folders
  std::vector<IncludedFile> includes;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string kind, hash;
    words >> kind;
    if (kind == "file") {
      words >> hash;
      std::string path;
      std::getline(words, path);
      const fs::path old = fs::path(std::string(trim(path))).lexically_normal();
      if (std::find(now.begin(), now.end(), old) != now.end()) continue;
      for (const fs::path& f : now) {
        if (hash_of(f) == hash) {
          moved[old.string()] = f.string();
          break;
        }
      }
    } else if (kind == "incdir") {
      int i = 0;
      std::string dir;
      words >> i;
      std::getline(words, dir);
      incdirs[i] = std::string(trim(dir));
    } else if (kind == "include") {
      IncludedFile inc;
      std::string rel;
      words >> inc.hash >> inc.dir;
      std::getline(words, rel);
      inc.rel = std::string(trim(rel));
      if (!words.fail() || words.eof()) includes.push_back(inc);
    }
  }
  const std::vector<fs::path> dirs = rtl_include_dirs(design.include_dirs, design.files);
  for (const IncludedFile& inc : includes) {
    if (inc.dir < 0 || !incdirs.contains(inc.dir)) continue;
    const fs::path old = (incdirs[inc.dir] / inc.rel).lexically_normal();
    const auto found = resolve_include(inc, dirs);
    if (!found) continue;
    const fs::path f = found->lexically_normal();
    if (f != old && hash_of(f) == inc.hash) moved[old.string()] = f.string();
  }
  return moved;
}

std::map<std::string, std::uint64_t> relocated(const std::map<std::string, std::uint64_t>& points,
                                               const std::map<std::string, std::string>& moved) {
  if (moved.empty()) return points;
  std::map<std::string, std::uint64_t> out;
  for (const auto& [key, count] : points) {
    const std::string f = field(key, "f");
    const auto it = moved.find(fs::path(f).lexically_normal().string());
    if (it == moved.end()) {
      out[key] += count;
      continue;
    }
    const std::string mark =
        "\x01"
        "f\x02" +
        f;
    std::string k = key;
    if (const auto at = k.find(mark); at != std::string::npos) {
      k.replace(at, mark.size(),
                std::string("\x01"
                            "f\x02") +
                    it->second);
    }
    out[k] += count;
  }
  return out;
}

void check_waivers(const std::map<std::string, std::uint64_t>& points,
                   std::span<const UserWaiver> waivers) {
  WaiverMatcher matcher({}, waivers);
  for (const auto& [key, count] : points) {
    if (is_line(key)) (void)matcher.waiver_of(key);
  }
  matcher.check_used();
}

CoverageSummary count_coverage_points(const std::map<std::string, std::uint64_t>& points,
                                      const CoverageInputs& inputs) {
  return count(points, inputs, nullptr);
}

CoverageSummary count_coverage_points(const std::map<std::string, std::uint64_t>& points,
                                      std::span<const LineWaiver> waivers) {
  CoverageInputs inputs;
  inputs.line_waivers.assign(waivers.begin(), waivers.end());
  return count(points, inputs, nullptr);
}

std::string lcov_info(const std::map<std::string, std::uint64_t>& points,
                      const CoverageInputs& inputs) {
  std::set<std::string> waived;
  (void)count(points, inputs, &waived);
  return lcov_of(points, waived);
}

CoverageSummary merge_coverage(const fs::path& dir, const CoverageInputs& inputs) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "data", ec)) {
    if (e.path().extension() == ".dat") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw Error(fmt::format("{}: no coverage data", (dir / "data").string()));
  std::map<std::string, std::uint64_t> points;
  for (const auto& f : files) read_points(f, points);
  points = relocated(points, inputs.moved);
  std::set<std::string> waived;
  CoverageSummary s = count(points, inputs, &waived);
  s.files = files.size();
  const fs::path info = dir / "coverage.info";
  {
    std::ofstream out(info, std::ios::binary | std::ios::trunc);
    out << lcov_of(points, waived);
    if (!out) throw Error(fmt::format("cannot write {}", info.string()));
  }
  const fs::path html = dir / "html";
  fs::remove_all(html, ec);
  // The page's figures are the counted ones, named as lcov names them: the title says which.
  const std::string title =
      "phongsim RTL coverage. Branches: Verilator's line and branch points (phongsim's "
      "'lines' figure); Lines: the source lines of their statements; Functions: toggle "
      "points, one per signal bit (phongsim's 'toggles'); waived points left out";
  if (const ProcessResult r =
          run_process({"genhtml", "--quiet", "--branch-coverage", "--function-coverage", "--title",
                       title, "--output-directory", html.string(), info.string()});
      r.exit_code != 0) {
    throw Error(
        fmt::format("genhtml failed (scripts/setup.sh installs lcov): {}", first_lines(r.out)));
  }
  return s;
}

CoverageSummary merge_coverage(const fs::path& dir, std::span<const LineWaiver> waivers) {
  CoverageInputs inputs;
  inputs.line_waivers.assign(waivers.begin(), waivers.end());
  return merge_coverage(dir, inputs);
}

}  // namespace phongsim
