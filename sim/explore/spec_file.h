// What sweep files and search files share (sim/explore/sweep.h, sim/explore/search.h): reading
// them (errors name the file and line), resolving the paths in them, a point's configuration (a
// base with some values replaced), scoring a configuration on a scene, and writing a text file.
// Internal to sim/explore.
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sim/render/image.h"

namespace phongsim::explore {

// Error("<file>:<line of n>: <what>").
[[noreturn]] void fail_at(const std::filesystem::path& file, const toml::node& n,
                          const std::string& what);

// The file parsed; a syntax error as Error("<file>:<line>: <what>").
[[nodiscard]] toml::table parse_toml(const std::filesystem::path& file);

// A path in a sweep or search file: relative to the file's directory, else to the source tree.
[[nodiscard]] std::filesystem::path resolve_path(const std::filesystem::path& file,
                                                 const std::string& p);

// The point's configuration: the base with the values ("format.p" -> "\"S1.9\"", TOML literals)
// replaced, `header` (comment lines) first, and `description` when not empty. Error when the
// base has no such key.
[[nodiscard]] std::string point_toml(const std::filesystem::path& base,
                                     const std::vector<std::pair<std::string, std::string>>& values,
                                     const std::string& header, const std::string& description);

// `method` on `scene` through the unit configuration `config` (model backend) against float
// Phong.
[[nodiscard]] ImageMetrics scene_metrics(const std::string& scene, const std::string& method,
                                         int size, const std::filesystem::path& config);

// Writes `text` to `path` (base/output_file.h: complete or absent).
void write_text(const std::filesystem::path& path, const std::string& text);

}  // namespace phongsim::explore
