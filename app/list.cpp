// phongsim list: the pipelines and their named configurations.
#include <fmt/format.h>

#include "app/commands.h"
#include "base/paths.h"

namespace phongsim::cli {

void add_list(CLI::App& app, Action& action) {
  app.add_subcommand("list", "Pipelines and their named configurations")->callback([&action]() {
    action = []() {
      for (const auto& p : pipelines()) {
        fmt::print("{:<8} {}\n", p.name, p.summary);
        for (const auto& f : pipeline_configs(p)) {
          const Config cfg = Config::load(f);
          fmt::print("  {:<40} {}\n", f.lexically_relative(data_root()).string(),
                     cfg.description());
        }
      }
      return 0;
    };
  });
}

}  // namespace phongsim::cli
