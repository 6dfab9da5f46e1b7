// `phongsim study`: the seeds' claims over many random scenes (docs/results.md, "How often the
// claims hold"). Each scene is a built-in mesh under a random view, random point lights and a
// random material; it is rendered twice — full colour against float Phong, and Vlasic's protocol
// (specular term only, against Blinn) — and, for a closed mesh, its glancing variant (one light
// behind the object) once more for Lyon's glancing highlight; every claim that applies to it is
// judged from the colour correctness (eq. 6.1) of its methods. A claim's result is the fraction
// of scenes in which it holds, with a 95 % Wilson interval.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "base/output_file.h"

namespace phongsim {

struct StudyOptions {
  std::uint64_t scenes = 200;
  std::uint64_t seed = 1;
  int size = 160;     // image width of every scene
  unsigned jobs = 0;  // worker threads; 0: one per core
};

// One random scene: what it is made of, and per claim (in study_claims() order) whether it
// applies, whether it holds, and the metric difference the claim is about.
struct StudyScene {
  std::uint64_t index = 0;
  std::string mesh;
  double shininess = 0;
  int lights = 0;
  std::vector<bool> applies, holds;
  std::vector<double> difference;
  std::string file;  // the scene file (scenes/scene<index>.toml: `phongsim render --scene` it)
  // Its glancing variant (scenes/scene<index>-glancing.toml): the same scene lit from behind
  // (Lyon's glancing highlight); empty for the triangle.
  std::string glancing_file;
};

struct StudyClaim {
  std::string_view name;
  std::string_view statement;   // the seed's claim, one line
  std::string_view difference;  // what the metric difference measures ("> 0" when it holds)
};
[[nodiscard]] const std::vector<StudyClaim>& study_claims();

struct ClaimResult {
  std::uint64_t scenes = 0;  // where the claim applies
  std::uint64_t holds = 0;
  double fraction = 0, ci_low = 0, ci_high = 0;
};

struct StudyResult {
  std::vector<StudyScene> scenes;
  std::vector<ClaimResult> claims;  // study_claims() order
};

// The 95 % Wilson score interval of `holds` successes in `n` trials.
[[nodiscard]] std::pair<double, double> wilson_interval(std::uint64_t holds, std::uint64_t n);

// Renders and judges every scene (in parallel; the result does not depend on the number of
// jobs). `progress(done, total)` after each scene. Error (one line) on bad options.
[[nodiscard]] StudyResult run_study(
    const StudyOptions& o, const std::function<void(std::uint64_t, std::uint64_t)>& progress);

// study.csv (a row per scene), study.md (the claims table), study.png (the distribution of each
// claim's metric difference, scripts/plot.py study) and every scene's file, scenes/scene<i>.toml,
// into `set`; returns their names.
std::vector<std::filesystem::path> write_study_outputs(const StudyResult& r, OutputSet& set);

// The claims table (Markdown), as study.md holds it.
[[nodiscard]] std::string study_markdown(const StudyResult& r);

}  // namespace phongsim
