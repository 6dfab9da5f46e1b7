#include "model/config.h"

#include <fmt/format.h>

#include <toml++/toml.h>
#include <algorithm>
#include <cctype>

#include "base/error.h"
#include "base/file_util.h"

namespace phongsim {
namespace {

constexpr std::string_view kTables[] = {"format", "mode", "param", "setup"};

int line_of(const toml::node& node) { return static_cast<int>(node.source().begin.line); }

}  // namespace

Config Config::load(const std::filesystem::path& path) {
  return parse(read_file(path, "configuration file"), path.string());
}

Config Config::parse(std::string_view text, const std::string& origin) {
  Config cfg;
  cfg.origin_ = origin;
  cfg.name_ = std::filesystem::path(origin).stem().string();

  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}: {}", origin, e.source().begin.line, e.description()));
  }

  for (const auto& [key, node] : root) {
    const std::string k(key.str());
    if (k == "pipeline" || k == "description") {
      const auto* s = node.as_string();
      if (s == nullptr) {
        throw Error(fmt::format("{}:{}: '{}' must be a string", origin, line_of(node), k));
      }
      (k == "pipeline" ? cfg.pipeline_ : cfg.description_) = s->get();
      continue;
    }
    if (std::find(std::begin(kTables), std::end(kTables), k) == std::end(kTables)) {
      throw Error(
          fmt::format("{}:{}: unknown top-level key '{}' (expected pipeline, description, "
                      "[format], [mode], [param], [setup])",
                      origin, line_of(node), k));
    }
    const auto* table = node.as_table();
    if (table == nullptr) {
      throw Error(fmt::format("{}:{}: '{}' must be a table ([{}])", origin, line_of(node), k, k));
    }
    auto& entries = cfg.tables_[k];
    for (const auto& [sub_key, value] : *table) {
      Entry e;
      e.line = line_of(value);
      if (const auto* s = value.as_string()) {
        e.text = s->get();
      } else if (const auto* i = value.as_integer()) {
        e.integer = i->get();
        e.is_integer = true;
        e.text = std::to_string(e.integer);
      } else {
        throw Error(fmt::format("{}:{}: [{}] {} must be a string or an integer", origin, e.line, k,
                                sub_key.str()));
      }
      entries.emplace(std::string(sub_key.str()), std::move(e));
    }
  }
  if (cfg.pipeline_.empty()) {
    throw Error(fmt::format("{}: missing 'pipeline = \"<name>\"' at the top", origin));
  }
  return cfg;
}

const Config::Entry& Config::entry(const std::string& table, const std::string& key) const {
  const auto t = tables_.find(table);
  const auto e = t == tables_.end() ? decltype(t->second.end()){} : t->second.find(key);
  if (t == tables_.end() || e == t->second.end()) {
    throw Error(fmt::format("{}: [{}] is missing '{}' (required by pipeline {})", origin_, table,
                            key, pipeline_));
  }
  used_.insert(table + "." + key);
  return e->second;
}

fx::Format Config::format(const std::string& key) const {
  const Entry& e = entry("format", key);
  try {
    return fx::Format::parse(e.text);
  } catch (const Error& err) {
    throw Error(fmt::format("{}:{}: [format] {}: {}", origin_, e.line, key, err.what()));
  }
}

fx::Round Config::round(const std::string& key) const {
  const Entry& e = entry("mode", key);
  try {
    return fx::parse_round(e.text);
  } catch (const Error& err) {
    throw Error(fmt::format("{}:{}: [mode] {}: {}", origin_, e.line, key, err.what()));
  }
}

fx::Overflow Config::overflow(const std::string& key) const {
  const Entry& e = entry("mode", key);
  try {
    return fx::parse_overflow(e.text);
  } catch (const Error& err) {
    throw Error(fmt::format("{}:{}: [mode] {}: {}", origin_, e.line, key, err.what()));
  }
}

std::int64_t Config::integer(const std::string& table, const std::string& key, std::int64_t lo,
                             std::int64_t hi) const {
  const Entry& e = entry(table, key);
  if (!e.is_integer || e.integer < lo || e.integer > hi) {
    throw Error(fmt::format("{}:{}: [{}] {} = {} must be an integer in [{}, {}]", origin_, e.line,
                            table, key, e.text, lo, hi));
  }
  return e.integer;
}

std::int64_t Config::param(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  return integer("param", key, lo, hi);
}

std::int64_t Config::setup_integer(const std::string& key, std::int64_t lo, std::int64_t hi) const {
  return integer("setup", key, lo, hi);
}

std::string Config::setup(const std::string& key,
                          std::initializer_list<std::string_view> allowed) const {
  const Entry& e = entry("setup", key);
  for (const auto a : allowed) {
    if (e.text == a) return e.text;
  }
  std::string list;
  for (const auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
  throw Error(fmt::format("{}:{}: [setup] {} = '{}' (expected one of: {})", origin_, e.line, key,
                          e.text, list));
}

void Config::check_all_used() const {
  const Entry* first = nullptr;  // the unknown key that comes first in the file
  std::string where;
  for (const auto& [table, entries] : tables_) {
    for (const auto& [key, e] : entries) {
      if (used_.count(table + "." + key) == 0 && (first == nullptr || e.line < first->line)) {
        first = &e;
        where = fmt::format("[{}] {}", table, key);
      }
    }
  }
  if (first != nullptr) {
    throw Error(fmt::format("{}:{}: {}: unknown key for pipeline {}", origin_, first->line, where,
                            pipeline_));
  }
}

namespace {

std::string upper_camel(std::string_view key) {
  std::string out;
  bool up = true;
  for (const char c : key) {
    if (c == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  return out;
}

}  // namespace

std::vector<RtlParam> Config::rtl_parameters() const {
  std::vector<RtlParam> params;
  const auto table = [&](const char* name) -> const std::map<std::string, Entry>& {
    static const std::map<std::string, Entry> empty;
    const auto t = tables_.find(name);
    return t == tables_.end() ? empty : t->second;
  };
  for (const auto& [key, e] : table("format")) {
    fx::Format f;
    try {
      f = fx::Format::parse(e.text);
    } catch (const Error& err) {
      throw Error(fmt::format("{}:{}: [format] {}: {}", origin_, e.line, key, err.what()));
    }
    params.push_back({upper_camel(key) + "Fmt", format_word(f),
                      fmt::format("[format] {} = {} (format word: signed·65536 + int·256 + frac)",
                                  key, f.str())});
  }
  for (const auto& [key, e] : table("mode")) {
    std::int64_t code = 0;
    try {
      code = static_cast<std::int64_t>(fx::parse_round(e.text));
    } catch (const Error&) {
      try {
        code = static_cast<std::int64_t>(fx::parse_overflow(e.text));
      } catch (const Error&) {
        throw Error(
            fmt::format("{}:{}: [mode] {}: unknown mode '{}'", origin_, e.line, key, e.text));
      }
    }
    params.push_back(
        {upper_camel(key), code, fmt::format("[mode] {} = {} (encoding {})", key, e.text, code)});
  }
  for (const auto& [key, e] : table("param")) {
    if (!e.is_integer) {
      throw Error(
          fmt::format("{}:{}: [param] {}: '{}' is not an integer", origin_, e.line, key, e.text));
    }
    params.push_back({upper_camel(key), e.integer, fmt::format("[param] {} = {}", key, e.integer)});
  }
  return params;
}

void Config::fail(const std::string& message) const {
  throw Error(fmt::format("{}: {}", origin_, message));
}

}  // namespace phongsim
