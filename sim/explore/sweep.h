// Bit-width exploration (`phongsim sweep`): a sweep file names a base configuration (or several)
// and axes of [format]/[mode]/[param]/[setup] values; every point of the grid is written as a
// configuration file and evaluated: model error against the pipeline's float reference,
// optionally colour correctness and PSNR on scenes, real synthesis (sim/explore/synth.h), latency.
// Points are independent jobs (`plan` writes one command line each; `merge` collects them), and
// a greedy search finds the narrowest configuration within an error budget. docs/exploration.md.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/config.h"
#include "sim/explore/synth.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

struct SweepAxis {
  std::string key;                  // "format.vec", "param.k", "mode.round", "setup.policy"
  std::vector<std::string> values;  // TOML literals: "\"S1.8\"", "2"
};

struct SweepScene {
  std::string scene;   // built-in scene or scene file
  std::string method;  // a unit method of the swept pipeline (its unit becomes the point)
};

struct SweepSpec {
  std::filesystem::path file;
  std::string name;
  std::vector<std::filesystem::path> bases;
  std::vector<SweepAxis> axes;
  std::uint64_t samples = 20000;
  std::uint64_t seed = 1;
  std::vector<SweepScene> scenes;
  int scene_size = 32;  // render --size for the scenes
  SynthOptions synth{false, false};
  std::string variant;         // an axis key or "base": one Pareto curve per value ("": one curve)
  std::string area = "cells";  // x axis of the Pareto plot: cells, transistors or lut4
};

// Reads a sweep file; throws Error("<file>:<line>: ...") for unknown keys, empty or malformed
// axes, missing bases.
[[nodiscard]] SweepSpec load_sweep(const std::filesystem::path& file);

struct SweepPoint {
  std::size_t index = 0;
  std::filesystem::path base;
  std::vector<std::pair<std::string, std::string>> values;  // axis key -> literal
  std::string toml;                                         // the point's configuration
};

// Every point of the grid (bases × axes, first axis slowest), each validated by building its
// model: an axis key missing from a base, a value the pipeline rejects, intermediates that
// overflow the model's integers — Error naming the point, before any work.
[[nodiscard]] std::vector<SweepPoint> expand(const SweepSpec& spec);

struct PointResult {
  std::size_t index = 0;
  std::string config;  // the point's configuration file
  std::vector<std::pair<std::string, std::string>> values;
  std::string base;
  ModelError error;
  std::vector<std::pair<std::string, double>> colour_correctness;  // per scene
  std::vector<std::pair<std::string, double>> psnr;                // per scene
  SynthResult synth;
  bool synthesized = false;
  int latency = 0;
  double seconds = 0;
};

// Evaluates one point's configuration file (the sweep's error/scene/synthesis settings).
[[nodiscard]] PointResult evaluate_point(const SweepSpec& spec, const std::filesystem::path& config,
                                         std::size_t index, std::FILE* log);

// Writes <out>/points/NNNN.toml for every point, <out>/jobs.txt (one `phongsim sweep point` per
// line: `parallel < jobs.txt`, or line $SLURM_ARRAY_TASK_ID + 1 in a Slurm array job) and
// <out>/Makefile (`make -j`). Returns the points.
std::vector<SweepPoint> plan_sweep(const SweepSpec& spec, const std::filesystem::path& out);

// Result JSON of one point (written by `phongsim sweep point`, read by merge).
[[nodiscard]] std::string point_result_json(const PointResult& r);
void write_point_result(const PointResult& r, const std::filesystem::path& path);

// Collects <out>/results/*.json into <out>/sweep.csv and <out>/summary.md (the Pareto front
// marked) and, with synthesis, <out>/pareto.csv and pareto.png (scripts/plot.py pareto: max
// error against area, one series per variant, the front drawn and its points labelled).
// Error when a planned point has no result yet (naming it).
std::vector<PointResult> merge_sweep(const SweepSpec& spec, const std::filesystem::path& out);

// `run`: plan, evaluate every point in this process (progress on `progress`), merge.
std::vector<PointResult> run_sweep(const SweepSpec& spec, const std::filesystem::path& out,
                                   const std::function<void(std::size_t, std::size_t)>& progress,
                                   std::FILE* log);

// ---- Minimum-width search ----

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
[[nodiscard]] SearchResult search_min_width(const SearchSpec& spec,
                                            const std::function<void(std::string_view)>& note);

}  // namespace phongsim
