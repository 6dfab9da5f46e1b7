// phongsim contract: the port contract a design of a pipeline implements for one configuration,
// as a SystemVerilog module header with every port's width and what its bits carry.
#include <fmt/format.h>

#include <algorithm>

#include "app/commands.h"

namespace phongsim::cli {
namespace {

struct ContractCli {
  Target target;
  bool verilator_args = false;
};

int run(const ContractCli& c) {
  const Target& t = c.target;
  const Loaded l = load(t);
  const RtlDesign d = rtl_design(*l.pipeline, l.cfg);
  if (c.verilator_args) {  // for your own verilate(): cmake/phongsimConfig.cmake.in
    fmt::print("TOP {}\n", d.top);
    for (const RtlParam& p : d.params) fmt::print("PARAM -G{}={}\n", p.name, p.value);
    for (const auto& f : d.files) fmt::print("SOURCE {}\n", f.string());
    return 0;
  }
  fmt::print("// Port contract of pipeline {} for {} (docs/your-rtl.md).\n", l.pipeline->name,
             l.cfg.origin());
  fmt::print(
      "// Handshake: a transaction moves when valid and ready are both high at a rising edge of\n"
      "// clk_i; out_valid_o and the output data stay unchanged while out_ready_i is low; rst_ni\n"
      "// is active low. Any latency, any number of transactions in flight; outputs in the order\n"
      "// the model produces them{}.\n",
      l.pipeline->independent_vectors ? "" : " (state carries from one input word to the next)");
  fmt::print("module {} #(\n", d.top);
  for (std::size_t i = 0; i < d.params.size(); ++i) {
    fmt::print("  parameter int {} = {}{}\n", d.params[i].name, d.params[i].value,
               i + 1 < d.params.size() ? "," : "");
  }
  fmt::print(") (\n  input  logic clk_i,\n  input  logic rst_ni,\n");
  const auto ports = [&](bool input) {
    std::string s;
    for (const PortBinding& b : d.ports) {
      if (b.input != input) continue;
      int width = 0;
      std::string fields;
      for (const auto& name : b.fields) {
        const auto& list = input ? l.model->inputs() : l.model->outputs();
        const auto f =
            std::find_if(list.begin(), list.end(), [&](const Field& x) { return x.name == name; });
        fields += fmt::format("{}{} {} [{}:{}]", fields.empty() ? "" : ", ", name, f->fmt.str(),
                              width + f->fmt.width() - 1, width);
        width += f->fmt.width();
      }
      s += fmt::format("  {} logic [{}:0] {},  // {}\n", input ? "input " : "output", width - 1,
                       b.port, fields);
    }
    return s;
  };
  fmt::print("  input  logic in_valid_i,\n  output logic in_ready_o,\n{}", ports(true));
  std::string last = ports(false);  // the last port has no comma: the module header compiles
  last.replace(last.rfind(",  //"), 1, " ");
  fmt::print("  output logic out_valid_o,\n  input  logic out_ready_i,\n{}", last);
  fmt::print(");\n");
  return 0;
}

}  // namespace

void add_contract(CLI::App& app, Action& action) {
  auto c = std::make_shared<ContractCli>();
  auto* cmd = app.add_subcommand(
      "contract",
      "Print the port contract a pipeline's RTL implements for a configuration (a SystemVerilog "
      "module header: parameters, ports, widths, which bits carry which field)");
  c->target.add_options(*cmd, false);
  cmd->add_flag("--verilator-args", c->verilator_args,
                "print the built-in design's top, -G parameters and sources, one per line (TOP, "
                "PARAM, SOURCE), for your own Verilator build");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
