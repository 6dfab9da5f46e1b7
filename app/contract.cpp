// phongsim contract: the port contract a design of a pipeline implements for one configuration,
// as a SystemVerilog module header with every port's width and what its bits carry, or as JSON
// (--json: docs/json.md) for scripts that generate wrappers, packing functions or drivers.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>

#include "app/commands.h"
#include "app/json.h"
#include "base/error.h"

namespace phongsim::cli {
namespace {

struct ContractCli {
  Target target;
  bool verilator_args = false;
  std::string json;
};

// One model field in a data port: bits [msb:lsb], packed from bit 0 up in the binding's order.
struct FieldBits {
  std::string name;
  fx::Format fmt;
  int lsb = 0;
  int msb = 0;
};

// One port of the top, in the header's order. Control ports (clock, reset, valid, ready) are one
// bit wide and carry no fields; a data port is as wide as its fields together.
struct Port {
  std::string name;
  bool input = true;
  std::string_view role;  // "clock", "reset", "valid", "ready" or "data"
  int width = 1;
  std::vector<FieldBits> fields;  // LSB first; data ports only
};

// The top's ports: the one place that says which bits of which port carry which field (the text
// header and the JSON both print this list).
std::vector<Port> contract_ports(const RtlDesign& d, const PipelineModel& model) {
  std::vector<Port> ports;
  const auto data_ports = [&](bool input) {
    const std::vector<Field>& list = input ? model.inputs() : model.outputs();
    for (const PortBinding& b : d.ports) {
      if (b.input != input) continue;
      Port p{b.port, input, "data", 0, {}};
      for (const std::string& name : b.fields) {
        const auto f =
            std::find_if(list.begin(), list.end(), [&](const Field& x) { return x.name == name; });
        if (f == list.end()) {
          throw Error(fmt::format("{}: port {} carries field {}, which the model does not have",
                                  d.name, b.port, name));
        }
        p.fields.push_back({name, f->fmt, p.width, p.width + f->fmt.width() - 1});
        p.width += f->fmt.width();
      }
      ports.push_back(std::move(p));
    }
  };
  const auto control = [&](const char* name, bool input, std::string_view role) {
    ports.push_back({name, input, role, 1, {}});
  };
  control("clk_i", true, "clock");
  control("rst_ni", true, "reset");
  control("in_valid_i", true, "valid");
  control("in_ready_o", false, "ready");
  data_ports(true);
  control("out_valid_o", false, "valid");
  control("out_ready_i", true, "ready");
  data_ports(false);
  return ports;
}

// The handshake rules, each a clause: the header's comment and the JSON's `handshake` say the
// same. The last two are freedoms (the header starts a sentence with the first of them).
constexpr std::array<std::string_view, 5> kHandshake{
    "a transaction moves when valid and ready are both high at a rising edge of clk_i",
    "out_valid_o and the output data stay unchanged while out_ready_i is low",
    "rst_ni is active low",
    "any latency, any number of transactions in flight",
    "outputs in the order the model produces them",
};
constexpr std::string_view kStateCarries = " (state carries from one input word to the next)";

std::vector<std::string> handshake_rules(bool independent_vectors) {
  std::vector<std::string> rules(kHandshake.begin(), kHandshake.end());
  if (!independent_vectors) rules.back() += kStateCarries;
  return rules;
}

// `text` as `//` comment lines of at most 90 columns, broken at spaces.
std::string comment_lines(std::string_view text) {
  constexpr std::size_t kColumns = 90;
  std::string out;
  std::string line = "//";
  while (!text.empty()) {
    const std::size_t end = text.find(' ');
    const std::string_view word = text.substr(0, end);
    if (line.size() > 2 && line.size() + 1 + word.size() > kColumns) {
      out += line + "\n";
      line = "//";
    }
    line += fmt::format(" {}", word);
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
  }
  return out + line + "\n";
}

void print_header(const Loaded& l, const RtlDesign& d, const std::vector<Port>& ports,
                  std::FILE* out) {
  fmt::print(out, "// Port contract of pipeline {} for {} (docs/your-rtl.md).\n", l.pipeline->name,
             l.cfg.origin());
  const std::vector<std::string> rules = handshake_rules(l.pipeline->independent_vectors);
  std::string freedom = rules[3];  // starts the second sentence
  freedom[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(freedom[0])));
  fmt::print(out, "{}",
             comment_lines(fmt::format("Handshake: {}; {}; {}. {}; {}.", rules[0], rules[1],
                                       rules[2], freedom, rules[4])));
  fmt::print(out, "module {} #(\n", d.top);
  for (std::size_t i = 0; i < d.params.size(); ++i) {
    fmt::print(out, "  parameter int {} = {}{}\n", d.params[i].name, d.params[i].value,
               i + 1 < d.params.size() ? "," : "");
  }
  fmt::print(out, ") (\n");
  for (std::size_t i = 0; i < ports.size(); ++i) {
    const Port& p = ports[i];
    const bool last = i + 1 == ports.size();  // no comma: the module header compiles
    const std::string_view direction = p.input ? "input " : "output";
    if (p.role != "data") {
      fmt::print(out, "  {} logic {}{}\n", direction, p.name, last ? "" : ",");
      continue;
    }
    std::string fields;
    for (const FieldBits& f : p.fields) {
      fields += fmt::format("{}{} {} [{}:{}]", fields.empty() ? "" : ", ", f.name, f.fmt.str(),
                            f.msb, f.lsb);
    }
    fmt::print(out, "  {} logic [{}:0] {}{}  // {}\n", direction, p.width - 1, p.name,
               last ? " " : ",", fields);
  }
  fmt::print(out, ");\n");
}

nlohmann::ordered_json contract_document(const Loaded& l, const RtlDesign& d,
                                         const std::vector<Port>& ports) {
  nlohmann::ordered_json j = json_document("contract");
  j["pipeline"] = l.pipeline->name;
  j["config"] = l.cfg.name();
  j["config_path"] = l.cfg.origin();
  j["top"] = d.top;
  j["parameters"] = nlohmann::ordered_json::array();
  for (const RtlParam& p : d.params) {
    j["parameters"].push_back({{"name", p.name}, {"value", p.value}, {"meaning", p.meaning}});
  }
  j["ports"] = nlohmann::ordered_json::array();
  for (const Port& p : ports) {
    nlohmann::ordered_json port = {{"name", p.name},
                                   {"direction", p.input ? "input" : "output"},
                                   {"width", p.width},
                                   {"role", p.role},
                                   {"fields", nullptr}};
    if (p.role == "data") {
      port["fields"] = nlohmann::ordered_json::array();
      for (const FieldBits& f : p.fields) {
        port["fields"].push_back({{"name", f.name},
                                  {"lsb", f.lsb},
                                  {"msb", f.msb},
                                  {"format", format_word(f.fmt)},
                                  {"format_text", f.fmt.str()},
                                  {"signed", f.fmt.is_signed},
                                  {"int_bits", f.fmt.int_bits},
                                  {"frac_bits", f.fmt.frac_bits}});
      }
    }
    j["ports"].push_back(std::move(port));
  }
  j["handshake"] = handshake_rules(l.pipeline->independent_vectors);
  j["independent_vectors"] = l.pipeline->independent_vectors;
  return j;
}

int run(const ContractCli& c) {
  const Target& t = c.target;
  const Loaded l = load(t);
  const RtlDesign d = rtl_design(*l.pipeline, l.cfg);
  check_outputs({{"--json", c.json}}, t.inputs());
  JsonOutput json(c.json);
  const std::vector<Port> ports = contract_ports(d, *l.model);
  std::FILE* const out = json.text();
  if (c.verilator_args) {  // for your own verilate(): cmake/phongsimConfig.cmake.in
    fmt::print(out, "TOP {}\n", d.top);
    for (const RtlParam& p : d.params) fmt::print(out, "PARAM -G{}={}\n", p.name, p.value);
    for (const auto& f : d.files) fmt::print(out, "SOURCE {}\n", f.string());
  } else {
    print_header(l, d, ports, out);
  }
  json.write(contract_document(l, d, ports));
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
  cmd->add_option("--json", c->json,
                  "also write the contract as JSON (docs/json.md: parameters with their meaning, "
                  "ports with their fields' bit ranges and formats, handshake; - is standard "
                  "output)");
  cmd->callback([c, &action]() { action = [c]() { return run(*c); }; });
}

}  // namespace phongsim::cli
