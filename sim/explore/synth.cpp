#include "sim/explore/synth.h"

#include <fmt/format.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <span>
#include <sstream>
#include <string_view>
#include <tuple>
#include <vector>

#include "base/error.h"
#include "base/file_util.h"
#include "base/paths.h"
#include "base/process.h"
#include "base/temporaries.h"
#include "base/text.h"
#include "sim/cosim/portable.h"
#include "sim/cosim/rtl_plugin.h"
#include "sim/cosim/rtl_sources.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

// Paths and tools fixed when phongsim was configured (CMakeLists.txt).

// Part of every cache key: bump when the flow changes in a way the hashed scripts do not show
// (the wrapper, what is counted, how results are parsed).
constexpr const char* kFlowVersion = "phongsim synth flow 2";  // 2: logic depth
constexpr const char* kWrapTop = "phongsim_synth_wrap";

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!trim(line).empty()) lines.emplace_back(trim(line));
  }
  return lines;
}

// What a failing tool said: its last ERROR line (yosys lists a failed selection after it), else
// its last line.
std::string last_error_line(const std::string& log) {
  const auto lines = lines_of(log);
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) {
    if (it->find("ERROR") != std::string::npos) return *it;
  }
  return lines.empty() ? std::string("no output") : lines.back();
}

// A path as a yosys file argument of read_verilog (quoted) or of tee -o (plain: no spaces).
std::string quoted(const fs::path& path) {
  const std::string s = path.string();
  if (s.find_first_of("\"\n;") != std::string::npos) {
    throw Error(fmt::format("synthesis cannot pass the path '{}' to yosys (quote or ;)", s));
  }
  return fmt::format("\"{}\"", s);
}
std::string plain(const fs::path& path) {
  const std::string s = path.string();
  if (s.find_first_of("\" \t\n;") != std::string::npos) {
    throw Error(fmt::format("synthesis cannot use the directory '{}' (space, quote or ;)", s));
  }
  return s;
}

// The tool's version line; Error naming the tool and its Debian package when it cannot run.
std::string tool_version(const std::vector<std::string>& argv, const char* package) {
  const auto r = run_process(argv);
  if (r.exit_code != 0) {
    throw Error(
        fmt::format("synthesis needs {}, which cannot be run: install the Debian package {} "
                    "(scripts/setup.sh installs it)",
                    argv[0], package));
  }
  const auto lines = lines_of(r.out);
  return lines.empty() ? std::string() : lines.back();
}

// "chparam -set PFmt 65802 -set K 2": the parameters as Yosys takes them.
std::string chparams(std::span<const RtlParam> params) {
  std::string out;
  for (const RtlParam& p : params) {
    out += fmt::format("{}-set {} {}", out.empty() ? "" : " ", p.name, p.value);
  }
  return out;
}

// The start of every yosys script: read the sources (plus `extra`), set the parameters.
std::string read_script(const RtlDesign& src, const std::string& chparam,
                        const std::string& extra) {
  std::string s = "read_verilog -sv";
  // -I DIR and -D NAME=VALUE unquoted: Yosys keeps the quotes of a quoted option's value.
  for (const std::string& flag : rtl_source_flags(src)) {
    if (flag.find_first_of(" \t\n\"';") != std::string::npos) {
      throw Error(fmt::format("synthesis cannot pass '{}' to yosys (a space, quote or ;)", flag));
    }
    s += " " + flag;
  }
  for (const auto& f : src.files) s += fmt::format(" {}", quoted(f));
  if (!extra.empty()) s += fmt::format(" {}", extra);
  s += "; ";
  if (!chparam.empty()) s += fmt::format("chparam {} {}; ", chparam, src.top);
  return s;
}

std::string generic_script(const std::string& top, const std::string& dir) {
  return fmt::format(
      "synth -flatten -top {0}; check -assert; select -assert-none t:$*dlatch* t:$_DLATCH*; "
      "tee -q -o {1}/generic.json stat -json; write_json {1}/netlist.json; dffunmap; "
      "tee -q -o {1}/cmos.json stat -json -tech cmos",
      top, dir);
}

std::string ports_script(const std::string& top, const std::string& dir) {
  return fmt::format("hierarchy -top {0}; tee -q -o {1}/ports.txt portlist {0}", top, dir);
}

// The top is flattened on its own and kept as one module under the wrapper, so its cells can be
// counted apart from the wrapper's.
std::string ice40_script(const std::string& top, const std::string& dir) {
  return fmt::format(
      "hierarchy -top {2}; proc; flatten {0}; select -assert-none t:$*dlatch*; "
      "synth_ice40 -dsp -noflatten -top {2} -json {1}/ice40.json; "
      "tee -q -o {1}/ice40-stat.json stat -json",
      top, dir, kWrapTop);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void log_line(std::FILE* log, const std::string& text, std::chrono::steady_clock::time_point t0) {
  if (log == nullptr) return;
  fmt::print(log, "phongsim: synth: {} ({:.1f} s)\n", text, seconds_since(t0));
  std::fflush(log);
}

void run_yosys(const std::string& script, const fs::path& log_path, const std::string& label,
               const RtlDesign& src) {
  const std::string& top = src.top;
  const auto r = run_process({"yosys", "-q", "-p", script}, log_path);
  if (r.exit_code == 0) return;
  const std::string line = last_error_line(read_file(log_path));
  if (const std::string missing = missing_top_problem(src, line); !missing.empty()) {
    throw Error(fmt::format("{}: {}", label, missing));
  }
  if (line.find("Assertion failed") != std::string::npos &&
      (line.find("dlatch") != std::string::npos || line.find("DLATCH") != std::string::npos)) {
    throw Error(fmt::format("{}: the RTL of {} has latches (yosys: {})", label, top, line));
  }
  throw Error(fmt::format("{}: yosys synthesis of {} failed (exit {}): {}{}", label, top,
                          r.exit_code, line, portable_hint(line, "Yosys 0.23")));
}

nlohmann::json read_json(const fs::path& path) {
  try {
    return nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("cannot read yosys statistics {}: {}", path.string(), e.what()));
  }
}

// stat -json: {"modules": {"\\name": {"num_cells": n, "num_cells_by_type": {...}}}, "design": ..}
const nlohmann::json& stat_module(const nlohmann::json& stat, const std::string& top) {
  const auto& modules = stat.at("modules");
  const auto it = modules.find("\\" + top);
  if (it == modules.end()) throw Error(fmt::format("yosys statistics have no module {}", top));
  return *it;
}

void run_generic(const RtlDesign& src, const std::string& chparam, const fs::path& dir,
                 const std::string& label, SynthResult& r, std::FILE* log) {
  const auto t0 = std::chrono::steady_clock::now();
  run_yosys(read_script(src, chparam, "") + generic_script(src.top, plain(dir)),
            dir / "yosys-generic.log", label, src);
  try {
    const auto generic = read_json(dir / "generic.json");
    r.cells = stat_module(generic, src.top).at("num_cells").get<std::int64_t>();
    // "285336+": the '+' says some cells (asynchronous-reset flip-flops) have no cost.
    const auto cmos = read_json(dir / "cmos.json");
    const auto& est = cmos.at("design").at("estimated_num_transistors");
    r.transistors = est.is_string() ? std::stoll(est.get<std::string>()) : est.get<std::int64_t>();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // JSON shape, number syntax
    throw Error(fmt::format("unexpected yosys statistics for {}: {}", label, e.what()));
  }
  r.stages = logic_depth(read_file(dir / "netlist.json"), src.top);
  r.depth = r.stages.empty() ? 0 : r.stages.front().levels;
  log_line(log,
           fmt::format("yosys generic synthesis of {} ({}): {} cells, ~{} transistors, depth {} "
                       "levels",
                       label, src.top, r.cells, r.transistors, r.depth),
           t0);
}

struct Port {
  std::string direction;
  std::string name;
  int width = 0;
};

std::vector<Port> read_ports(const fs::path& path, const std::string& top) {
  // portlist: "module lyon_top", then "input [35:0] in_n0_i" per port.
  static const std::regex port(R"(^(input|output|inout) \[(-?\d+):(-?\d+)\] (\S+)$)");
  std::vector<Port> ports;
  for (const auto& line : lines_of(read_file(path))) {
    std::smatch m;
    if (!std::regex_match(line, m, port)) continue;
    const int msb = std::stoi(m[2].str());
    const int lsb = std::stoi(m[3].str());
    ports.push_back({m[1].str(), m[4].str(), std::abs(msb - lsb) + 1});
  }
  if (ports.empty()) throw Error(fmt::format("yosys listed no ports of {}", top));
  return ports;
}

// The wrapper that puts any top on a few pins: every input but clk_i and rst_ni comes from a
// shift register fed by sin_i; every output is loaded (load_i) into a shift register read at
// sout_o. Only register-to-register paths through the top remain, which nextpnr times.
std::string wrapper(const std::string& top, const std::vector<Port>& ports) {
  int in_bits = 0;
  int out_bits = 0;
  bool has_clk = false;
  bool has_rst = false;
  std::string conns;
  for (const auto& p : ports) {
    std::string net;
    if (p.direction == "inout") throw Error(fmt::format("{}: inout port {}", top, p.name));
    if (p.name == "clk_i" && p.direction == "input") {
      has_clk = true;
      net = "clk_i";
    } else if (p.name == "rst_ni" && p.direction == "input") {
      has_rst = true;
      net = "rst_ni";
    } else if (p.direction == "input") {
      net = fmt::format("in_sr[{}:{}]", in_bits + p.width - 1, in_bits);
      in_bits += p.width;
    } else {
      net = fmt::format("outs[{}:{}]", out_bits + p.width - 1, out_bits);
      out_bits += p.width;
    }
    conns += fmt::format("{}    .{}({})", conns.empty() ? "" : ",\n", p.name, net);
  }
  if (!has_clk) throw Error(fmt::format("{} has no clk_i input to time", top));
  const int ni = std::max(1, in_bits);
  const int no = std::max(1, out_bits);
  std::string v =
      fmt::format("module {}(input clk_i,{} input sin_i, input load_i, output sout_o);\n", kWrapTop,
                  has_rst ? " input rst_ni," : "");
  v += fmt::format("  reg [{}:0] in_sr;\n  reg [{}:0] out_sr;\n  wire [{}:0] outs;\n", ni - 1,
                   no - 1, no - 1);
  v += ni == 1
           ? "  always @(posedge clk_i) in_sr <= sin_i;\n"
           : fmt::format("  always @(posedge clk_i) in_sr <= {{in_sr[{}:0], sin_i}};\n", ni - 2);
  v += "  always @(posedge clk_i) out_sr <= load_i ? outs : (out_sr << 1);\n";
  v += fmt::format("  assign sout_o = out_sr[{}];\n", no - 1);
  v += fmt::format("  {} core (\n{});\nendmodule\n", top, conns);
  return v;
}

// nextpnr's "Device utilisation" lines: "Info:   ICESTORM_LC:  608/ 5280  11%". Returns the
// over-used resources ("ICESTORM_DSP 26/8").
std::vector<std::string> overused(const std::string& log) {
  static const std::regex util(R"(^Info:\s+([A-Za-z0-9_]+):\s+(\d+)/\s*(\d+)\s+\d+%)");
  std::vector<std::string> over;
  for (const auto& line : lines_of(log)) {
    std::smatch m;
    if (std::regex_search(line, m, util) && std::stoll(m[2].str()) > std::stoll(m[3].str())) {
      over.push_back(fmt::format("{} {}/{}", m[1].str(), m[2].str(), m[3].str()));
    }
  }
  return over;
}

void run_ice40(const RtlDesign& src, const std::string& chparam, const fs::path& dir,
               const std::string& label, SynthResult& r, std::FILE* log) {
  auto t0 = std::chrono::steady_clock::now();
  run_yosys(read_script(src, chparam, "") + ports_script(src.top, plain(dir)),
            dir / "yosys-ports.log", label, src);
  const fs::path wrap = dir / "wrap.v";
  std::ofstream(wrap) << wrapper(src.top, read_ports(dir / "ports.txt", src.top));
  run_yosys(read_script(src, chparam, quoted(wrap)) + ice40_script(src.top, plain(dir)),
            dir / "yosys-ice40.log", label, src);
  try {
    const auto stat = read_json(dir / "ice40-stat.json");
    const auto& top = stat_module(stat, src.top);
    r.lut4 = r.carry = r.mac16 = r.ff = 0;
    for (const auto& [type, n] : top.at("num_cells_by_type").items()) {
      const auto count = n.get<std::int64_t>();
      if (type == "SB_LUT4") r.lut4 += count;
      if (type == "SB_CARRY") r.carry += count;
      if (type == "SB_MAC16") r.mac16 += count;
      if (type.starts_with("SB_DFF")) r.ff += count;
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("unexpected yosys statistics for {}: {}", label, e.what()));
  }
  log_line(log,
           fmt::format("yosys synth_ice40 of {} ({}): {} LUT4, {} carries, {} SB_MAC16, {} FFs",
                       label, src.top, r.lut4, r.carry, r.mac16, r.ff),
           t0);

  t0 = std::chrono::steady_clock::now();
  const fs::path pnr_log = dir / "nextpnr.log";
  const fs::path report = dir / "report.json";
  const auto p = run_process(
      {"nextpnr-ice40", std::string("--") + kSynthIce40Device, "--package", kSynthIce40Package,
       "--json", (dir / "ice40.json").string(), "--report", report.string(), "--freq",
       std::to_string(kSynthIce40TargetMhz), "--seed", std::to_string(kSynthIce40Seed),
       "--timing-allow-fail", "-q", "-l", pnr_log.string()});
  const std::string pnr_text = read_file(pnr_log);
  if (p.exit_code != 0) {
    const auto over = overused(pnr_text);
    const std::string line = last_error_line(pnr_text.empty() ? p.out : pnr_text);
    if (over.empty() && line.find("no BELs remaining") == std::string::npos) {
      throw Error(fmt::format("{}: nextpnr-ice40 failed on {} (exit {}): {}", label, src.top,
                              p.exit_code, line));
    }
    r.fits = false;
    r.fmax_mhz = 0;
    std::string why;
    for (const auto& o : over) why += (why.empty() ? "" : ", ") + o;
    log_line(log,
             fmt::format("nextpnr-ice40 --{} of {}: does not fit ({})", kSynthIce40Device, label,
                         why.empty() ? line : why),
             t0);
    return;
  }
  double fmax = std::numeric_limits<double>::infinity();
  try {
    const auto j = read_json(report);
    for (const auto& [clock, f] : j.at("fmax").items()) {
      fmax = std::min(fmax, f.at("achieved").get<double>());
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("unexpected nextpnr report for {}: {}", label, e.what()));
  }
  if (!std::isfinite(fmax)) throw Error(fmt::format("nextpnr timed no clock of {}", src.top));
  r.fits = true;
  r.fmax_mhz = fmax;
  log_line(log,
           fmt::format("nextpnr-ice40 --{} of {}: fmax {:.2f} MHz", kSynthIce40Device, label, fmax),
           t0);
}

nlohmann::json to_json(const SynthResult& r) {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageDepth& s : r.stages) {
    stages.push_back({{"to", s.to},
                      {"output", s.output},
                      {"bits", s.bits},
                      {"levels", s.levels},
                      {"from", s.from}});
  }
  return {{"key", r.key},     {"cells", r.cells},      {"transistors", r.transistors},
          {"depth", r.depth}, {"stages", stages},      {"lut4", r.lut4},
          {"carry", r.carry}, {"mac16", r.mac16},      {"ff", r.ff},
          {"fits", r.fits},   {"fmax_mhz", r.fmax_mhz}};
}

std::optional<SynthResult> read_cached(const fs::path& path, const std::string& key) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  try {
    const auto j = nlohmann::json::parse(read_file(path));
    if (j.at("key").get<std::string>() != key) return std::nullopt;
    SynthResult r;
    r.key = key;
    r.cells = j.at("cells").get<std::int64_t>();
    r.transistors = j.at("transistors").get<std::int64_t>();
    r.depth = j.at("depth").get<std::int64_t>();
    for (const auto& s : j.at("stages")) {
      r.stages.push_back({s.at("to").get<std::string>(), s.at("output").get<bool>(),
                          s.at("bits").get<std::int64_t>(), s.at("levels").get<std::int64_t>(),
                          s.at("from").get<std::string>()});
    }
    r.lut4 = j.at("lut4").get<std::int64_t>();
    r.carry = j.at("carry").get<std::int64_t>();
    r.mac16 = j.at("mac16").get<std::int64_t>();
    r.ff = j.at("ff").get<std::int64_t>();
    r.fits = j.at("fits").get<bool>();
    r.fmax_mhz = j.at("fmax_mhz").get<double>();
    r.cached = true;
    return r;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;  // unreadable (e.g. from another version): synthesize again
  }
}

// Temp file in the cache directory, then rename: readers see the whole file or none. A cache that
// cannot be written costs the next caller a synthesis, not this one its result: `log` is told.
void write_cached(const fs::path& path, const nlohmann::json& j, std::FILE* log) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  bool written = false;
  if (!ec) {
    try {
      OwnedTemp tmp(temp_prefix_beside(path), OwnedTemp::Kind::file);
      const std::string text = j.dump(2) + "\n";
      written = write(tmp.fd(), text.data(), text.size()) == static_cast<ssize_t>(text.size()) &&
                std::rename(tmp.path().c_str(), path.c_str()) == 0;
      if (written) tmp.release();
    } catch (const Error&) {
    }
  }
  if (!written && log != nullptr) {
    fmt::print(log, "phongsim: synth: warning: cannot write the synthesis cache {}\n",
               path.string());
  }
}

// Logic depth ----------------------------------------------------------------------------------

// "valid_q", "vl_q5": a register's name in the RTL (STYLE.md: registers end _q, copies _q2, ...).
bool register_name(std::string_view name) {
  const auto dot = name.rfind('.');
  std::string_view last = dot == std::string_view::npos ? name : name.substr(dot + 1);
  while (!last.empty() && last.back() >= '0' && last.back() <= '9') last.remove_suffix(1);
  return last.ends_with("_q");
}

// Whether `a` names a flip-flop's output better than `b`: a register name first, then the
// innermost (most dots: where the register is declared, not a wire it is assigned to), then the
// shorter, then the first in order.
bool better_name(const std::string& a, const std::string& b) {
  const auto key = [](const std::string& n) {
    return std::tuple(register_name(n), std::count(n.begin(), n.end(), '.'),
                      -static_cast<std::ptrdiff_t>(n.size()));
  };
  const auto ka = key(a);
  const auto kb = key(b);
  return ka != kb ? ka > kb : a < b;
}

}  // namespace

std::vector<StageDepth> logic_depth(const std::string& netlist_json, const std::string& top) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(netlist_json);
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("cannot read the yosys netlist of {}: {}", top, e.what()));
  }
  try {
    const auto& mod = j.at("modules").at(top);
    // Bits are numbers; "0", "1", "x", "z" are constants (-1 here).
    const auto bit_of = [](const nlohmann::json& b) {
      return b.is_number_integer() ? b.get<std::int64_t>() : std::int64_t{-1};
    };
    struct Cell {
      bool sequential = false;
      std::vector<std::int64_t> in, out;
    };
    std::vector<Cell> cells;
    std::int64_t max_bit = 0;
    for (const auto& [name, c] : mod.at("cells").items()) {
      Cell cell;
      const auto& dirs = c.at("port_directions");
      // A flip-flop (Yosys's $_DFF*, $_SDFF*, $_ALDFF*, ... cells) has an output Q; its clock C
      // starts no path.
      cell.sequential = dirs.contains("Q") && dirs.at("Q") == "output";
      for (const auto& [port, bits] : c.at("connections").items()) {
        const std::string dir = dirs.at(port).get<std::string>();
        if (cell.sequential && port == "C") continue;
        for (const auto& b : bits) {
          const std::int64_t bit = bit_of(b);
          if (bit < 0) continue;
          max_bit = std::max(max_bit, bit);
          (dir == "output" ? cell.out : cell.in).push_back(bit);
        }
      }
      cells.push_back(std::move(cell));
    }
    std::vector<std::pair<std::string, std::vector<std::int64_t>>> inputs, outputs;
    for (const auto& [name, p] : mod.at("ports").items()) {
      std::vector<std::int64_t> bits;
      for (const auto& b : p.at("bits")) {
        bits.push_back(bit_of(b));
        max_bit = std::max(max_bit, bits.back());
      }
      (p.at("direction") == "output" ? outputs : inputs).emplace_back(name, std::move(bits));
    }
    const auto n = static_cast<std::size_t>(max_bit + 1);

    // Levels in topological order (Kahn): a gate's output is one more than its deepest input; a
    // bit no gate drives (an input port, a flip-flop's output) is level 0 and starts its paths.
    constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> driver(n, kNone);
    std::vector<bool> reg_out(n, false);
    for (std::size_t c = 0; c < cells.size(); ++c) {
      for (const auto bit : cells[c].out) {
        if (cells[c].sequential) {
          reg_out[bit] = true;
        } else {
          driver[bit] = c;
        }
      }
    }
    std::vector<std::int64_t> level(n, 0);
    std::vector<std::int64_t> start(n);
    for (std::size_t b = 0; b < n; ++b) start[b] = static_cast<std::int64_t>(b);
    std::vector<std::vector<std::size_t>> readers(n);
    std::vector<std::size_t> pending(cells.size(), 0);
    std::vector<std::size_t> ready;
    std::size_t gates = 0;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].sequential) continue;
      ++gates;
      for (const auto bit : cells[c].in) {
        if (driver[bit] == kNone) continue;
        readers[bit].push_back(c);
        ++pending[c];
      }
      if (pending[c] == 0) ready.push_back(c);
    }
    std::size_t done = 0;
    while (!ready.empty()) {
      const std::size_t c = ready.back();
      ready.pop_back();
      ++done;
      std::int64_t deepest = 0;
      std::int64_t from = -1;
      for (const auto bit : cells[c].in) {
        if (from < 0 || level[bit] > deepest) {
          deepest = level[bit];
          from = start[bit];
        }
      }
      for (const auto bit : cells[c].out) {
        level[bit] = deepest + 1;
        start[bit] = from;
        for (const std::size_t r : readers[bit]) {
          if (--pending[r] == 0) ready.push_back(r);
        }
      }
    }
    if (done != gates) {
      throw Error(fmt::format("the netlist of {} has a combinational loop", top));
    }

    // Names: an input port's bits by the port, a flip-flop's output by its best public wire.
    std::vector<const std::string*> name(n, nullptr);
    std::vector<std::string> netnames;
    for (const auto& [net, v] : mod.at("netnames").items()) {
      if (v.value("hide_name", 0) != 0) continue;
      netnames.push_back(net);
    }
    for (const auto& net : netnames) {
      for (const auto& b : mod.at("netnames").at(net).at("bits")) {
        const std::int64_t bit = bit_of(b);
        if (bit < 0 || bit > max_bit || !reg_out[bit]) continue;  // a wire no cell or port uses
        if (name[bit] == nullptr || better_name(net, *name[bit])) name[bit] = &net;
      }
    }
    for (const auto& [port, bits] : inputs) {
      for (const auto bit : bits) {
        if (bit >= 0) name[bit] = &port;
      }
    }
    static const std::string unnamed = "(unnamed register)";
    const auto name_of = [&](std::int64_t bit) -> std::string {
      if (bit < 0) return "";
      return name[bit] != nullptr ? *name[bit] : reg_out[bit] ? unnamed : "";
    };

    std::map<std::pair<bool, std::string>, StageDepth> stages;
    const auto add = [&](const std::string& to, bool output, std::span<const std::int64_t> bits,
                         std::int64_t count) {
      StageDepth& s = stages[{output, to}];
      s.to = to;
      s.output = output;
      s.bits += count;
      for (const auto bit : bits) {
        if (bit < 0) continue;  // a constant
        if (level[bit] > s.levels || (s.from.empty() && level[bit] == s.levels)) {
          s.levels = level[bit];
          s.from = name_of(start[bit]);
        }
      }
    };
    for (const Cell& c : cells) {
      if (!c.sequential || c.out.empty()) continue;
      add(name_of(c.out.front()), false, c.in, 1);
    }
    for (const auto& [port, bits] : outputs) {
      add(port, true, bits, static_cast<std::int64_t>(bits.size()));
    }
    std::vector<StageDepth> out;
    for (auto& [k, s] : stages) out.push_back(std::move(s));
    std::stable_sort(out.begin(), out.end(),
                     [](const StageDepth& a, const StageDepth& b) { return a.levels > b.levels; });
    return out;
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("unexpected yosys netlist of {}: {}", top, e.what()));
  }
}

SynthResult synthesize(const RtlDesign& src, const std::string& label, const SynthOptions& options,
                       std::FILE* log) {
  const std::string gflags = verilator_gflags(src.params);
  const std::string chparam = chparams(src.params);
  const std::string yosys_version = tool_version({"yosys", "-V"}, "yosys");
  const std::string nextpnr_version =
      options.ice40 ? tool_version({"nextpnr-ice40", "--version"}, "nextpnr-ice40") : "";

  const TempDir tmp("synth");  // removed when the synthesis is over, or on a signal

  ContentHash h;
  h.add(kFlowVersion);
  h.add(src.top);
  h.add(gflags);
  h.add(fmt::format("generic={} ice40={}", options.generic, options.ice40));
  h.add(yosys_version);
  RtlDesign shape;  // the script's words, without the design's
  shape.top = "TOP";
  shape.files = {"SRC"};
  h.add(read_script(shape, "CHPARAM", "EXTRA"));
  if (options.generic) h.add(generic_script("TOP", "DIR"));
  if (options.ice40) {
    h.add(nextpnr_version);
    h.add(fmt::format("{} {} {} {}", kSynthIce40Device, kSynthIce40Package, kSynthIce40TargetMhz,
                      kSynthIce40Seed));
    h.add(ports_script("TOP", "DIR"));
    h.add(ice40_script("TOP", "DIR"));
  }
  for (const auto& f : src.files) {
    h.add(f.filename().string());
    h.add(read_file(f));
  }
  // What an `include may read (Yosys does not say which): every header and source in the
  // include folders, and the defines.
  for (const fs::path& dir : rtl_include_dirs(src.include_dirs, src.files)) {
    std::vector<fs::path> in_dir;
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string ext = it->path().extension().string();
      if (it->is_regular_file(ec) && (ext == ".svh" || ext == ".vh" || ext == ".sv" ||
                                      ext == ".v" || ext == ".inc" || ext == ".h")) {
        in_dir.push_back(it->path());
      }
    }
    std::sort(in_dir.begin(), in_dir.end());
    for (const fs::path& f : in_dir) {
      h.add(f.filename().string());
      h.add(read_file(f));
    }
  }
  for (const std::string& def : src.defines) h.add("define " + def);
  const std::string key = h.hex();
  const fs::path cache_file = rtl_cache_dir() / "synth" / (key + ".json");
  if (auto cached = read_cached(cache_file, key)) return *cached;

  SynthResult r;
  r.key = key;
  if (!options.generic && !options.ice40) return r;
  if (options.generic) run_generic(src, chparam, tmp.path(), label, r, log);
  if (options.ice40) run_ice40(src, chparam, tmp.path(), label, r, log);

  auto j = to_json(r);
  j["design"] = src.name;
  j["config"] = label;
  j["top"] = src.top;
  j["gflags"] = gflags;
  j["generic"] = options.generic;
  j["ice40"] = options.ice40;
  if (options.ice40) j["device"] = kSynthIce40Device;
  j["yosys"] = yosys_version;
  if (options.ice40) j["nextpnr"] = nextpnr_version;
  write_cached(cache_file, j, log);
  return r;
}

void check_synthesizable(const RtlDesign& design, const std::string& label) {
  (void)tool_version({"yosys", "-V"}, "yosys");
  const TempDir tmp("synth");
  run_yosys(read_script(design, chparams(design.params), "") +
                fmt::format("synth -top {0}; check -assert; select -assert-none t:$*dlatch* "
                            "t:$_DLATCH*",
                            design.top),
            tmp.path() / "yosys-check.log", label, design);
}

}  // namespace phongsim
