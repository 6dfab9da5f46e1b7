// phongsim study: the seeds' claims measured over many random scenes (sim/render/study.h):
// the fraction of scenes in which each holds, with its 95 % interval.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "sim/render/study.h"

namespace phongsim::cli {
namespace {

struct StudyCli {
  StudyOptions options;
  std::uint64_t jobs = 0;
  std::string out = "study";
  std::string json;
  bool quiet = false;
};

int run(StudyCli c) {
  if (quick_mode()) {  // PHONGSIM_QUICK: a few small scenes (docs/cosim.md)
    c.options.scenes = std::min<std::uint64_t>(c.options.scenes, 4);
    c.options.size = std::min(c.options.size, 64);
  }
  c.options.jobs = static_cast<unsigned>(c.jobs);
  check_distinct({{"--json", c.json}});
  OutputSet set(c.out, "study", {"study"});
  std::optional<JsonOutput> json;
  const std::optional<std::filesystem::path> json_in_set =
      c.json.empty() || c.json == "-" ? std::nullopt : inside(c.json, c.out);
  if (!json_in_set) json.emplace(c.json);
  std::FILE* const text = json && json->to_stdout() ? stderr : stdout;
  const Progress line = progress_line(c.quiet);
  const StudyResult r = run_study(
      c.options, [&](std::uint64_t done, std::uint64_t all) { line("study: scenes", done, all); });
  const auto files = write_study_outputs(r, set);
  nlohmann::ordered_json j = json_document("study");
  j["scenes"] = c.options.scenes;
  j["seed"] = c.options.seed;
  j["size"] = c.options.size;
  j["out"] = c.out;
  j["files"] = nlohmann::ordered_json::array();
  for (const auto& f : files) j["files"].push_back((std::filesystem::path(c.out) / f).string());
  j["claims"] = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.claims.size(); ++k) {
    const StudyClaim& claim = study_claims()[k];
    const ClaimResult& cr = r.claims[k];
    j["claims"].push_back({{"name", claim.name},
                           {"statement", claim.statement},
                           {"difference", claim.difference},
                           {"scenes", cr.scenes},
                           {"holds", cr.holds},
                           {"holds_fraction", cr.fraction},
                           {"ci_low", cr.ci_low},
                           {"ci_high", cr.ci_high}});
  }
  if (json_in_set) std::fputs((j.dump(2) + "\n").c_str(), set.add(*json_in_set).get());
  set.commit();
  if (json) json->write(j);
  fmt::print(text, "The seeds' claims over {} random scenes (seed {}, {} pixels wide)\n{}",
             c.options.scenes, c.options.seed, c.options.size, study_markdown(r));
  fmt::print(text, "wrote {} files to {}\n", files.size(), c.out);
  return 0;
}

}  // namespace

void add_study(CLI::App& app, Action& action) {
  auto c = std::make_shared<StudyCli>();
  auto* cmd = app.add_subcommand(
      "study",
      "Measure the seeds' claims over many random scenes: the fraction of scenes in which each "
      "holds, with a 95 % interval (study.csv, study.md, study.png)");
  // At most 500: every scene writes up to two scene files, all held as temporaries until the
  // output set commits (base/temporaries.h: 1024 at once).
  add_count(*cmd, "--scenes", c->options.scenes, "random scenes (default 200, at most 500)", 500,
            1);
  add_count(*cmd, "--seed", c->options.seed, "seed of the scenes", UINT64_MAX);
  add_int(*cmd, "--size", c->options.size, "image width of each scene (default 160)", 16, 2048);
  add_count(*cmd, "--jobs", c->jobs, "worker threads (default 0: one per core)", 256);
  cmd->add_option("--out", c->out, "output directory (default: study)");
  cmd->add_option("--json", c->json,
                  "also write the results as JSON (docs/json.md; - is "
                  "standard output)");
  cmd->add_flag("--quiet", c->quiet, "no progress display");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
