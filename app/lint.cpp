// phongsim lint: verilator --lint-only -Wall over a configuration's RTL with its parameters; its
// findings as Verilator printed them, as GCC-style lines or as GitHub Actions annotations, and
// as JSON objects (sim/cosim/lint_findings.h).
#include <fmt/format.h>

#include <filesystem>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/process.h"
#include "sim/cosim/lint_findings.h"

namespace phongsim::cli {
namespace {

struct LintCli {
  Target target;
  std::string json;
  std::string format = "text";
  std::string fail_on = "warning";
};

template <typename T>
nlohmann::ordered_json or_null(const std::optional<T>& v) {
  return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json finding_json(const LintFinding& f) {
  nlohmann::ordered_json j;
  j["file"] = or_null(f.file);
  j["line"] = or_null(f.line);
  j["column"] = or_null(f.column);
  j["rule"] = or_null(f.rule);
  j["severity"] = severity_name(f.severity);
  j["message"] = f.message;
  return j;
}

std::string counted(std::size_t n, std::string_view what) {
  return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s");
}

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
  // No such top is not a finding of the design but a wrong command: one line, exit 2.
  if (const std::string missing = missing_top_problem(d, r.out); !missing.empty()) {
    throw Error(missing);
  }
  const std::vector<LintFinding> findings =
      parse_lint_findings(r.out, std::filesystem::current_path());
  std::size_t warnings = 0;
  for (const LintFinding& f : findings) warnings += f.severity == LintSeverity::warning ? 1 : 0;
  const std::size_t errors = findings.size() - warnings;
  const bool clean = r.exit_code == 0 && findings.empty();

  std::FILE* const out = json.text();
  if (c.format == "text") {
    fmt::print(out, "{}", r.out);
  } else {
    for (const LintFinding& f : findings) {
      fmt::print(out, "{}\n", c.format == "gcc" ? gcc_line(f) : github_line(f));
    }
  }
  nlohmann::ordered_json j = json_document("lint");
  j["pipeline"] = l.pipeline->name;
  j["config"] = l.cfg.name();
  j["config_path"] = l.cfg.origin();
  j["top"] = d.top;
  j["files"] = d.files.size();
  j["clean"] = clean;
  j["verilator_exit"] = r.exit_code;
  j["warnings"] = warnings;
  j["errors"] = errors;
  j["findings"] = nlohmann::ordered_json::array();
  for (const LintFinding& f : findings) j["findings"].push_back(finding_json(f));
  json.write(j);

  if (clean) {
    fmt::print(out, "lint clean: {} ({}, {} file{})\n", l.cfg.origin(), d.top, d.files.size(),
               d.files.size() == 1 ? "" : "s");
    return 0;
  }
  // Verilator failed and said nothing phongsim reads as a finding: a failure all the same.
  const bool fails = errors > 0 || (c.fail_on == "warning" && warnings > 0) ||
                     (r.exit_code != 0 && findings.empty());
  const std::string counts = fmt::format("{}, {} (verilator exit {})", counted(warnings, "warning"),
                                         counted(errors, "error"), r.exit_code);
  if (fails) {
    fmt::print(out, "LINT FAIL {} ({}): {}\n", l.cfg.origin(), d.top, counts);
    return 1;
  }
  fmt::print(out, "lint passed with warnings (--fail-on error): {} ({}): {}\n", l.cfg.origin(),
             d.top, counts);
  return 0;
}

}  // namespace

void add_lint(CLI::App& app, Action& action) {
  auto c = std::make_shared<LintCli>();
  auto* cmd = app.add_subcommand(
      "lint", "verilator --lint-only -Wall over a configuration's RTL with its parameters");
  // Lint reads sources: no plugin (--rtl-plugin, which would lint phongsim's RTL instead) and no
  // Verilation (--no-build).
  c->target.add_options(*cmd, false);
  c->target.add_source_options(*cmd);
  cmd->add_option("--json", c->json,
                  "also write the result as JSON, one object a finding (docs/json.md; - is "
                  "standard output)");
  add_choice(*cmd, "--format", c->format,
             "how findings are printed: text (Verilator's own words), gcc (one line a "
             "finding: file:line:col: severity: message [RULE]) or github (GitHub Actions "
             "::warning/::error annotations)",
             {"text", "gcc", "github"});
  add_choice(*cmd, "--fail-on", c->fail_on,
             "the least severe finding that fails the lint (exit 1): warning, or error "
             "(warnings are then printed and listed but exit 0)",
             {"warning", "error"});
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
