// phongsim analyze: a pipeline's accuracy analysis (its registry entry's report).
#include <fmt/format.h>

#include "app/commands.h"
#include "base/error.h"

namespace phongsim::cli {
namespace {

struct AnalyzeCli {
  std::string pipeline;
  std::vector<std::string> configs;
  std::uint64_t samples = 100000;
  std::uint64_t seed = 1;
};

int run(const AnalyzeCli& c) {
  const PipelineInfo& p = find_pipeline(c.pipeline);
  std::vector<Config> configs;
  if (c.configs.empty()) {
    for (const auto& f : pipeline_configs(p)) configs.push_back(Config::load(f));
  } else {
    for (const auto& f : c.configs) configs.push_back(Config::load(f));
  }
  for (const Config& cfg : configs) (void)make_model(p, cfg);  // refuse other pipelines' files
  if (configs.empty()) throw Error(fmt::format("no configurations of {} to analyze", p.name));
  p.analyze(configs, c.samples, c.seed, stdout);
  return 0;
}

}  // namespace

void add_analyze(CLI::App& app, Action& action) {
  auto c = std::make_shared<AnalyzeCli>();
  auto* cmd = app.add_subcommand(
      "analyze", "Accuracy analysis of a pipeline: approximations and fixed-point error");
  cmd->add_option("pipeline", c->pipeline, "pipeline (phongsim list)")->required();
  cmd->add_option("--config", c->configs,
                  "configuration(s) to analyze (default: every one in configs/<pipeline>)");
  add_count(*cmd, "--samples", c->samples, "random samples per configuration", 1'000'000'000);
  add_count(*cmd, "--seed", c->seed, "seed", UINT64_MAX);
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
