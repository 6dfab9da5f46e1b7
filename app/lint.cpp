// phongsim lint: verilator --lint-only -Wall over a configuration's RTL with its parameters.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "base/process.h"

namespace phongsim::cli {
namespace {

struct LintCli {
  Target target;
  std::string json;
};

int run(const LintCli& c) {
  const Target& t = c.target;
  check_outputs({{"--json", c.json}}, t.inputs());
  JsonOutput json(c.json);
  const Loaded l = load(t);
  const RtlDesign d = design_of(l, t);
  std::vector<std::string> argv{"verilator", "--lint-only", "-Wall", "--top-module", d.top};
  for (const RtlParam& p : d.params) argv.push_back(fmt::format("-G{}={}", p.name, p.value));
  for (const std::string& f : rtl_source_flags(d)) argv.push_back(f);
  for (const auto& f : d.files) argv.push_back(f.string());
  const ProcessResult r = run_process(argv);
  std::FILE* const out = json.text();
  fmt::print(out, "{}", r.out);
  nlohmann::ordered_json j = json_document("lint");
  j["pipeline"] = l.pipeline->name;
  j["config"] = l.cfg.name();
  j["config_path"] = l.cfg.origin();
  j["top"] = d.top;
  j["files"] = d.files.size();
  j["clean"] = r.exit_code == 0;
  j["verilator_exit"] = r.exit_code;
  j["findings"] = r.out;
  json.write(j);
  if (r.exit_code != 0) {
    fmt::print(out, "LINT FAIL {} ({}): verilator exit {}\n", l.cfg.origin(), d.top, r.exit_code);
    return 1;
  }
  fmt::print(out, "lint clean: {} ({}, {} file{})\n", l.cfg.origin(), d.top, d.files.size(),
             d.files.size() == 1 ? "" : "s");
  return 0;
}

}  // namespace

void add_lint(CLI::App& app, Action& action) {
  auto c = std::make_shared<LintCli>();
  auto* cmd = app.add_subcommand(
      "lint", "verilator --lint-only -Wall over a configuration's RTL with its parameters");
  c->target.add_options(*cmd);
  cmd->add_option("--json", c->json,
                  "also write the result as JSON (docs/json.md; - is standard output)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
