#include "sim/cosim/rtl_plugin.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "base/error.h"
#include "base/file_util.h"
#include "base/paths.h"
#include "base/process.h"
#include "base/temporaries.h"
#include "sim/cosim/rtl_flags.h"
#include "sim/cosim/rtl_sources.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

// How every plugin is Verilated (part of its key). FST tracing is added by the CMake function.
// A module defined twice is an error (which one Verilator would take is not what a verdict may
// depend on).
const std::vector<std::string> kVerilatorFlags = {
    "--assert", "-Wno-fatal", "-Werror-MODDUP", "-O3", "-x-assign", "fast", "-x-initial", "fast"};
// The XInit::random variant: X assignments and power-up values drawn at run time.
const std::vector<std::string> kVerilatorFlagsXRandom = {
    "--assert",  "-Wno-fatal", "-Werror-MODDUP", "-O3",
    "-x-assign", "unique",     "-x-initial",     "unique"};

// Everything Verilator is given besides the sources and the include folders: the defaults, the
// variant's, and $PHONGSIM_VERILATOR_FLAGS (sim/cosim/rtl_flags.h; how the defaults were chosen is
// in docs/performance.md).
std::vector<std::string> verilator_flags(const RtlDesign& d) {
  std::vector<std::string> flags =
      d.x_init == XInit::random ? kVerilatorFlagsXRandom : kVerilatorFlags;
  // The coverage variant: Verilator's line (and branch) points, and toggle points if asked.
  if (d.coverage) flags.emplace_back("--coverage-line");
  if (d.coverage && d.coverage_toggle) flags.emplace_back("--coverage-toggle");
  const std::vector<std::string> extra = verilator_env_flags();
  flags.insert(flags.end(), extra.begin(), extra.end());
  return flags;
}

// -I<folder> for each folder an `include is searched in (rtl_sources.h).
std::vector<std::string> include_flags(const RtlDesign& d) {
  std::vector<std::string> flags;
  for (const fs::path& dir : rtl_include_dirs(d.files)) flags.push_back("-I" + dir.string());
  return flags;
}

// The first line a tool prints for --version, once per process.
std::string tool_version(const std::string& program) {
  static std::mutex mutex;
  static std::map<std::string, std::string> versions;
  const std::lock_guard lock(mutex);
  if (const auto it = versions.find(program); it != versions.end()) return it->second;
  const ProcessResult r = run_process({program, "--version"});
  if (r.exit_code != 0) {
    throw Error(
        fmt::format("cannot run '{}': is it installed? (scripts/setup.sh installs it)", program));
  }
  return versions[program] = r.out.substr(0, r.out.find('\n'));
}

std::string last_lines(const std::string& text, int n) {
  std::size_t pos = text.size();
  for (int i = 0; i <= n && pos != std::string::npos && pos > 0; ++i) {
    pos = text.rfind('\n', pos - 1);
  }
  std::string tail = pos == std::string::npos ? text : text.substr(pos + 1);
  std::replace(tail.begin(), tail.end(), '\n', ' ');
  return tail;
}

// The project files the generated adapter compiles: verilated_dut.h and what it includes,
// transitively (quoted includes that resolve in the tree).
std::vector<fs::path> adapter_headers() {
  std::vector<fs::path> found;
  std::vector<fs::path> todo{"sim/cosim/verilated_dut.h"};
  static const std::regex include(R"re(^\s*#\s*include\s+"([^"]+)")re");
  while (!todo.empty()) {
    const fs::path rel = todo.back();
    todo.pop_back();
    if (std::find(found.begin(), found.end(), rel) != found.end()) continue;
    found.push_back(rel);
    std::istringstream in(read_file(include_root() / rel));
    std::string line;
    std::smatch m;
    while (std::getline(in, line)) {
      if (std::regex_search(line, m, include) && fs::exists(include_root() / m[1].str())) {
        todo.emplace_back(m[1].str());
      }
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string ports_text(const RtlDesign& d) {
  std::string s;
  for (const PortBinding& p : d.ports) {
    s += fmt::format("port {} {}", p.input ? "input" : "output", p.port);
    for (const auto& f : p.fields) s += " " + f;
    s += "\n";
  }
  return s;
}

// The generated adapter: binds the design's ports and records what the plugin is built from.
// An XInit::random plugin's top is a subclass that sets its context's random reset and seed
// before the Verilated constructor draws the power-up state; phongsim_rtl_x_seed() sets the
// seed for the DUTs the calling thread makes next. A coverage plugin's top (a subclass of that)
// writes its context's coverage counts when it is destroyed, to PREFIX<n>.dat with the prefix
// phongsim_rtl_coverage_prefix() set for the calling thread when it was made (none: no file).
std::string adapter_source(const RtlDesign& d, const std::string& info) {
  std::string s = fmt::format(
      "// Generated by phongsim (sim/cosim/rtl_plugin.cpp) for {}.\n"
      "#include \"V{}.h\"\n#include \"sim/cosim/verilated_dut.h\"\n\n"
      "static const char kInfo[] = R\"phongsim({})phongsim\";\n#define PHONGSIM_RTL_INFO kInfo\n\n",
      d.name, d.top, info);
  std::string top = "V" + d.top;
  if (d.x_init == XInit::random) {
    s += fmt::format(
        "static thread_local int x_seed = 1;\n"
        "extern \"C\" __attribute__((visibility(\"default\"))) void phongsim_rtl_x_seed(int seed) "
        "{{\n  x_seed = seed;\n}}\n"
        "struct {0}_xrandom : {0} {{\n"
        "  {0}_xrandom(VerilatedContext* context, const char* name) : {0}(seeded(context), name) "
        "{{}}\n"
        "  static VerilatedContext* seeded(VerilatedContext* context) {{\n"
        "    context->randReset(2);\n    context->randSeed(x_seed);\n    return context;\n  }}\n"
        "}};\n\n",
        top);
    top += "_xrandom";
  }
  if (d.coverage) {
    s += fmt::format(
        "#include <unistd.h>\n#include <atomic>\n#include <string>\n"
        "static thread_local std::string coverage_prefix;\n"
        "static std::atomic<unsigned> coverage_files{{0}};\n"
        "extern \"C\" __attribute__((visibility(\"default\"))) void "
        "phongsim_rtl_coverage_prefix(const char* prefix) {{\n  coverage_prefix = prefix;\n}}\n"
        "struct {0}_coverage : {0} {{\n"
        "  {0}_coverage(VerilatedContext* context, const char* name)\n"
        "      : {0}(context, name), prefix(coverage_prefix) {{}}\n"
        "  ~{0}_coverage() {{\n"
        "    if (prefix.empty()) return;\n"
        "    const std::string file = prefix + std::to_string(coverage_files++) + \".dat\";\n"
        "    contextp()->coveragep()->write(file.c_str());\n  }}\n"
        "  std::string prefix;\n"
        "}};\n\n",
        top);
    top += "_coverage";
  }
  s += fmt::format("PHONGSIM_RTL_PLUGIN({}, []({}& top, phongsim::PortMap& map) {{\n", top, top);
  for (const PortBinding& p : d.ports) {
    std::string fields;
    for (const auto& f : p.fields) fields += fmt::format("{}\"{}\"", fields.empty() ? "" : ", ", f);
    s += fmt::format("  map.{}(top.{}, {{{}}});\n", p.input ? "input" : "output", p.port, fields);
  }
  return s + "})\n";
}

// The value of a record's first line "<field> <value>" ("" when it has none).
std::string info_field(const std::string& info, std::string_view field) {
  std::istringstream in(info);
  std::string line;
  const std::string prefix = std::string(field) + " ";
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  }
  return "";
}

// The values of all of a record's lines "<field> <value>".
std::vector<std::string> info_lines(const std::string& info, std::string_view field) {
  std::vector<std::string> lines;
  std::istringstream in(info);
  const std::string prefix = std::string(field) + " ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) lines.push_back(line.substr(prefix.size()));
  }
  return lines;
}

std::string runtime_key() {
  ContentHash h;
  h.add(fmt::format("phongsim verilated runtime, abi {}", kRtlPluginAbi));
  h.add(tool_version("verilator"));
  h.add(tool_version(cxx_compiler()));
  h.add(read_file(data_root() / "cmake" / "PhongsimRtl.cmake"));
  return h.hex();
}

// The design's own files, hashed, and everything else its key depends on but the files they
// `include (known only once Verilator has read them).
struct Keyed {
  std::string base;               // the hash of all that
  std::vector<HashedFile> files;  // the design's files, in order
  std::string head;               // the record's lines that do not depend on included files
};

Keyed key_of(const RtlDesign& d) {
  Keyed k;
  for (const fs::path& f : d.files) k.files.push_back(hash_file(f));
  ContentHash h;
  h.add(fmt::format("phongsim rtl plugin, abi {}", kRtlPluginAbi));
  h.add(runtime_key());
  const std::vector<std::string> flags = verilator_flags(d);
  for (const auto& f : flags) h.add(f);
  h.add(d.top);
  const std::string gflags = verilator_gflags(d.params);
  h.add(gflags);
  h.add(ports_text(d));
  // By name and content: the same files in another copy of the tree have the same key.
  for (const HashedFile& f : k.files) {
    h.add(f.path.filename().string());
    h.add(f.hash);
  }
  // How many folders the files are in, and which file is in which: the include folders' order.
  const std::vector<fs::path> dirs = rtl_include_dirs(d.files);
  for (const HashedFile& f : k.files) {
    h.add(std::to_string(std::find(dirs.begin(), dirs.end(), f.path.parent_path()) - dirs.begin()));
  }
  for (const fs::path& header : adapter_headers()) {
    h.add(header.string());
    h.add(read_file(include_root() / header));
  }
  // The key covers the adapter too; its text embeds the record, so hash what precedes it.
  h.add(adapter_source(d, ""));
  k.base = h.hex();
  const std::vector<std::string> extra = verilator_env_flags();
  k.head =
      fmt::format("base {}\nname {}\ntop {}\ngflags {}\n{}{}{}{}", k.base, d.name, d.top, gflags,
                  d.x_init == XInit::random ? "x_init random\n" : "",
                  !d.coverage         ? ""
                  : d.coverage_toggle ? "coverage line toggle\n"
                                      : "coverage line\n",
                  extra.empty() ? "" : fmt::format("verilator_extra {}\n", fmt::join(extra, " ")),
                  ports_text(d));
  for (const HashedFile& f : k.files)
    k.head += fmt::format("file {} {}\n", f.hash, f.path.string());
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    k.head += fmt::format("incdir {} {}\n", i, dirs[i].string());
  }
  return k;
}

std::string include_line(const IncludedFile& inc) {
  return fmt::format("include {} {} {}\n", inc.hash, inc.dir, inc.rel.string());
}

std::optional<IncludedFile> parse_include(const std::string& rest) {
  std::istringstream words(rest);
  IncludedFile inc;
  words >> inc.hash >> inc.dir;
  std::string rel;
  std::getline(words, rel);
  if (!words.eof() && !words) return std::nullopt;
  if (rel.empty() || rel.front() != ' ' || inc.hash.size() != 64) return std::nullopt;
  inc.rel = rel.substr(1);
  return inc;
}

// The full key: the base and every included file (where it is found, and its content).
std::string full_key(const std::string& base, std::span<const IncludedFile> includes) {
  ContentHash h;
  h.add(base);
  for (const IncludedFile& inc : includes) h.add(include_line(inc));
  return h.hex();
}

// The record a plugin carries (compiled into it, and in its cache folder's info.txt).
std::string record_of(const Keyed& k, std::span<const IncludedFile> includes,
                      const std::map<std::string, int>& widths) {
  std::string info = fmt::format("key {}\n{}", full_key(k.base, includes), k.head);
  for (const IncludedFile& inc : includes) info += include_line(inc);
  for (const auto& [port, width] : widths) info += fmt::format("width {} {}\n", port, width);
  return info;
}

// "lyon-<base>-<key>": a design's plugins share the first part, one per content of the files
// they include.
fs::path plugin_dir(const RtlDesign& d, const std::string& base, const std::string& key) {
  return rtl_cache_dir() / fmt::format("{}-{}-{}", d.name, base.substr(0, 16), key.substr(0, 16));
}

struct Cached {
  fs::path dir;
  std::string key;
  std::string info;
};

// The cached plugin of `d` whose every included file has, where the design finds it now, the
// content it was built from; nothing when there is none.
std::optional<Cached> find_cached(const RtlDesign& d, const Keyed& k) {
  const std::string prefix = fmt::format("{}-{}-", d.name, k.base.substr(0, 16));
  const std::vector<fs::path> dirs = rtl_include_dirs(d.files);
  std::error_code ec;
  std::vector<fs::path> candidates;
  for (const auto& e : fs::directory_iterator(rtl_cache_dir(), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && !is_temporary_name(name)) candidates.push_back(e.path());
  }
  std::sort(candidates.begin(), candidates.end());
  for (const fs::path& dir : candidates) {
    const std::string info = read_file(dir / "info.txt");
    if (info_field(info, "base") != k.base) continue;
    std::vector<IncludedFile> includes;
    bool same = true;
    for (const std::string& line : info_lines(info, "include")) {
      const auto inc = parse_include(line);
      const auto path = inc ? resolve_include(*inc, dirs) : std::nullopt;
      same = path && fs::is_regular_file(*path, ec) && file_hash(*path) == inc->hash;
      if (!same) break;
      includes.push_back(*inc);
    }
    const std::string key = info_field(info, "key");
    if (same && key == full_key(k.base, includes)) return Cached{dir, key, info};
  }
  return std::nullopt;
}

// Why a cached folder cannot be used: its plugin (or the runtime it links) is not the file
// recorded when it was built. Empty when it is intact.
std::string damage(const fs::path& dir, const std::string& info, const std::string& file_name) {
  std::istringstream words(info_field(info, "file_hash " + file_name));
  std::uintmax_t size = 0;
  std::string hash;
  words >> size >> hash;
  const fs::path file = dir / file_name;
  std::error_code ec;
  if (hash.empty()) return fmt::format("{} has no record of {}", dir.string(), file_name);
  if (!fs::is_regular_file(file, ec)) return fmt::format("{} is missing", file.string());
  if (fs::file_size(file, ec) != size) {
    return fmt::format("{} is {} bytes, not the {} it was built with", file.string(),
                       fs::file_size(file, ec), size);
  }
  if (file_hash(file) != hash)
    return fmt::format("{} is not the file it was built as", file.string());
  return "";
}

// Moves a cache folder out of the way (renamed to a temporary's name, then removed), so that a
// process still using it keeps what it opened.
void discard(const fs::path& dir) {
  const OwnedTemp gone(temp_prefix_beside(dir), OwnedTemp::Kind::directory);
  std::error_code ec;
  fs::rename(dir, gone.path() / "old", ec);
}

// A directory renamed into place only when complete (a temporary, base/temporaries.h, until then).
class Staging {
 public:
  explicit Staging(fs::path final_path)
      : final_(std::move(final_path)),
        temp_(temp_prefix_beside(final_), OwnedTemp::Kind::directory) {}
  [[nodiscard]] const fs::path& path() const { return temp_.path(); }
  // Atomic publish; when another process published the same content first, theirs stays.
  void commit() {
    std::error_code ec;
    fs::rename(temp_.path(), final_, ec);
    if (!ec) temp_.release();
  }

 private:
  fs::path final_;
  OwnedTemp temp_;
};

std::string cmake_list(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += fmt::format(" \"{}\"", i);
  return s;
}

// A file of a build's record as "<content hash> <file name>": the same file in another copy of
// the tree (another absolute path) has not changed.
std::set<std::string> info_files(const std::string& info) {
  std::set<std::string> files;
  for (const std::string& line : info_lines(info, "file")) {
    const auto path_at = line.find(' ');
    files.insert(line.substr(0, path_at) + " " +
                 fs::path(line.substr(path_at + 1)).filename().string());
  }
  for (const std::string& line : info_lines(info, "include")) {
    if (const auto inc = parse_include(line)) {
      files.insert(inc->hash + " " + inc->rel.filename().string());
    }
  }
  return files;
}

// Says why a rebuild happens: the Verilator flags, when a cached build of the same top,
// parameters and files has other $PHONGSIM_VERILATOR_FLAGS; else the files that differ from the
// newest cached build of the same top and parameters.
std::string changed_since_last_build(const RtlDesign& d, const Keyed& k) {
  std::error_code ec;
  fs::file_time_type newest{};
  std::string previous;
  const std::set<std::string> now = info_files(k.head);
  const std::string extra = info_field(k.head, "verilator_extra");
  for (const auto& e : fs::directory_iterator(rtl_cache_dir(), ec)) {
    const fs::path info = e.path() / "info.txt";
    if (e.path().filename().string().rfind(d.name + "-", 0) != 0 || !fs::exists(info)) continue;
    const std::string text = read_file(info);
    if (info_field(text, "top") != d.top ||
        info_field(text, "gflags") != info_field(k.head, "gflags") ||
        info_field(text, "x_init") != info_field(k.head, "x_init") ||
        info_field(text, "coverage") != info_field(k.head, "coverage"))
      continue;
    std::set<std::string> given;  // its own files, without the included ones
    for (const std::string& f : info_files(text)) {
      if (now.contains(f)) given.insert(f);
    }
    if (given == now && info_field(text, "verilator_extra") != extra) {
      return fmt::format("PHONGSIM_VERILATOR_FLAGS changed: now \"{}\"", extra);
    }
    if (const auto t = fs::last_write_time(info, ec); previous.empty() || t > newest) {
      newest = t;
      previous = text;
    }
  }
  if (previous.empty()) return "first build of these parameters";
  const std::set<std::string> before = info_files(previous);
  std::string list;
  for (const std::string& f : now) {
    if (!before.contains(f)) list += (list.empty() ? "" : ", ") + f.substr(f.find(' ') + 1);
  }
  if (!list.empty()) return "changed since the last build: " + list;
  if (info_field(previous, "base") == k.base) return "a file it includes changed";
  return "phongsim's plugin code or the tools changed";
}

// The port widths a Verilated class declares: VL_IN*/VL_OUT*(&name, msb, lsb).
std::map<std::string, int> declared_ports(const RtlDesign& d, const fs::path& header) {
  std::map<std::string, int> widths;
  static const std::regex decl(R"(VL_(IN|OUT|INOUT)\w*\(&(\w+),(\d+),(\d+))");
  const std::string text = read_file(header);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), decl); it != std::sregex_iterator();
       ++it) {
    const auto& m = *it;
    if (m[1] == "INOUT") {
      throw Error(fmt::format("{}: top {} has an inout port {}; the contract has none", d.name,
                              d.top, m[2].str()));
    }
    widths[m[2]] = std::stoi(m[3]) - std::stoi(m[4]) + 1;
  }
  return widths;
}

// Verilator's words about a design it cannot read: a module defined twice named with both files,
// else its first error line.
std::string verilator_problem(const RtlDesign& d, const std::string& out, int exit_code) {
  static const std::regex moddup(
      R"(%Error-MODDUP: ([^\n]*?):(\d+):\d+: Duplicate declaration of module: '([^']*)'[\s\S]*?\n\s*([^\n]*?):(\d+):\d+: \.\.\. Location of original declaration)");
  std::smatch m;
  if (std::regex_search(out, m, moddup)) {
    return fmt::format(
        "module {} is defined twice, in {}:{} and {}:{}; give each module once (which one "
        "Verilator would take is not what a verdict may depend on)",
        m[3].str(), m[4].str(), m[5].str(), m[1].str(), m[2].str());
  }
  std::string first = out;
  if (const auto at = out.find("%Error"); at != std::string::npos) first = out.substr(at);
  first = first.substr(0, first.find('\n'));
  return fmt::format("Verilator cannot read the RTL of {} (top {}): {}", d.name, d.top,
                     first.empty() ? "exit " + std::to_string(exit_code) : first);
}

// What the check before a build learned: the ports as Verilator sees them, and every file it
// read with the stamp it saw.
struct Checked {
  std::map<std::string, bool> inputs;  // port -> is an input
  std::map<std::string, int> widths;
  std::map<fs::path, FileStamp> read;
};

// Verilates the design as the build will (same files, include folders and flags that matter
// for reading it, from an empty folder) and reads the class's port declarations.
Checked verilate_interface(const RtlDesign& d) {
  const TempDir dir("ports");
  const fs::path mdir = dir.path() / "obj";
  std::vector<std::string> argv{"verilator",    "--cc", "-Wno-fatal", "-Werror-MODDUP",
                                "--top-module", d.top,  "-Mdir",      mdir.string()};
  for (const RtlParam& p : d.params) argv.push_back(fmt::format("-G{}={}", p.name, p.value));
  for (const std::string& i : include_flags(d)) argv.push_back(i);
  for (const fs::path& f : d.files) argv.push_back(fs::absolute(f).lexically_normal().string());
  const ProcessResult r = run_process(argv, {}, dir.path());
  if (r.exit_code != 0) throw Error(verilator_problem(d, r.out, r.exit_code));
  Checked c;
  c.read = verilator_read(mdir, "V" + d.top, dir.path());
  static const std::regex decl(R"(VL_(IN|OUT|INOUT)\w*\(&(\w+),(\d+),(\d+))");
  const std::string header = read_file(mdir / fmt::format("V{}.h", d.top));
  for (auto it = std::sregex_iterator(header.begin(), header.end(), decl);
       it != std::sregex_iterator(); ++it) {
    const auto& m = *it;
    if (m[1] == "INOUT") {
      throw Error(fmt::format("{}: top {} has an inout port {}; the contract has none", d.name,
                              d.top, m[2].str()));
    }
    c.inputs[m[2]] = m[1] == "IN";
  }
  c.widths = declared_ports(d, mdir / fmt::format("V{}.h", d.top));
  return c;
}

// The ports Verilator found against the binding and the model's field formats (check_ports).
void check_contract(const RtlDesign& d, const PipelineModel& model, const Checked& c) {
  std::map<std::string, std::pair<bool, int>> actual;  // port -> (input, width)
  for (const auto& [name, input] : c.inputs) actual[name] = {input, c.widths.at(name)};
  struct Port {
    bool input;
    int width;
  };
  std::vector<std::pair<std::string, Port>> expected = {
      {"clk_i", {true, 1}},       {"rst_ni", {true, 1}},       {"in_valid_i", {true, 1}},
      {"in_ready_o", {false, 1}}, {"out_valid_o", {false, 1}}, {"out_ready_i", {true, 1}}};
  for (const PortBinding& b : d.ports) {
    int width = 0;
    for (const auto& name : b.fields) {
      const auto& fields = b.input ? model.inputs() : model.outputs();
      const auto f = std::find_if(fields.begin(), fields.end(),
                                  [&](const Field& x) { return x.name == name; });
      if (f == fields.end()) {
        throw Error(fmt::format("{}: port {} names unknown {} field '{}'", d.name, b.port,
                                b.input ? "input" : "output", name));
      }
      width += f->fmt.width();
    }
    expected.push_back({b.port, {b.input, width}});
  }
  for (const auto& [name, want] : expected) {
    const auto got = actual.find(name);
    if (got == actual.end()) {
      throw Error(fmt::format("{}: top {} has no port {} ({} [{}:0] expected)", d.name, d.top, name,
                              want.input ? "input" : "output", want.width - 1));
    }
    if (got->second.first != want.input) {
      throw Error(fmt::format("{}: port {} of {} is an {}, the contract says {}", d.name, name,
                              d.top, got->second.first ? "input" : "output",
                              want.input ? "input" : "output"));
    }
    if (got->second.second != want.width) {
      throw Error(
          fmt::format("{}: port {} of {} is {} bits wide, the contract says {} with these "
                      "parameters",
                      d.name, name, d.top, got->second.second, want.width));
    }
    actual.erase(got);
  }
  if (!actual.empty()) {
    throw Error(fmt::format("{}: top {} has a port the contract does not know: {}", d.name, d.top,
                            actual.begin()->first));
  }
}

// A design waiting for its build: what it is built from, as hashed before the build.
struct Pending {
  const RtlDesign* design = nullptr;
  Keyed keyed;
  std::vector<IncludedFile> includes;
  std::map<fs::path, FileStamp> stamps;  // every file it reads, as hashed
  std::map<std::string, int> widths;
  std::string key;
  std::string info;
  fs::path dir;  // where its plugin goes
};

// Checks a design's ports and learns what it includes; the record its plugin will carry.
Pending prepare(const RtlDesign& d, Keyed k, const PipelineModel& model) {
  Pending p;
  p.design = &d;
  const Checked c = verilate_interface(d);
  check_contract(d, model, c);
  p.widths = c.widths;
  const std::vector<fs::path> dirs = rtl_include_dirs(d.files);
  for (const HashedFile& f : k.files) p.stamps[f.path] = f.stamp;
  for (const auto& [path, stamp] : c.read) {
    if (p.stamps.contains(path)) continue;
    const HashedFile f = hash_file(path);
    p.stamps[path] = f.stamp;
    p.includes.push_back(locate_include(f, dirs));
  }
  p.key = full_key(k.base, p.includes);
  p.info = record_of(k, p.includes, p.widths);
  p.dir = plugin_dir(d, k.base, p.key);
  p.keyed = std::move(k);
  return p;
}

// After the build: Verilator read exactly the files that were hashed, unchanged (their stamps as
// Verilator saw them equal the stamps they had while hashed), and declared the ports checked.
// Otherwise nothing may be cached: Error naming the file.
void verify_build(const Pending& p, const fs::path& vdir, const fs::path& cwd) {
  const RtlDesign& d = *p.design;
  const std::map<fs::path, FileStamp> read = verilator_read(vdir, "V" + d.top, cwd);
  const auto changed = [&](const fs::path& f) {
    return Error(fmt::format(
        "{} changed while {} was being built (saved, checked out or touched): nothing was "
        "cached; run again once it is stable",
        f.string(), d.name));
  };
  for (const auto& [path, stamp] : read) {
    const auto it = p.stamps.find(path);
    if (it == p.stamps.end()) throw changed(path);
    if (it->second != stamp) throw changed(path);
  }
  for (const auto& [path, stamp] : p.stamps) {
    if (!read.contains(path)) throw changed(path);
  }
  if (declared_ports(d, vdir / fmt::format("V{}.h", d.top)) != p.widths) {
    throw Error(fmt::format("the ports of {} changed while it was being built: run again", d.name));
  }
}

std::string file_record(const fs::path& file, std::string_view name) {
  std::error_code ec;
  return fmt::format("file_hash {} {} {}\n", name, fs::file_size(file, ec), file_hash(file));
}

// One generated CMake project that builds every pending plugin (and the Verilator runtime they
// share, if it is missing or damaged) in parallel; each plugin is cached only if its build read
// what was hashed (verify_build).
void build_missing(const std::vector<Pending>& pending) {
  const fs::path cache = rtl_cache_dir();
  try {
    fs::create_directories(cache);
  } catch (const fs::filesystem_error& e) {
    throw Error(
        fmt::format("cannot create the RTL cache {}: {}", cache.string(), e.code().message()));
  }
  const std::string rkey = runtime_key();
  const fs::path runtime_dir = cache / ("runtime-" + rkey.substr(0, 16));
  bool have_runtime = fs::exists(runtime_dir / "info.txt");
  if (have_runtime) {
    const std::string problem =
        damage(runtime_dir, read_file(runtime_dir / "info.txt"), "libphongsim_verilated.so");
    if (!problem.empty()) {
      discard(runtime_dir);
      have_runtime = false;
    }
  }
  const OwnedTemp work(cache / "build.phongsim-tmp-", OwnedTemp::Kind::directory);
  const fs::path build_log = work.path() / "build.log";

  std::string lists = fmt::format(
      "cmake_minimum_required(VERSION 3.25)\nproject(phongsim_rtl CXX C)\n"
      "set(PHONGSIM_INCLUDE_DIR \"{}\")\ninclude(\"{}\")\nphongsim_find_rtl_tools()\n",
      include_root().string(), (data_root() / "cmake" / "PhongsimRtl.cmake").string());
  lists += have_runtime ? fmt::format("phongsim_import_verilator_runtime(runtime \"{}\")\n",
                                      (runtime_dir / "libphongsim_verilated.so").string())
                        : "phongsim_add_verilator_runtime(runtime)\n";
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const RtlDesign& d = *pending[i].design;
    const fs::path adapter = work.path() / fmt::format("adapter_{}.cpp", i);
    { std::ofstream(adapter) << adapter_source(d, pending[i].info); }
    std::vector<std::string> files, gflags;
    for (const HashedFile& f : pending[i].keyed.files) files.push_back(f.path.string());
    for (const RtlParam& p : d.params) gflags.push_back(fmt::format("-G{}={}", p.name, p.value));
    std::vector<std::string> args = verilator_flags(d);
    for (const std::string& inc : include_flags(d)) args.push_back(inc);
    // COVERAGE: the plugin compiles Verilator's coverage runtime in (the shared runtime has none).
    lists += fmt::format(
        "phongsim_add_rtl_plugin(plugin_{} TOP {} ADAPTER \"{}\" OUTPUT_DIR \"{}\" RUNTIME runtime "
        "RUNTIME_RPATH \"$ORIGIN/../{}\"{}\n  SOURCES{}\n  VERILATOR_ARGS{}{})\n",
        i, d.top, adapter.string(), (work.path() / fmt::format("out_{}", i)).string(),
        runtime_dir.filename().string(), d.coverage ? " COVERAGE" : "", cmake_list(files),
        cmake_list(gflags), cmake_list(args));
  }
  { std::ofstream(work.path() / "CMakeLists.txt") << lists; }
  const unsigned jobs = std::max(1U, std::thread::hardware_concurrency());
  const std::vector<std::vector<std::string>> steps = {
      {cmake_program(), "-S", work.path().string(), "-B", (work.path() / "b").string(), "-G",
       "Ninja", "-DCMAKE_BUILD_TYPE=Release",
       std::string("-DCMAKE_CXX_COMPILER=") + cxx_compiler()},
      {cmake_program(), "--build", (work.path() / "b").string(), "--parallel",
       std::to_string(jobs)},
  };
  for (const auto& step : steps) {
    if (run_process(step, build_log).exit_code != 0) {
      const fs::path kept = cache / "last-failed-build.log";
      std::error_code ec;
      fs::copy_file(build_log, kept, fs::copy_options::overwrite_existing, ec);
      const std::string text = read_file(build_log);
      std::string why = last_lines(text, 3);
      for (const char* mark : {"%Error", "error:"}) {
        if (const auto at = text.find(mark); at != std::string::npos) {
          const auto bol = text.rfind('\n', at);
          why = text.substr(bol == std::string::npos ? 0 : bol + 1);
          why = why.substr(0, why.find('\n'));
          break;
        }
      }
      std::string names;
      for (const Pending& p : pending) names += (names.empty() ? "" : ", ") + p.design->name;
      throw Error(
          fmt::format("building the RTL of {} failed: {} (log: {})", names, why, kept.string()));
    }
  }
  if (!have_runtime) {
    Staging r(runtime_dir);
    const fs::path lib = r.path() / "libphongsim_verilated.so";
    fs::copy_file(work.path() / "b" / "libphongsim_verilated.so", lib);
    std::ofstream(r.path() / "info.txt") << file_record(lib, "libphongsim_verilated.so");
    r.commit();
  }
  // Every plugin whose build read what was hashed is cached; then the first that did not is
  // reported.
  std::optional<Error> refused;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    const RtlDesign& d = *pending[i].design;
    try {
      verify_build(pending[i],
                   work.path() / "b" / "CMakeFiles" / fmt::format("plugin_{}.dir", i) /
                       fmt::format("V{}.dir", d.top),
                   work.path());
    } catch (const Error& e) {
      if (!refused) refused = e;
      continue;
    }
    Staging p(pending[i].dir);
    const fs::path plugin = p.path() / "plugin.so";
    fs::copy_file(work.path() / fmt::format("out_{}", i) / fmt::format("plugin_{}.so", i), plugin);
    std::ofstream(p.path() / "info.txt") << pending[i].info << file_record(plugin, "plugin.so");
    p.commit();
  }
  if (refused) throw *refused;
}

// The cached plugin of `d`, intact; otherwise (policy never) an Error saying why, or nothing
// (it is to be built; a damaged one has been moved out of the way, with a notice on `log`).
std::optional<RtlPlugin> usable_cached(const RtlDesign& d, const Keyed& k, RtlBuild policy,
                                       std::FILE* log) {
  const std::optional<Cached> c = find_cached(d, k);
  if (!c) {
    if (policy == RtlBuild::never) {
      throw Error(fmt::format(
          "the RTL of {} is not built for its current content and parameters ({}); build it "
          "with phongsim build-rtl, or drop --no-build",
          d.name, changed_since_last_build(d, k)));
    }
    return std::nullopt;
  }
  std::string problem = damage(c->dir, c->info, "plugin.so");
  const fs::path runtime = c->dir.parent_path() / ("runtime-" + runtime_key().substr(0, 16));
  if (problem.empty()) {
    problem = damage(runtime, read_file(runtime / "info.txt"), "libphongsim_verilated.so");
  }
  if (problem.empty()) return RtlPlugin{c->dir / "plugin.so", c->key, "cached"};
  if (policy == RtlBuild::never) {
    throw Error(fmt::format(
        "the cached plugin of {} is damaged ({}); drop --no-build to rebuild it", d.name, problem));
  }
  if (log != nullptr) {
    fmt::print(log, "phongsim: cached plugin of {} damaged ({}), rebuilding\n", d.name, problem);
  }
  discard(c->dir);
  return std::nullopt;
}

// Where a loaded plugin and the runtime it links lie in memory (their loadable segments).
std::vector<AddressRange> loaded_range(void* handle) {
  link_map* map = nullptr;
  if (dlinfo(handle, RTLD_DI_LINKMAP, &map) != 0 || map == nullptr) return {};
  struct Search {
    ElfW(Addr) plugin;
    std::vector<AddressRange> ranges;
  } search{map->l_addr, {}};
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        auto* s = static_cast<Search*>(data);
        const std::string_view name = info->dlpi_name != nullptr ? info->dlpi_name : "";
        if (info->dlpi_addr != s->plugin && name.find("libphongsim_verilated") == name.npos) {
          return 0;
        }
        AddressRange r{UINTPTR_MAX, 0};
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = info->dlpi_phdr[i];
          if (ph.p_type != PT_LOAD) continue;
          r.begin = std::min<std::uintptr_t>(r.begin, info->dlpi_addr + ph.p_vaddr);
          r.end = std::max<std::uintptr_t>(r.end, info->dlpi_addr + ph.p_vaddr + ph.p_memsz);
        }
        if (r.begin < r.end) s->ranges.push_back(r);
        return 0;
      },
      &search);
  return search.ranges;
}

}  // namespace

std::string verilator_gflags(std::span<const RtlParam> params) {
  std::string flags;
  for (const RtlParam& p : params) {
    flags += fmt::format("{}-G{}={}", flags.empty() ? "" : " ", p.name, p.value);
  }
  return flags;
}

std::vector<fs::path> rtl_files(std::span<const fs::path> paths) {
  std::vector<fs::path> files;
  for (const fs::path& p : paths) {
    if (fs::is_directory(p)) {
      std::vector<fs::path> in_dir;
      for (const auto& e : fs::directory_iterator(p)) {
        if (e.is_regular_file() && e.path().extension() == ".sv") in_dir.push_back(e.path());
      }
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else if (fs::is_regular_file(p)) {
      if (p.extension() != ".sv" && p.extension() != ".v") {
        throw Error(fmt::format("{}: not a SystemVerilog file (.sv or .v)", p.string()));
      }
      files.push_back(p);
    } else {
      throw Error(fmt::format("{}: no such file or folder", p.string()));
    }
  }
  if (files.empty()) throw Error("the RTL paths hold no .sv files");
  std::stable_partition(files.begin(), files.end(),
                        [](const fs::path& f) { return f.stem().string().ends_with("_pkg"); });
  // The same file given twice (also by two spellings of its path) is read once.
  std::vector<fs::path> unique;
  std::vector<fs::path> seen;
  for (const fs::path& f : files) {
    std::error_code ec;
    const fs::path canon = fs::weakly_canonical(fs::absolute(f), ec);
    if (std::find(seen.begin(), seen.end(), canon) != seen.end()) continue;
    seen.push_back(canon);
    unique.push_back(f);
  }
  return unique;
}

fs::path rtl_cache_dir() {
  if (const char* c = std::getenv("PHONGSIM_CACHE"); c != nullptr && *c != '\0') return c;
  return default_cache_dir();
}

std::map<std::string, int> check_ports(const RtlDesign& d, const PipelineModel& model) {
  const Checked c = verilate_interface(d);
  check_contract(d, model, c);
  return c.widths;
}

std::vector<RtlPlugin> build_rtl(std::span<const RtlDesign> designs,
                                 std::span<const PipelineModel* const> models, std::FILE* log) {
  std::vector<RtlPlugin> plugins(designs.size());
  std::vector<Pending> pending;
  std::vector<std::size_t> built_as(designs.size(), SIZE_MAX);  // index into pending
  std::map<std::string, std::size_t> queued;                    // base key -> pending
  for (std::size_t i = 0; i < designs.size(); ++i) {
    Keyed k = key_of(designs[i]);
    if (const auto c = usable_cached(designs[i], k, RtlBuild::if_missing, log)) {
      plugins[i] = *c;
      continue;
    }
    if (const auto q = queued.find(k.base); q != queued.end()) {  // same design twice: build once
      built_as[i] = q->second;
      continue;
    }
    // The port check first: a design it refuses is one line, with no notice of a build.
    const std::string why = changed_since_last_build(designs[i], k);
    queued[k.base] = pending.size();
    built_as[i] = pending.size();
    pending.push_back(prepare(designs[i], std::move(k), *models[i]));
    if (log != nullptr) {
      fmt::print(log, "phongsim: Verilating {} ({}; cached in {})\n", designs[i].name, why,
                 rtl_cache_dir().string());
      std::fflush(log);
    }
  }
  if (!pending.empty()) build_missing(pending);
  for (std::size_t i = 0; i < designs.size(); ++i) {
    if (built_as[i] == SIZE_MAX) continue;
    const Pending& p = pending[built_as[i]];
    plugins[i] = {p.dir / "plugin.so", p.key, "built now"};
  }
  return plugins;
}

RtlPlugin locate_rtl(const RtlDesign& design, const PipelineModel& model, RtlBuild policy,
                     std::FILE* log) {
  if (policy == RtlBuild::never) {
    if (auto c = usable_cached(design, key_of(design), policy, log)) return *c;
  }
  const PipelineModel* models[] = {&model};
  return build_rtl(std::span(&design, 1), models, log).front();
}

std::shared_ptr<RtlLibrary> RtlLibrary::load(const fs::path& path) {
  std::shared_ptr<RtlLibrary> lib(new RtlLibrary());
  lib->path_ = path;
  {
    // A plugin that crashes while it loads (a file truncated meanwhile) is named, not a SIGBUS.
    const CrashContext loading(fmt::format("loading the RTL plugin {}", path.string()));
    lib->handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  }
  if (lib->handle_ == nullptr) {
    throw Error(fmt::format("cannot load RTL plugin {}: {}", path.string(), dlerror()));
  }
  lib->crash_ = std::make_unique<CrashRegion>(loaded_range(lib->handle_),
                                              fmt::format("the RTL plugin {}", path.string()));
  const auto abi = reinterpret_cast<RtlAbiFn>(dlsym(lib->handle_, "phongsim_rtl_abi"));
  lib->info_ = reinterpret_cast<RtlInfoFn>(dlsym(lib->handle_, "phongsim_rtl_info"));
  lib->create_ = reinterpret_cast<RtlCreateFn>(dlsym(lib->handle_, "phongsim_rtl_create"));
  lib->x_seed_ = reinterpret_cast<void (*)(int)>(dlsym(lib->handle_, "phongsim_rtl_x_seed"));
  lib->coverage_ =
      reinterpret_cast<void (*)(const char*)>(dlsym(lib->handle_, "phongsim_rtl_coverage_prefix"));
  if (abi == nullptr || lib->info_ == nullptr || lib->create_ == nullptr ||
      abi() != kRtlPluginAbi) {
    throw Error(fmt::format("{} is not a phongsim RTL plugin of ABI {}; rebuild it", path.string(),
                            kRtlPluginAbi));
  }
  return lib;
}

std::shared_ptr<RtlLibrary> RtlLibrary::open(const RtlPlugin& plugin) {
  auto lib = load(plugin.path);
  if (info_field(lib->info_(), "key") != plugin.key) {
    throw Error(fmt::format("{} was built for key {}, not {}; remove it and rebuild",
                            plugin.path.string(), info_field(lib->info_(), "key"), plugin.key));
  }
  return lib;
}

std::shared_ptr<RtlLibrary> RtlLibrary::open_file(const fs::path& path, const RtlDesign& design) {
  auto lib = load(path);
  const std::string info = lib->info_();
  const Keyed k = key_of(design);
  if (info_field(info, "x_init") != info_field(k.head, "x_init") ||
      info_field(info, "coverage") != info_field(k.head, "coverage")) {
    throw Error(
        fmt::format("{} was built with --x-init random or --coverage; --rtl-plugin "
                    "takes a plugin of the default build (phongsim build-rtl)",
                    path.string()));
  }
  for (const char* field : {"top", "gflags"}) {
    if (info_field(info, field) != info_field(k.head, field)) {
      throw Error(fmt::format("{} was built with {} '{}', not '{}'", path.string(), field,
                              info_field(info, field), info_field(k.head, field)));
    }
  }
  // Every file it was compiled from, where it was then, must hold the same bytes now.
  std::vector<std::pair<std::string, fs::path>> sources;
  for (const std::string& line : info_lines(info, "file")) {
    const auto at = line.find(' ');
    sources.emplace_back(line.substr(0, at), line.substr(at + 1));
  }
  std::map<int, fs::path> dirs;
  for (const std::string& line : info_lines(info, "incdir")) {
    const auto at = line.find(' ');
    dirs[std::stoi(line.substr(0, at))] = line.substr(at + 1);
  }
  for (const std::string& line : info_lines(info, "include")) {
    const auto inc = parse_include(line);
    if (!inc || (inc->dir >= 0 && !dirs.contains(inc->dir))) {
      throw Error(
          fmt::format("{}: unreadable record of an included file; rebuild it", path.string()));
    }
    sources.emplace_back(inc->hash, inc->dir < 0 ? inc->rel : dirs[inc->dir] / inc->rel);
  }
  for (const auto& [hash, file] : sources) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec) || file_hash(file) != hash) {
      throw Error(
          fmt::format("{} was built from an older {} (changed or missing since); rebuild it",
                      path.string(), file.string()));
    }
  }
  return lib;
}

std::string RtlLibrary::verilator_extra() const { return info_field(info_(), "verilator_extra"); }

RtlLibrary::~RtlLibrary() {
  crash_.reset();
  if (handle_ != nullptr) dlclose(handle_);
}

DutPtr RtlLibrary::create(const PipelineModel& model, std::uint32_t x_seed,
                          const std::string& coverage_prefix) {
  // The ports' widths as built against the model's fields now: constants the RTL and the model
  // share (index and coordinate widths) must still agree.
  std::istringstream in(info_());
  std::map<std::string, int> built;
  struct Bound {
    std::string port;
    bool input = true;
    std::vector<std::string> fields;
  };
  std::vector<Bound> bound;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string kind, a, b;
    words >> kind >> a >> b;
    if (kind == "width") built[a] = std::stoi(b);
    if (kind == "port") {  // port input|output NAME FIELD...
      Bound p{b, a == "input", {}};
      for (std::string f; words >> f;) p.fields.push_back(f);
      bound.push_back(std::move(p));
    }
  }
  // An input and an output may share a name (a triangle's number in and out).
  for (const auto& [port, input, fields] : bound) {
    int width = 0;
    for (const auto& name : fields) {
      for (const Field& f : input ? model.inputs() : model.outputs()) {
        width += f.name == name ? f.fmt.width() : 0;
      }
    }
    if (const auto it = built.find(port); it != built.end() && it->second != width) {
      throw Error(fmt::format(
          "{}: port {} was built {} bits wide but the model's fields need {}: the RTL and the "
          "model disagree on a constant they share; rebuild after fixing one of them",
          path_.string(), port, it->second, width));
    }
  }
  if (x_seed_ != nullptr) {
    // Verilator seeds with an int, and 0 would mean "from the clock": not reproducible.
    if (x_seed == 0 || x_seed > 0x7fffffffU) {
      throw Error(fmt::format("x-init seed {} is out of range (1..2147483647)", x_seed));
    }
    x_seed_(static_cast<int>(x_seed));  // thread-local in the plugin: this thread's next DUT
  }
  if (!coverage_prefix.empty() && coverage_ == nullptr) {
    throw Error(fmt::format("{} was not built for coverage", path_.string()));
  }
  if (coverage_ != nullptr) coverage_(coverage_prefix.c_str());  // thread-local too
  try {
    auto dut = create_(model.inputs(), model.outputs());
    return DutPtr(dut.release(), DutDeleter{shared_from_this()});
  } catch (const std::runtime_error& e) {
    throw Error(fmt::format("{}: {}", path_.string(), e.what()));
  }
}

DutFactory rtl_duts(const RtlDesign& design, const PipelineModel& model, RtlBuild policy,
                    std::FILE* log, RtlPlugin* located, std::uint32_t x_seed,
                    const std::string& coverage_prefix) {
  const RtlPlugin plugin = locate_rtl(design, model, policy, log);
  if (located != nullptr) *located = plugin;
  auto library = RtlLibrary::open(plugin);
  // Bind once now (writing no coverage): a port/field disagreement is an error here.
  (void)library->create(model, x_seed);
  const PipelineModel* m = &model;  // must outlive the factory (rtl_plugin.h)
  return [library, m, x_seed, coverage_prefix]() {
    return library->create(*m, x_seed, coverage_prefix);
  };
}

}  // namespace phongsim
