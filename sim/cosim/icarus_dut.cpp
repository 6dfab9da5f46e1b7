#include "sim/cosim/icarus_dut.h"

#include <fmt/format.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/process.h"
#include "base/temporaries.h"
#include "sim/cosim/portable.h"

namespace fs = std::filesystem;

namespace phongsim {

namespace {

// A data port and where each of its fields sits (packed from bit 0 up, as verilated_dut.h).
struct IcarusPort {
  std::string name;
  int width = 0;
  std::vector<std::size_t> fields;  // indices into the model's inputs() or outputs()
  std::vector<fx::Format> formats;
};

std::vector<IcarusPort> ports_of(const RtlDesign& design, const std::vector<Field>& fields,
                                 bool input) {
  std::vector<IcarusPort> ports;
  for (const PortBinding& b : design.ports) {
    if (b.input != input) continue;
    IcarusPort p{b.port, 0, {}, {}};
    for (const auto& name : b.fields) {
      const auto it = std::find_if(fields.begin(), fields.end(),
                                   [&](const Field& f) { return f.name == name; });
      if (it == fields.end()) throw Error(fmt::format("port {}: no field {}", b.port, name));
      p.fields.push_back(static_cast<std::size_t>(it - fields.begin()));
      p.formats.push_back(it->fmt);
      p.width += it->fmt.width();
    }
    ports.push_back(std::move(p));
  }
  return ports;
}

// The testbench: the top with the configuration's parameters, driven by commands on stdin
//   R            reset (4 clocks, valid and ready low)             -> "@r"
//   C v r hex..  drive in_valid_i, out_ready_i and the input ports, settle
//                -> "@ in_ready out_valid hex.." (outputs, MSB first, x/z as Icarus prints them)
//   K            one clock (rising edge, then low again)            -> "@k"
// Anything else vvp prints (an RTL $error, say) passes through on other lines.
std::string testbench(const RtlDesign& design, const std::vector<IcarusPort>& in,
                      const std::vector<IcarusPort>& out) {
  std::string s = "`timescale 1ns/1ps\nmodule phongsim_icarus_tb;\n";
  s += "  logic clk_i = 0, rst_ni = 0, in_valid_i = 0, out_ready_i = 0;\n";
  s += "  logic in_ready_o, out_valid_o;\n";
  for (const auto& p : in) s += fmt::format("  logic [{}:0] {} = '0;\n", p.width - 1, p.name);
  for (const auto& p : out) s += fmt::format("  logic [{}:0] {};\n", p.width - 1, p.name);
  s += fmt::format("  {} #(", design.top);
  for (std::size_t i = 0; i < design.params.size(); ++i) {
    s +=
        fmt::format("{}.{}({})", i == 0 ? "" : ", ", design.params[i].name, design.params[i].value);
  }
  s += ") dut (.clk_i, .rst_ni, .in_valid_i, .in_ready_o, .out_valid_o, .out_ready_i";
  for (const auto& p : in) s += fmt::format(", .{}", p.name);
  for (const auto& p : out) s += fmt::format(", .{}", p.name);
  s += ");\n";
  s += "  localparam integer In = 32'h8000_0000, Out = 32'h8000_0001;\n";
  s += "  reg [7:0] cmd;\n  integer n;\n";
  s += "  initial begin\n    forever begin\n";
  s += "      n = $fscanf(In, \" %c\", cmd);\n      if (n != 1) $finish;\n";
  s += "      case (cmd)\n";
  s += "        \"R\": begin\n          rst_ni = 0; in_valid_i = 0; out_ready_i = 0;\n";
  s += "          repeat (4) begin #5 clk_i = 1; #5 clk_i = 0; end\n";
  s += "          rst_ni = 1; #1 $fdisplay(Out, \"@r\");\n        end\n";
  s += "        \"C\": begin\n          n = $fscanf(In, \" %h %h";
  for (std::size_t i = 0; i < in.size(); ++i) s += " %h";
  s += "\", in_valid_i, out_ready_i";
  for (const auto& p : in) s += ", " + p.name;
  s += ");\n          #1 $fdisplay(Out, \"@ %b %b";
  for (std::size_t i = 0; i < out.size(); ++i) s += " %h";
  s += "\", in_ready_o, out_valid_o";
  for (const auto& p : out) s += ", " + p.name;
  s += ");\n        end\n";
  s += "        \"K\": begin #4 clk_i = 1; #5 clk_i = 0; #1 $fdisplay(Out, \"@k\"); end\n";
  s += "        default: $finish;\n      endcase\n      $fflush(Out);\n    end\n  end\n";
  s += "endmodule\n";
  return s;
}

// The compiled simulation; its directory goes when the last DUT and the factory are gone (or a
// signal ends phongsim).
struct IcarusBuild {
  TempDir dir{"icarus"};
  std::vector<IcarusPort> in, out;
  std::string top;
};

std::vector<std::string> words_of(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

std::string hex_of(const std::vector<std::int64_t>& fields, const IcarusPort& p) {
  std::vector<bool> bits;
  for (std::size_t k = 0; k < p.fields.size(); ++k) {
    const std::uint64_t v = fx::to_bits(fields[p.fields[k]], p.formats[k]);
    for (int b = 0; b < p.formats[k].width(); ++b) bits.push_back(((v >> b) & 1U) != 0);
  }
  std::string hex;
  for (int d = (p.width + 3) / 4 - 1; d >= 0; --d) {
    int digit = 0;
    for (int b = 3; b >= 0; --b) {
      const auto i = static_cast<std::size_t>(4 * d + b);
      digit = 2 * digit + (i < bits.size() && bits[i] ? 1 : 0);
    }
    hex += "0123456789abcdef"[digit];
  }
  return hex;
}

class IcarusDut final : public RtlDut {
 public:
  IcarusDut(std::shared_ptr<const IcarusBuild> build, std::size_t inputs, std::size_t outputs)
      : build_(std::move(build)), in_(inputs), out_(outputs) {
    int to_child[2], from_child[2];
    if (pipe(to_child) != 0 || pipe(from_child) != 0) throw Error("icarus: cannot create pipes");
    pid_ = fork();
    if (pid_ < 0) throw Error("icarus: cannot start vvp");
    if (pid_ == 0) {
      dup2(to_child[0], 0);
      dup2(from_child[1], 1);
      close(to_child[1]);
      close(from_child[0]);
      const std::string vvp = (build_->dir.path() / "sim.vvp").string();
      execlp("vvp", "vvp", "-n", vvp.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    close(to_child[0]);
    close(from_child[1]);
    to_ = fdopen(to_child[1], "w");
    from_ = fdopen(from_child[0], "r");
  }
  ~IcarusDut() override {
    if (to_ != nullptr) std::fclose(to_);  // vvp sees end of input and finishes
    if (from_ != nullptr) std::fclose(from_);
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, &status, 0);
    }
  }
  IcarusDut(const IcarusDut&) = delete;
  IcarusDut& operator=(const IcarusDut&) = delete;

  void reset() override {
    command("R\n", "@r");
    cycle_ = 0;
  }
  void set_input(std::span<const std::int64_t> fields) override {
    in_.assign(fields.begin(), fields.end());
  }
  void set_in_valid(bool valid) override { in_valid_ = valid; }
  void set_out_ready(bool ready) override { out_ready_ = ready; }
  void settle() override {
    std::string c = fmt::format("C {} {}", in_valid_ ? 1 : 0, out_ready_ ? 1 : 0);
    for (const auto& p : build_->in) c += " " + hex_of(in_, p);
    const std::vector<std::string> w = words_of(command(c + "\n", "@"));
    if (w.size() != 3 + build_->out.size()) throw Error("icarus: malformed reply from vvp");
    const auto bit = [&](const std::string& v, const char* port) {
      if (v != "0" && v != "1") {
        throw UnknownValue(fmt::format("cycle {}: {} is {} (X or Z)", cycle_, port, v));
      }
      return v == "1";
    };
    in_ready_ = bit(w[1], "in_ready_o");
    out_valid_ = bit(w[2], "out_valid_o");
    if (!out_valid_) return;
    for (std::size_t k = 0; k < build_->out.size(); ++k) unpack(w[3 + k], build_->out[k]);
  }
  [[nodiscard]] bool in_ready() const override { return in_ready_; }
  [[nodiscard]] bool out_valid() const override { return out_valid_; }
  void output(std::span<std::int64_t> fields) const override {
    std::copy(out_.begin(), out_.end(), fields.begin());
  }
  void clock() override {
    command("K\n", "@k");
    ++cycle_;
  }
  [[nodiscard]] std::uint64_t cycle() const override { return cycle_; }
  [[nodiscard]] bool assertion_failed() const override { return assertion_failed_; }
  void open_trace(const std::string&) override {
    throw Error("--trace is not available with --simulator icarus");
  }
  void close_trace() override {}

 private:
  // Sends a command; returns the reply line that starts with `reply`. Other lines vvp prints go
  // to stderr; one with "ERROR" is an RTL assertion.
  std::string command(const std::string& text, std::string_view reply) {
    if (std::fputs(text.c_str(), to_) < 0 || std::fflush(to_) != 0) {
      throw Error("icarus: vvp exited early");
    }
    char buf[4096];
    std::string line;
    while (std::fgets(buf, sizeof buf, from_) != nullptr) {
      line += buf;
      if (line.back() != '\n') continue;
      line.pop_back();
      if (line.starts_with(reply)) return line;
      std::fprintf(stderr, "%s\n", line.c_str());
      if (line.find("ERROR") != std::string::npos) assertion_failed_ = true;
      line.clear();
    }
    throw Error(fmt::format("icarus: vvp exited at cycle {}", cycle_));
  }

  void unpack(const std::string& hex, const IcarusPort& p) {
    if (hex.size() != static_cast<std::size_t>((p.width + 3) / 4)) {
      throw Error(fmt::format("icarus: cycle {}: {} printed {} digits, not {}", cycle_, p.name,
                              hex.size(), (p.width + 3) / 4));
    }
    if (hex.find_first_not_of("0123456789abcdef") != std::string::npos) {
      throw UnknownValue(
          fmt::format("cycle {}: {} is {} while out_valid_o (X or Z)", cycle_, p.name, hex));
    }
    int lsb = 0;
    for (std::size_t k = 0; k < p.fields.size(); ++k) {
      std::uint64_t v = 0;
      for (int b = 0; b < p.formats[k].width(); ++b) {
        const int bit = lsb + b;
        const char c = hex[hex.size() - 1 - static_cast<std::size_t>(bit / 4)];
        const int digit = c <= '9' ? c - '0' : c - 'a' + 10;
        v |= static_cast<std::uint64_t>((digit >> (bit % 4)) & 1) << b;
      }
      out_[p.fields[k]] = fx::from_bits(v, p.formats[k]);
      lsb += p.formats[k].width();
    }
  }

  std::shared_ptr<const IcarusBuild> build_;
  pid_t pid_ = -1;
  std::FILE* to_ = nullptr;
  std::FILE* from_ = nullptr;
  std::vector<std::int64_t> in_, out_;
  bool in_valid_ = false, out_ready_ = false, in_ready_ = false, out_valid_ = false;
  bool assertion_failed_ = false;
  std::uint64_t cycle_ = 0;
};

}  // namespace

DutFactory icarus_duts(const RtlDesign& design, const PipelineModel& model, std::FILE* log) {
  (void)check_ports(design, model);  // the port contract, as for a Verilator build
  auto build = std::make_shared<IcarusBuild>();
  build->in = ports_of(design, model.inputs(), true);
  build->out = ports_of(design, model.outputs(), false);
  build->top = design.top;
  {
    std::ofstream tb(build->dir.path() / "tb.sv");
    tb << testbench(design, build->in, build->out);
  }
  std::vector<std::string> argv{"iverilog",
                                "-g2012",
                                "-o",
                                (build->dir.path() / "sim.vvp").string(),
                                "-s",
                                "phongsim_icarus_tb",
                                (build->dir.path() / "tb.sv").string()};
  // The same include folders and defines as Verilator's.
  for (const std::string& f : rtl_source_flags(design)) argv.push_back(f);
  for (const auto& f : rtl_files(design.files)) argv.push_back(f.string());
  if (log != nullptr) fmt::print(log, "Compiling {} with Icarus Verilog\n", design.name);
  const ProcessResult r = run_process(argv);
  if (r.exit_code != 0) {
    std::string errors;  // without Icarus's notes on sensitivity lists
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
      if (line.find("sorry: constant selects") == std::string::npos && !line.empty()) {
        errors += (errors.empty() ? "" : "\n") + line;
      }
    }
    throw Error(r.exit_code == -1
                    ? std::string("icarus: iverilog not found (Debian: iverilog)")
                    : fmt::format("iverilog failed for {}:\n{}{}", design.name, errors,
                                  portable_hint(errors, "Icarus Verilog 11")));
  }
  const std::size_t n_in = model.inputs().size(), n_out = model.outputs().size();
  std::shared_ptr<const IcarusBuild> shared = build;
  return [shared, n_in, n_out]() {
    return DutPtr(new IcarusDut(shared, n_in, n_out), DutDeleter{});  // the DUT holds the build
  };
}

}  // namespace phongsim
