// The minimum-width search (`phongsim sweep search`, docs/exploration.md): narrows the fraction
// bits of named [format] signals of a base configuration while the model's error against the
// pipeline's float reference (and optionally colour correctness on a scene) stays within a
// budget.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sim/pipelines/registry.h"

namespace phongsim {

// Bounds checked when a search file is read (one line with the number and the limit).
inline constexpr std::uint64_t kMaxSearchSamples = 10'000'000;
inline constexpr std::uint64_t kMaxVerifyVectors = 1'000'000'000;
inline constexpr std::size_t kMaxSearchSignals = 32;

struct SearchSpec {
  std::filesystem::path file;
  std::string name;
  std::filesystem::path base;
  std::vector<std::string> signals;  // [format] keys whose fraction bits the search reduces
  int min_frac = 1;
  // Budgets (at least one): model_error().max_lsb <= max_lsb, and colour correctness against
  // float Phong >= min_colour_correctness on `scene` rendered by `method` (a unit method of the
  // base's pipeline) through the candidate, model backend, at `scene_size`.
  double max_lsb = INFINITY;
  double min_colour_correctness = 0;
  std::string scene, method;
  int scene_size = 32;
  std::uint64_t samples = 20000;
  std::uint64_t seed = 1;
  std::uint64_t verify_vectors = 1000000;  // co-simulation of the result
};
[[nodiscard]] SearchSpec load_search(const std::filesystem::path& file);

struct SearchResult {
  std::string toml;  // the found configuration
  ModelError error;
  double colour_correctness = NAN;                           // with a colour-correctness budget
  std::vector<std::pair<std::string, std::string>> formats;  // signal -> found format
  int bits_saved = 0;                                        // fraction bits removed in total
  std::size_t evaluations = 0;
};

// Greedy coordinate descent: for each signal in turn, remove fraction bits one at a time while
// the budget holds; repeat the pass until no signal can lose a bit. Throws Error when the base
// itself misses the budget.
// `note` gets each accepted step, `progress` (may be empty) the number of evaluations so far.
[[nodiscard]] SearchResult search_min_width(const SearchSpec& spec,
                                            const std::function<void(std::string_view)>& note,
                                            const std::function<void(std::size_t)>& progress = {});

}  // namespace phongsim
