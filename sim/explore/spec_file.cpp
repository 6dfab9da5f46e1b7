#include "sim/explore/spec_file.h"

#include <fmt/format.h>

#include <sstream>

#include "base/error.h"
#include "base/file_util.h"
#include "base/output_file.h"
#include "base/paths.h"
#include "sim/render/render.h"

namespace phongsim::explore {
namespace fs = std::filesystem;

void fail_at(const fs::path& file, const toml::node& n, const std::string& what) {
  throw Error(fmt::format("{}:{}: {}", file.string(), n.source().begin.line, what));
}

toml::table parse_toml(const fs::path& file) {
  const std::string text = read_file(file, "file");
  try {
    return toml::parse(text, file.string());
  } catch (const toml::parse_error& e) {
    throw Error(fmt::format("{}:{}: {}", file.string(), e.source().begin.line, e.description()));
  }
}

fs::path resolve_path(const fs::path& file, const std::string& p) {
  const fs::path near = file.parent_path() / p;
  if (fs::exists(near)) return near;
  const fs::path tree = data_root() / p;
  if (fs::exists(tree)) return tree;
  throw Error(fmt::format("{}: {} does not exist (looked next to the file and in the source tree)",
                          file.string(), p));
}

std::string point_toml(const fs::path& base,
                       const std::vector<std::pair<std::string, std::string>>& values,
                       const std::string& header, const std::string& description) {
  toml::table t = parse_toml(base);
  if (!description.empty()) t.insert_or_assign("description", description);
  for (const auto& [key, value] : values) {
    const auto dot = key.find('.');
    const std::string section = key.substr(0, dot);
    const std::string name = key.substr(dot + 1);
    auto* table = t[section].as_table();
    if (table == nullptr || !table->contains(name)) {
      throw Error(fmt::format("{}: has no [{}] {} to sweep", base.string(), section, name));
    }
    const toml::table v = toml::parse("v = " + value);
    table->insert_or_assign(name, *v.get("v"));
  }
  std::ostringstream s;
  s << header << t << "\n";
  return s.str();
}

ImageMetrics scene_metrics(const std::string& scene, const std::string& method, int size,
                           const fs::path& config) {
  RenderOptions o;
  o.scene = scene;
  o.methods = {method};
  o.backend = Backend::model;
  o.size = size;
  o.unit_config = config.string();
  return render(o, [](std::string_view, std::uint64_t, std::uint64_t) {}).results.front().metrics;
}

void write_text(const fs::path& path, const std::string& text) {
  OutputFile f(path);
  std::fputs(text.c_str(), f.get());
  f.commit();
}

}  // namespace phongsim::explore
