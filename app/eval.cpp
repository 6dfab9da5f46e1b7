// phongsim eval and phongsim vectors: golden vectors as CSV, in and out.
#include <fmt/format.h>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"
#include "base/output_file.h"
#include "sim/cosim/eval.h"

namespace phongsim::cli {
namespace {

struct EvalCli {
  Target target;
  std::string backend = "model";
  std::string in;
  std::string out;
  std::string json;
  std::string stages;
  bool real = false;
};

int run_eval(const EvalCli& c) {
  std::vector<std::pair<std::string, std::filesystem::path>> inputs = c.target.inputs();
  inputs.emplace_back("--in", c.in);
  check_outputs({{"--out", c.out}, {"--json", c.json}, {"--stages", c.stages}}, inputs);
  const Loaded l = load(c.target);
  if (!c.stages.empty() && l.pipeline->stages == nullptr) {
    throw Error(fmt::format("--stages: {} has no stage table", l.pipeline->name));
  }
  DutFactory make_dut;
  if (c.backend == "rtl") {
    make_dut = rtl_of(l, c.target).make_dut;
  } else if (c.target.user_rtl() || !c.target.plugin.empty() || c.target.simulator != "verilator") {
    throw Error("--rtl, --rtl-plugin and --simulator need --backend rtl");
  } else if (c.target.x_init != "zero" || *c.target.x_seed_opt) {
    throw Error("--x-init and --x-seed need --backend rtl");
  }
  JsonOutput json(c.json);
  OutputFile out(c.out);
  std::optional<OutputFile> stages;
  if (!c.stages.empty()) stages.emplace(c.stages);
  const InputContract contract = l.pipeline->contract(*l.model, l.cfg);
  const EvalResult r = eval_csv(*l.model, make_dut, c.in, out.get(), c.real, contract,
                                l.pipeline->stages, stages ? stages->get() : nullptr);
  out.commit();
  if (stages) stages->commit();
  const std::string x_init =
      c.target.x_init == "random" ? fmt::format(", x-init random, seed {}", c.target.x_seed) : "";
  fmt::print(
      out.is_stdout() || json.to_stdout() || (stages && stages->is_stdout()) ? stderr : stdout,
      "{} output rows from {} ({} backend{}, {}) -> {}; {} vectors: {}\n", r.rows, c.in, c.backend,
      x_init, l.cfg.origin(), c.out, r.vectors, contract.summary(r.contract));
  if (json.wanted()) {
    nlohmann::ordered_json j = json_document("eval");
    j["pipeline"] = l.pipeline->name;
    j["config"] = l.cfg.name();
    j["config_path"] = l.cfg.origin();
    j["backend"] = c.backend;
    j["in"] = c.in;
    j["out"] = c.out;
    j["vectors"] = r.vectors;
    j["outputs"] = r.rows;
    j["in_contract"] = r.contract.in;
    j["out_of_contract"] = r.contract.out();
    j["contract_clauses"] = contract_json(contract.clauses(), r.contract);
    json.write(j);
  }
  return 0;
}

struct VectorsCli {
  Target target;
  std::uint64_t seed = 1;
  std::uint64_t random = 1000;
  bool directed = true;
  std::string out;
};

int run_vectors(const VectorsCli& c) {
  check_distinct({{"--out", c.out}, {"--config", c.target.config}});
  const Loaded l = load(c.target);
  const Stimulus stimulus = l.pipeline->make_stimulus(*l.model, l.cfg);
  const auto& fields = l.model->inputs();
  const std::uint64_t random = quick_cap(c.random, kQuickVectors);
  OutputFile file(c.out);
  std::string row;
  for (std::size_t i = 0; i < fields.size(); ++i) row += (i ? "," : "") + fields[i].name;
  fmt::print(file.get(), "{}\n", row);
  // Row by row: memory does not grow with the number of vectors.
  std::vector<std::int64_t> v(fields.size());
  const std::uint64_t first = c.directed ? 0 : stimulus.directed_count();
  const std::uint64_t last = stimulus.directed_count() + random;
  for (std::uint64_t index = first; index < last; ++index) {
    stimulus.vector(c.seed, index, v);
    row.clear();
    for (std::size_t i = 0; i < v.size(); ++i)
      fmt::format_to(std::back_inserter(row), "{}{}", i ? "," : "", v[i]);
    row += "\n";
    std::fputs(row.c_str(), file.get());
  }
  file.commit();
  fmt::print(file.is_stdout() ? stderr : stdout,
             "{} vectors ({} directed + {} random, seed {}) -> {}\n", last - first,
             c.directed ? stimulus.directed_count() : 0, random, c.seed, c.out);
  return 0;
}

}  // namespace

void add_eval(CLI::App& app, Action& action) {
  auto c = std::make_shared<EvalCli>();
  auto* cmd =
      app.add_subcommand("eval", "Evaluate a CSV of input vectors through the model or the RTL");
  c->target.add_options(*cmd);
  c->target.add_simulator_option(*cmd);
  add_choice(*cmd, "--backend", c->backend, "model or rtl", {"model", "rtl"});
  cmd->add_option("--in", c->in, "input CSV: header of input field names, one vector per row")
      ->required();
  cmd->add_option("--out", c->out,
                  "output CSV: header of output field names (- is standard output)")
      ->required();
  cmd->add_flag("--real", c->real, "values are reals instead of raw integers");
  cmd->add_option("--stages", c->stages,
                  "also write the model's stage values of every vector (the names of the "
                  "pipeline's spec table) as CSV: vector,stage,format,raw,real (- is standard "
                  "output)");
  cmd->add_option("--json", c->json,
                  "write the counts as JSON (docs/json.md: vectors, outputs, inside and outside "
                  "the input contract); - is standard output");
  cmd->callback([c, &action]() { action = [c]() { return run_eval(*c); }; });
}

void add_vectors(CLI::App& app, Action& action) {
  auto c = std::make_shared<VectorsCli>();
  auto* cmd = app.add_subcommand(
      "vectors", "Write the co-simulation stimulus (directed + seeded random) as an input CSV");
  c->target.add_options(*cmd, false);
  add_count(*cmd, "--vectors", c->random, "random vectors after the directed ones", kMaxVectors);
  add_count(*cmd, "--seed", c->seed, "seed", UINT64_MAX);
  cmd->add_flag("!--no-directed", c->directed, "skip the directed corners");
  cmd->add_option("--out", c->out, "output CSV, the input of phongsim eval (- is standard output)")
      ->required();
  cmd->callback([c, &action]() { action = [c]() { return run_vectors(*c); }; });
}

}  // namespace phongsim::cli
