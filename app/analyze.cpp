// phongsim analyze: a pipeline's accuracy analysis (its registry entry's report), as text and,
// with --json, as tables of values.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"

namespace phongsim::cli {
namespace {

struct AnalyzeCli {
  std::string pipeline;
  std::vector<std::string> configs;
  std::uint64_t samples = 100000;
  std::uint64_t seed = 1;
  std::string json;
};

nlohmann::ordered_json cell_json(const ReportCell& c) {
  return std::visit([](const auto& v) { return nlohmann::ordered_json(v); }, c);
}

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
  std::vector<std::pair<std::string, std::filesystem::path>> paths{{"--json", c.json}};
  for (const auto& f : c.configs) paths.emplace_back("--config", f);
  check_distinct(paths);
  JsonOutput json(c.json);
  const std::uint64_t samples = quick_cap(c.samples, 2000);
  AnalysisReport report(json.text());
  p.analyze(configs, samples, c.seed, report);
  nlohmann::ordered_json j = json_document("analyze");
  j["pipeline"] = p.name;
  j["samples"] = samples;
  j["seed"] = c.seed;
  j["configs"] = nlohmann::ordered_json::array();
  for (const Config& cfg : configs) {
    j["configs"].push_back({{"name", cfg.name()}, {"path", cfg.origin()}});
  }
  j["tables"] = nlohmann::ordered_json::array();
  for (const ReportTable& t : report.tables()) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const auto& r : t.rows) {
      nlohmann::ordered_json row = nlohmann::ordered_json::object();
      for (std::size_t i = 0; i < r.size() && i < t.columns.size(); ++i) {
        row[t.columns[i]] = cell_json(r[i]);
      }
      rows.push_back(std::move(row));
    }
    j["tables"].push_back({{"title", t.title}, {"columns", t.columns}, {"rows", rows}});
  }
  json.write(j);
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
  add_count(*cmd, "--samples", c->samples, "random samples per configuration", 1'000'000'000, 1);
  add_count(*cmd, "--seed", c->seed, "seed", UINT64_MAX);
  cmd->add_option("--json", c->json,
                  "also write the tables as JSON (docs/json.md; - is standard output)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
