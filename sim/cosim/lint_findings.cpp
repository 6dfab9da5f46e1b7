#include "sim/cosim/lint_findings.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <system_error>
#include <vector>

namespace phongsim {
namespace {

namespace fs = std::filesystem;

// The number at the front of `text` (digits only), advancing `pos` past it.
std::optional<int> number_at(std::string_view text, std::size_t& pos) {
  int value = 0;
  const char* const begin = text.data() + pos;
  const auto [end, ec] = std::from_chars(begin, text.data() + text.size(), value);
  if (ec != std::errc() || end == begin || *begin == '-' || *begin == '+') return std::nullopt;
  pos += static_cast<std::size_t>(end - begin);
  return value;
}

struct Located {
  std::string file;
  int line = 0;
  std::optional<int> column;
  std::string_view message;
};

// "FILE:LINE:COL: message" or "FILE:LINE: message" (Verilator's manual, "Error And Warning
// Format"); FILE holds no ": ", so a message that only mentions a path has no location.
std::optional<Located> located(std::string_view body) {
  for (std::size_t colon = body.find(':'); colon != std::string_view::npos;
       colon = body.find(':', colon + 1)) {
    if (colon == 0) return std::nullopt;
    if (colon + 1 < body.size() && body[colon + 1] == ' ') return std::nullopt;
    std::size_t pos = colon + 1;
    const std::optional<int> line = number_at(body, pos);
    if (!line || pos >= body.size() || body[pos] != ':') continue;
    ++pos;
    std::optional<int> column;
    if (pos < body.size() && body[pos] != ' ') {
      column = number_at(body, pos);
      if (!column || pos >= body.size() || body[pos] != ':') continue;
      ++pos;
    }
    if (pos >= body.size() || body[pos] != ' ') continue;
    return Located{std::string(body.substr(0, colon)), *line, column, body.substr(pos + 1)};
  }
  return std::nullopt;
}

std::optional<fs::path> under(const fs::path& path, const fs::path& dir) {
  const fs::path rel = path.lexically_normal().lexically_relative(dir.lexically_normal());
  if (rel.empty() || rel == "." || *rel.begin() == "..") return std::nullopt;
  return rel;
}

// `file` relative to `cwd` when it lies under it; else absolute (as given, or a relative path
// such as ../x.sv made absolute against `cwd`).
std::string shown(const std::string& file, const fs::path& cwd) {
  if (cwd.empty()) return file;
  const fs::path given(file);
  const fs::path path = given.is_absolute() ? given : (cwd / given).lexically_normal();
  if (const auto rel = under(path, cwd)) return rel->string();
  // Through symbolic links: the file's folder and the current one as they really are (the
  // file's own name kept: a link there is the name the user gave).
  std::error_code ec1;
  std::error_code ec2;
  const fs::path folder = fs::weakly_canonical(path.parent_path(), ec1);
  const fs::path here = fs::weakly_canonical(cwd, ec2);
  if (!ec1 && !ec2) {
    if (const auto rel = under(folder / path.filename(), here)) return rel->string();
  }
  return given.is_absolute() ? file : path.string();
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t'))
    s.remove_suffix(1);
  return s;
}

bool rule_word(std::string_view code) {
  if (code.empty()) return false;
  for (const char c : code) {
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  }
  return true;
}

// GitHub's escapes (actions/toolkit, command.ts): escapeData for the message, escapeProperty
// for a property's value.
std::string escape_data(std::string_view s) {
  std::string out;
  for (const char c : s) {
    if (c == '%') {
      out += "%25";
    } else if (c == '\r') {
      out += "%0D";
    } else if (c == '\n') {
      out += "%0A";
    } else {
      out += c;
    }
  }
  return out;
}

std::string escape_property(std::string_view s) {
  std::string out;
  for (const char c : escape_data(s)) {
    if (c == ':') {
      out += "%3A";
    } else if (c == ',') {
      out += "%2C";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

std::string_view severity_name(LintSeverity severity) {
  return severity == LintSeverity::warning ? "warning" : "error";
}

std::vector<LintFinding> parse_lint_findings(std::string_view output, const fs::path& cwd) {
  std::vector<LintFinding> findings;
  while (!output.empty()) {
    const std::size_t eol = output.find('\n');
    const std::string_view text = trimmed(output.substr(0, eol));
    output.remove_prefix(eol == std::string_view::npos ? output.size() : eol + 1);
    // A finding's first line: %Warning[-CODE]: ... or %Error[-CODE]: ...; every other line
    // (source excerpt, "... In instance", notes, hints, "Looked in:" lists) belongs to the one
    // above it.
    LintFinding f;
    std::string_view rest;
    if (text.starts_with("%Warning")) {
      f.severity = LintSeverity::warning;
      rest = text.substr(8);
    } else if (text.starts_with("%Error")) {
      f.severity = LintSeverity::error;
      rest = text.substr(6);
    } else {
      continue;
    }
    if (rest.starts_with("-")) {
      const std::size_t colon = rest.find(':');
      if (colon == std::string_view::npos || !rule_word(rest.substr(1, colon - 1))) continue;
      f.rule = std::string(rest.substr(1, colon - 1));
      rest.remove_prefix(colon);
    }
    if (!rest.starts_with(": ")) continue;
    std::string_view body = rest.substr(2);
    if (!f.rule && (body.starts_with("Exiting due to ") || body == "Cannot continue")) continue;
    // "%Error: Internal Error: FILE:LINE:COL: ../V3Foo.h:124: message": the location is the
    // design's.
    std::string_view lead;
    if (body.starts_with("Internal Error: ")) {
      lead = body.substr(0, 16);
      body.remove_prefix(16);
    }
    if (const std::optional<Located> at = located(body)) {
      f.file = shown(at->file, cwd);
      f.line = at->line;
      f.column = at->column;
      f.message = std::string(lead) + std::string(at->message);
    } else {
      f.message = std::string(lead) + std::string(body);
    }
    findings.push_back(std::move(f));
  }
  return findings;
}

std::string gcc_line(const LintFinding& f) {
  std::string where;
  if (f.file) {
    where = *f.file + ":";
    if (f.line) where += fmt::format("{}:", *f.line);
    if (f.line && f.column) where += fmt::format("{}:", *f.column);
    where += " ";
  }
  return fmt::format("{}{}: {}{}", where, severity_name(f.severity), f.message,
                     f.rule ? fmt::format(" [{}]", *f.rule) : "");
}

std::string github_line(const LintFinding& f) {
  std::vector<std::string> properties;
  if (f.file) {
    properties.push_back("file=" + escape_property(*f.file));
    if (f.line) properties.push_back(fmt::format("line={}", *f.line));
    if (f.line && f.column) properties.push_back(fmt::format("col={}", *f.column));
  }
  if (f.rule) properties.push_back("title=" + escape_property(*f.rule));
  return fmt::format("::{}{}{}::{}", severity_name(f.severity), properties.empty() ? "" : " ",
                     fmt::join(properties, ","), escape_data(f.message));
}

}  // namespace phongsim
