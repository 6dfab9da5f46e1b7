// phongsim list: the pipelines and their named configurations.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "base/paths.h"

namespace phongsim::cli {

void add_list(CLI::App& app, Action& action) {
  auto json_path = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("list", "Pipelines and their named configurations");
  cmd->add_option("--json", *json_path,
                  "also write the list as JSON (docs/json.md; - is standard output)");
  cmd->callback([json_path, &action]() {
    action = [json_path]() {
      JsonOutput json(*json_path);
      nlohmann::ordered_json j = json_document("list");
      j["pipelines"] = nlohmann::ordered_json::array();
      for (const auto& p : pipelines()) {
        fmt::print(json.text(), "{:<8} {}\n", p.name, p.summary);
        nlohmann::ordered_json configs = nlohmann::ordered_json::array();
        for (const auto& f : pipeline_configs(p)) {
          const Config cfg = Config::load(f);
          const std::string relative = f.lexically_relative(data_root()).string();
          fmt::print(json.text(), "  {:<40} {}\n", relative, cfg.description());
          configs.push_back(
              {{"name", cfg.name()}, {"path", relative}, {"description", cfg.description()}});
        }
        j["pipelines"].push_back({{"name", p.name}, {"summary", p.summary}, {"configs", configs}});
      }
      json.write(j);
      return 0;
    };
  });
}

}  // namespace phongsim::cli
