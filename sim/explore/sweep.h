// Bit-width exploration (`phongsim sweep`): a sweep file names a base configuration (or several)
// and axes of [format]/[mode]/[param]/[setup] values; every point of the grid is written as a
// configuration file and evaluated: model error against the pipeline's float reference,
// optionally colour correctness and PSNR on scenes, real synthesis (sim/explore/synth.h), latency.
// Points are independent jobs (`plan` writes one command line each; `merge` collects them).
// The minimum-width search is sim/explore/search.h. docs/exploration.md.
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
#include "sim/cosim/rtl_args.h"
#include "sim/explore/synth.h"
#include "sim/pipelines/registry.h"

namespace phongsim {

// Bounds checked when a sweep file is read, before any work (one line naming the number and the
// limit): values per axis, points in the grid, random samples per point.
inline constexpr std::size_t kMaxAxisValues = 256;
inline constexpr std::size_t kMaxSweepPoints = 10000;
inline constexpr std::uint64_t kMaxSweepSamples = 10'000'000;

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
  std::string config;       // the point's configuration file
  std::string config_hash;  // of its content (merge refuses a result of another version)
  std::vector<std::pair<std::string, std::string>> values;
  std::string base;
  ModelError error;
  std::vector<std::pair<std::string, double>> colour_correctness;  // per scene
  std::vector<std::pair<std::string, double>> psnr;                // per scene
  SynthResult synth;
  bool synthesized = false;
  int latency = 0;  // the built-in unit's, or the user's RTL's as measured
  double seconds = 0;
  // With the user's RTL (SweepRtl): which design, and its co-simulation at this point.
  std::string rtl;               // SweepRtl::Verdict::rtl; "" for phongsim's
  std::optional<bool> verified;  // passed or not; none without the user's RTL
  std::string verification;      // the co-simulation's summary line
};

// The user's RTL in a sweep (docs/exploration.md, "Your RTL in a sweep"): every point
// synthesizes it instead of phongsim's and co-simulates it with the point's configuration.
struct SweepRtl {
  RtlSources sources;
  std::string top;      // empty: the built-in top's name
  std::string options;  // the command-line words that name it again (for jobs.txt)
  struct Verdict {
    bool passed = false;
    std::string summary;  // the co-simulation's summary line
    std::string rtl;      // the design's identity, the same at every point (top, content hash)
    int latency = -1;     // measured (stall-free), cycles; -1: not measured
  };
  std::function<Verdict(const std::filesystem::path& config)> verify;
};

// Evaluates one point's configuration file (the sweep's error/scene/synthesis settings), with
// the user's RTL when `rtl` is given.
[[nodiscard]] PointResult evaluate_point(const SweepSpec& spec, const std::filesystem::path& config,
                                         std::size_t index, std::FILE* log,
                                         const SweepRtl* rtl = nullptr);

// Writes <out>/points/NNNN.toml for every point, <out>/jobs.txt (one `phongsim sweep point` per
// line: `parallel < jobs.txt`, or line $SLURM_ARRAY_TASK_ID + 1 in a Slurm array job) and
// <out>/Makefile (`make -j`), all or none (an OutputSet, "sweep plan": planning again replaces
// the plan and the merged tables), and makes <out>/results/. Returns the points.
// With `rtl`, each job names the user's RTL too (SweepRtl::options).
std::vector<SweepPoint> plan_sweep(const SweepSpec& spec, const std::filesystem::path& out,
                                   const SweepRtl* rtl = nullptr);

// The hash a point result keeps of its configuration's content.
[[nodiscard]] std::string content_hash(const std::string& text);

// Result JSON of one point (written by `phongsim sweep point`, read by merge).
[[nodiscard]] std::string point_result_json(const PointResult& r);
void write_point_result(const PointResult& r, const std::filesystem::path& path);

// Collects <out>/results/*.json into <out>/sweep.csv and <out>/summary.md (the Pareto front
// marked) and, with synthesis, <out>/pareto.csv and pareto.png (scripts/plot.py pareto: max
// error against area, one series per variant, the front drawn and its points labelled), all or
// none (an OutputSet, "sweep merge"). Error when a planned point has no result yet, or one
// computed from another version of its point, or results of different RTL (naming it).
// Results with the user's RTL carry its verdicts: summary.md has a column of them.
std::vector<PointResult> merge_sweep(const SweepSpec& spec, const std::filesystem::path& out);

// Whether the Pareto column of `r` (among `results`) is set: no other point has both less or
// equal area and less or equal max error, one of them less; NaN area (no synthesis): false.
[[nodiscard]] bool on_pareto_front(const SweepSpec& spec, const PointResult& r,
                                   const std::vector<PointResult>& results);

// `run`: plan, evaluate every point in this process (progress on `progress`), merge.
std::vector<PointResult> run_sweep(const SweepSpec& spec, const std::filesystem::path& out,
                                   const std::function<void(std::size_t, std::size_t)>& progress,
                                   std::FILE* log, const SweepRtl* rtl = nullptr);

// The points whose co-simulation of the user's RTL failed ("" when none): "3 of 12 points
// fail co-simulation: 0004, 0007, 0011".
[[nodiscard]] std::string failed_points(const std::vector<PointResult>& results);

}  // namespace phongsim
