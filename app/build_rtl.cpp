// phongsim build-rtl: Verilate a configuration's RTL (or every built-in configuration's) into the
// content-keyed plugin cache, and say where each plugin is.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/paths.h"

namespace phongsim::cli {
namespace {

struct BuildCli {
  Target target;
  bool all = false;
  std::string json;
};

int run(const BuildCli& c) {
  check_outputs({{"--json", c.json}}, c.target.inputs());
  JsonOutput json(c.json);
  std::vector<Loaded> loaded;
  std::vector<RtlDesign> designs;
  if (c.all) {
    if (!c.target.pipeline.empty() || !c.target.config.empty() || c.target.user_rtl()) {
      throw Error(
          "--all builds every configuration in configs/; give no pipeline, --config or --rtl");
    }
    for (const PipelineInfo& p : pipelines()) {
      for (const auto& file : pipeline_configs(p)) {
        Target t;
        t.config = file.string();
        loaded.push_back(load(t));
        designs.push_back(design_of(loaded.back(), t));
      }
    }
  } else {
    loaded.push_back(load(c.target));
    designs.push_back(design_of(loaded.back(), c.target));
  }
  std::vector<const PipelineModel*> models;
  for (const Loaded& l : loaded) models.push_back(l.model.get());
  // --no-build: build nothing; say where each plugin is, or refuse the first one not built.
  std::vector<RtlPlugin> plugins;
  if (c.target.no_build) {
    for (std::size_t i = 0; i < designs.size(); ++i) {
      plugins.push_back(locate_rtl(designs[i], *models[i], RtlBuild::never, stderr));
    }
  } else {
    plugins = build_rtl(designs, models, stderr);
  }
  nlohmann::ordered_json j = json_document("build-rtl");
  j["plugins"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < plugins.size(); ++i) {
    (void)RtlLibrary::open(plugins[i])->create(*loaded[i].model);  // loads and binds
    fmt::print(json.text(), "{} ({}): {}\n", loaded[i].cfg.origin(), plugins[i].origin,
               plugins[i].path.string());
    j["plugins"].push_back({{"config_path", loaded[i].cfg.origin()},
                            {"pipeline", loaded[i].pipeline->name},
                            {"key", plugins[i].key},
                            {"origin", plugins[i].origin},
                            {"path", plugins[i].path.string()}});
  }
  json.write(j);
  return 0;
}

}  // namespace

void add_build_rtl(CLI::App& app, Action& action) {
  auto c = std::make_shared<BuildCli>();
  auto* cmd = app.add_subcommand(
      "build-rtl",
      "Verilate a configuration's RTL into the plugin cache (keyed by content: nothing is "
      "rebuilt that did not change), or every built-in configuration's with --all; with "
      "--no-build, only check that it is built");
  c->target.add_options(*cmd);
  cmd->add_flag("--all", c->all, "every configuration in configs/, in one parallel build");
  cmd->add_option("--json", c->json,
                  "also write the plugins as JSON (docs/json.md; - is standard output)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
