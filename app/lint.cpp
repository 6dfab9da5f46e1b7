// phongsim lint: verilator --lint-only -Wall over a configuration's RTL with its parameters.
#include <fmt/format.h>

#include "app/commands.h"
#include "base/process.h"

namespace phongsim::cli {
namespace {

int run(const Target& t) {
  const Loaded l = load(t);
  const RtlDesign d = design_of(l, t);
  std::vector<std::string> argv{"verilator", "--lint-only", "-Wall", "--top-module", d.top};
  for (const RtlParam& p : d.params) argv.push_back(fmt::format("-G{}={}", p.name, p.value));
  for (const auto& f : d.files) argv.push_back(f.string());
  const ProcessResult r = run_process(argv);
  fmt::print("{}", r.out);
  if (r.exit_code != 0) {
    fmt::print("LINT FAIL {} ({}): verilator exit {}\n", l.cfg.origin(), d.top, r.exit_code);
    return 1;
  }
  fmt::print("lint clean: {} ({}, {} file{})\n", l.cfg.origin(), d.top, d.files.size(),
             d.files.size() == 1 ? "" : "s");
  return 0;
}

}  // namespace

void add_lint(CLI::App& app, Action& action) {
  auto t = std::make_shared<Target>();
  auto* cmd = app.add_subcommand(
      "lint", "verilator --lint-only -Wall over a configuration's RTL with its parameters");
  t->add_options(*cmd);
  cmd->callback([t, &action]() { action = [t]() { return run(*t); }; });
}

}  // namespace phongsim::cli
