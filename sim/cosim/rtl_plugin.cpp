#include "sim/cosim/rtl_plugin.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "base/error.h"
#include "base/file_util.h"
#include "base/paths.h"
#include "base/process.h"
#include "base/temporaries.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

// How every plugin is Verilated (part of its key). FST tracing is added by the CMake function.
const std::vector<std::string> kVerilatorFlags = {"--assert", "-Wno-fatal", "-O3", "-x-assign",
                                                  "fast",     "-x-initial", "fast"};
// The XInit::random variant: X assignments and power-up values drawn at run time.
const std::vector<std::string> kVerilatorFlagsXRandom = {
    "--assert", "-Wno-fatal", "-O3", "-x-assign", "unique", "-x-initial", "unique"};

// $PHONGSIM_VERILATOR_FLAGS: extra Verilator arguments, split at white space, appended to every
// plugin's (so part of its key), e.g. "--threads 2" or "-CFLAGS -march=native"; how the defaults
// were chosen is in docs/performance.md.
// Arguments that would change the design itself (parameters, macros, sources, the top) are
// refused: those come from the configuration and --rtl, and a verdict must describe them.
std::vector<std::string> extra_verilator_flags() {
  std::vector<std::string> flags;
  const char* env = std::getenv("PHONGSIM_VERILATOR_FLAGS");
  std::istringstream words(env ? env : "");
  bool value = false;  // the word after -CFLAGS or -LDFLAGS is the compiler's, not Verilator's
  for (std::string w; words >> w;) {
    const bool design =
        !value && (w.starts_with("-G") || w.starts_with("-pvalue") || w.starts_with("+define+") ||
                   w.starts_with("-D") || w.starts_with("+incdir+") || w.starts_with("-I") ||
                   w == "-f" || w == "-F" || w == "-v" || w == "-y" || w.starts_with("--top") ||
                   w.ends_with(".sv") || w.ends_with(".v") || w.ends_with(".svh"));
    if (design) {
      throw Error(fmt::format(
          "PHONGSIM_VERILATOR_FLAGS: {} would change the design (its parameters, macros, sources "
          "and top come from the configuration and --rtl)",
          w));
    }
    value = !value && (w == "-CFLAGS" || w == "-LDFLAGS");
    flags.push_back(w);
  }
  return flags;
}

std::vector<std::string> verilator_flags(const RtlDesign& d) {
  std::vector<std::string> flags =
      d.x_init == XInit::random ? kVerilatorFlagsXRandom : kVerilatorFlags;
  // The coverage variant: Verilator's line (and branch) points, and toggle points if asked.
  if (d.coverage) flags.emplace_back("--coverage-line");
  if (d.coverage && d.coverage_toggle) flags.emplace_back("--coverage-toggle");
  const std::vector<std::string> extra = extra_verilator_flags();
  flags.insert(flags.end(), extra.begin(), extra.end());
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

std::string file_hash(const fs::path& file) {
  ContentHash h;
  h.add(read_file(file));
  return h.hex();
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

struct Keyed {
  std::string key;
  std::string info;     // what the plugin records about itself (its manifest)
  std::string adapter;  // the generated adapter's source
};

std::string runtime_key() {
  ContentHash h;
  h.add(fmt::format("phongsim verilated runtime, abi {}", kRtlPluginAbi));
  h.add(tool_version("verilator"));
  h.add(tool_version(cxx_compiler()));
  h.add(read_file(data_root() / "cmake" / "PhongsimRtl.cmake"));
  return h.hex();
}

Keyed key_of(const RtlDesign& d) {
  for (const fs::path& f : d.files) {
    if (!fs::is_regular_file(f)) throw Error(fmt::format("{}: no such RTL file", f.string()));
  }
  ContentHash h;
  h.add(fmt::format("phongsim rtl plugin, abi {}", kRtlPluginAbi));
  h.add(runtime_key());
  for (const auto& f : verilator_flags(d)) h.add(f);
  h.add(d.top);
  const std::string gflags = verilator_gflags(d.params);
  h.add(gflags);
  h.add(ports_text(d));
  std::string files;
  for (const fs::path& f : d.files) {
    const std::string hash = file_hash(f);
    h.add(f.filename().string());
    h.add(hash);
    files += fmt::format("file {} {}\n", hash, fs::absolute(f).lexically_normal().string());
  }
  for (const fs::path& header : adapter_headers()) {
    h.add(header.string());
    h.add(read_file(include_root() / header));
  }
  Keyed k;
  // The key covers the adapter too; its text embeds the key, so hash what precedes it.
  h.add(adapter_source(d, ""));
  k.key = h.hex();
  std::string extra;
  for (const auto& f : extra_verilator_flags()) extra += (extra.empty() ? "" : " ") + f;
  k.info =
      fmt::format("key {}\nname {}\ntop {}\ngflags {}\n{}{}{}{}{}", k.key, d.name, d.top, gflags,
                  d.x_init == XInit::random ? "x_init random\n" : "",
                  !d.coverage         ? ""
                  : d.coverage_toggle ? "coverage line toggle\n"
                                      : "coverage line\n",
                  extra.empty() ? "" : "verilator_extra " + extra + "\n", ports_text(d), files);
  k.adapter = adapter_source(d, k.info);
  return k;
}

std::string info_field(const std::string& info, std::string_view field) {
  std::istringstream in(info);
  std::string line;
  const std::string prefix = std::string(field) + " ";
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  }
  return "";
}

// A directory renamed into place only when complete: removed if the build fails first, or
// if a signal ends phongsim (base/temporaries.h; a stale one is swept at the next start).
class TempDir {
 public:
  explicit TempDir(fs::path final_path)
      : final_(std::move(final_path)),
        temp_(final_.string() + temp_suffix()),
        registration_(temp_) {
    fs::remove_all(temp_);
    fs::create_directories(temp_);
  }
  ~TempDir() {
    std::error_code ec;
    if (!temp_.empty()) fs::remove_all(temp_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const fs::path& path() const { return temp_; }
  // Atomic publish; when another process published the same content first, theirs stays.
  void commit() {
    std::error_code ec;
    fs::rename(temp_, final_, ec);
    if (ec) fs::remove_all(temp_, ec);
    temp_.clear();
  }

 private:
  fs::path final_;
  fs::path temp_;
  TempRegistration registration_;
};

std::string cmake_list(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += fmt::format(" \"{}\"", i);
  return s;
}

fs::path plugin_dir(const RtlDesign& d, const std::string& key) {
  return rtl_cache_dir() / fmt::format("{}-{}", d.name, key);
}

// A file of a build's info as "<content hash> <file name>": the same file in another copy of the
// tree (another absolute path) has not changed.
std::set<std::string> info_files(const std::string& info) {
  std::set<std::string> files;
  std::istringstream in(info);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("file ", 0) != 0) continue;
    const auto path_at = line.find(' ', 5);
    files.insert(line.substr(5, path_at - 5) + " " +
                 fs::path(line.substr(path_at + 1)).filename().string());
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
  const std::set<std::string> now = info_files(k.info);
  const std::string extra = info_field(k.info, "verilator_extra");
  for (const auto& e : fs::directory_iterator(rtl_cache_dir(), ec)) {
    const fs::path info = e.path() / "info.txt";
    if (e.path().filename().string().rfind(d.name + "-", 0) != 0 || !fs::exists(info)) continue;
    const std::string text = read_file(info);
    if (info_field(text, "top") != d.top ||
        info_field(text, "gflags") != info_field(k.info, "gflags") ||
        info_field(text, "x_init") != info_field(k.info, "x_init") ||
        info_field(text, "coverage") != info_field(k.info, "coverage"))
      continue;
    if (info_files(text) == now && info_field(text, "verilator_extra") != extra) {
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
  if (list.empty()) return "phongsim's plugin code or the tools changed";
  return "changed since the last build: " + list;
}

// One generated CMake project that builds every missing plugin (and the Verilator runtime they
// share, if it is missing too) in parallel.
void build_missing(const std::vector<const RtlDesign*>& designs, const std::vector<Keyed>& keys) {
  const fs::path cache = rtl_cache_dir();
  try {
    fs::create_directories(cache);
  } catch (const fs::filesystem_error& e) {
    throw Error(
        fmt::format("cannot create the RTL cache {}: {}", cache.string(), e.code().message()));
  }
  const std::string rkey = runtime_key();
  const fs::path runtime_dir = cache / ("runtime-" + rkey);
  const bool have_runtime = fs::exists(runtime_dir / "libphongsim_verilated.so");
  TempDir work(cache / "build");
  const fs::path build_log = work.path() / "build.log";

  std::string lists = fmt::format(
      "cmake_minimum_required(VERSION 3.25)\nproject(phongsim_rtl CXX C)\n"
      "set(PHONGSIM_INCLUDE_DIR \"{}\")\ninclude(\"{}\")\nphongsim_find_rtl_tools()\n",
      include_root().string(), (data_root() / "cmake" / "PhongsimRtl.cmake").string());
  lists += have_runtime ? fmt::format("phongsim_import_verilator_runtime(runtime \"{}\")\n",
                                      (runtime_dir / "libphongsim_verilated.so").string())
                        : "phongsim_add_verilator_runtime(runtime)\n";
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const RtlDesign& d = *designs[i];
    const fs::path adapter = work.path() / fmt::format("adapter_{}.cpp", i);
    { std::ofstream(adapter) << keys[i].adapter; }
    std::vector<std::string> files, gflags;
    for (const fs::path& f : d.files) files.push_back(fs::absolute(f).string());
    for (const RtlParam& p : d.params) gflags.push_back(fmt::format("-G{}={}", p.name, p.value));
    // COVERAGE: the plugin compiles Verilator's coverage runtime in (the shared runtime has none).
    lists += fmt::format(
        "phongsim_add_rtl_plugin(plugin_{} TOP {} ADAPTER \"{}\" OUTPUT_DIR \"{}\" RUNTIME runtime "
        "RUNTIME_RPATH \"$ORIGIN/../runtime-{}\"{}\n  SOURCES{}\n  VERILATOR_ARGS{}{})\n",
        i, d.top, adapter.string(), (work.path() / fmt::format("out_{}", i)).string(), rkey,
        d.coverage ? " COVERAGE" : "", cmake_list(files), cmake_list(gflags),
        cmake_list(verilator_flags(d)));
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
      for (const RtlDesign* d : designs) names += (names.empty() ? "" : ", ") + d->name;
      throw Error(
          fmt::format("building the RTL of {} failed: {} (log: {})", names, why, kept.string()));
    }
  }
  if (!have_runtime) {
    TempDir r(runtime_dir);
    fs::copy_file(work.path() / "b" / "libphongsim_verilated.so",
                  r.path() / "libphongsim_verilated.so");
    r.commit();
  }
  for (std::size_t i = 0; i < designs.size(); ++i) {
    TempDir p(plugin_dir(*designs[i], keys[i].key));
    fs::copy_file(work.path() / fmt::format("out_{}", i) / fmt::format("plugin_{}.so", i),
                  p.path() / "plugin.so");
    std::ofstream(p.path() / "info.txt") << keys[i].info;
    p.commit();
  }
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
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

fs::path rtl_cache_dir() {
  if (const char* c = std::getenv("PHONGSIM_CACHE"); c != nullptr && *c != '\0') return c;
  return default_cache_dir();
}

std::map<std::string, int> check_ports(const RtlDesign& d, const PipelineModel& model) {
  const fs::path dir =
      fs::temp_directory_path() / fmt::format("phongsim-ports-{}-{}", getpid(), d.top);
  const TempRegistration registration(dir);
  fs::remove_all(dir);
  const std::shared_ptr<void> cleanup(nullptr, [dir](void*) {
    std::error_code ec;
    fs::remove_all(dir, ec);
  });
  std::vector<std::string> argv{"verilator", "--cc",  "-Wno-fatal", "--top-module",
                                d.top,       "-Mdir", dir.string()};
  for (const RtlParam& p : d.params) argv.push_back(fmt::format("-G{}={}", p.name, p.value));
  for (const fs::path& f : d.files) argv.push_back(f.string());
  const ProcessResult r = run_process(argv);
  if (r.exit_code != 0) {
    std::string first = r.out;
    if (const auto at = r.out.find("%Error"); at != std::string::npos) first = r.out.substr(at);
    first = first.substr(0, first.find('\n'));
    throw Error(fmt::format("Verilator cannot read the RTL of {} (top {}): {}", d.name, d.top,
                            first.empty() ? "exit " + std::to_string(r.exit_code) : first));
  }
  // The Verilated class declares each port as VL_IN*/VL_OUT*(&name, msb, lsb).
  struct Port {
    bool input;
    int width;
  };
  std::map<std::string, Port> actual;
  static const std::regex decl(R"(VL_(IN|OUT|INOUT)\w*\(&(\w+),(\d+),(\d+))");
  const std::string header = read_file(dir / fmt::format("V{}.h", d.top));
  for (auto it = std::sregex_iterator(header.begin(), header.end(), decl);
       it != std::sregex_iterator(); ++it) {
    const auto& m = *it;
    if (m[1] == "INOUT") {
      throw Error(fmt::format("{}: top {} has an inout port {}; the contract has none", d.name,
                              d.top, m[2].str()));
    }
    actual[m[2]] = {m[1] == "IN", std::stoi(m[3]) - std::stoi(m[4]) + 1};
  }
  std::map<std::string, int> widths;
  for (const auto& [name, port] : actual) widths[name] = port.width;
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
    if (got->second.input != want.input) {
      throw Error(fmt::format("{}: port {} of {} is an {}, the contract says {}", d.name, name,
                              d.top, got->second.input ? "input" : "output",
                              want.input ? "input" : "output"));
    }
    if (got->second.width != want.width) {
      throw Error(
          fmt::format("{}: port {} of {} is {} bits wide, the contract says {} with these "
                      "parameters",
                      d.name, name, d.top, got->second.width, want.width));
    }
    actual.erase(got);
  }
  if (!actual.empty()) {
    throw Error(fmt::format("{}: top {} has a port the contract does not know: {}", d.name, d.top,
                            actual.begin()->first));
  }
  return widths;
}

std::vector<RtlPlugin> build_rtl(std::span<const RtlDesign> designs,
                                 std::span<const PipelineModel* const> models, std::FILE* log) {
  std::vector<RtlPlugin> plugins(designs.size());
  std::vector<const RtlDesign*> missing;
  std::vector<Keyed> missing_keys;
  std::set<std::string> queued;
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const Keyed k = key_of(designs[i]);
    plugins[i] = {plugin_dir(designs[i], k.key) / "plugin.so", k.key, "cached"};
    if (fs::exists(plugins[i].path)) continue;
    plugins[i].origin = "built now";
    if (!queued.insert(k.key).second) continue;  // same design twice: build once
    Keyed built = k;
    // The port widths as built, so a model that later disagrees is refused when it loads this.
    for (const auto& [port, width] : check_ports(designs[i], *models[i])) {
      built.info += fmt::format("width {} {}\n", port, width);
    }
    built.adapter = adapter_source(designs[i], built.info);
    if (log != nullptr) {
      fmt::print(log, "phongsim: Verilating {} ({}; cached in {})\n", designs[i].name,
                 changed_since_last_build(designs[i], k), rtl_cache_dir().string());
      std::fflush(log);
    }
    missing.push_back(&designs[i]);
    missing_keys.push_back(built);
  }
  if (!missing.empty()) build_missing(missing, missing_keys);
  return plugins;
}

RtlPlugin locate_rtl(const RtlDesign& design, const PipelineModel& model, RtlBuild policy,
                     std::FILE* log) {
  if (policy == RtlBuild::never) {
    const Keyed k = key_of(design);
    const fs::path path = plugin_dir(design, k.key) / "plugin.so";
    if (!fs::exists(path)) {
      throw Error(fmt::format(
          "the RTL of {} is not built for its current content and parameters ({}); build it "
          "with phongsim build-rtl, or drop --no-build",
          design.name, changed_since_last_build(design, k)));
    }
    return {path, k.key, "cached"};
  }
  const PipelineModel* models[] = {&model};
  return build_rtl(std::span(&design, 1), models, log).front();
}

std::shared_ptr<RtlLibrary> RtlLibrary::load(const fs::path& path) {
  std::shared_ptr<RtlLibrary> lib(new RtlLibrary());
  lib->path_ = path;
  lib->handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (lib->handle_ == nullptr) {
    throw Error(fmt::format("cannot load RTL plugin {}: {}", path.string(), dlerror()));
  }
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
  if (info_field(info, "x_init") != info_field(k.info, "x_init") ||
      info_field(info, "coverage") != info_field(k.info, "coverage")) {
    throw Error(
        fmt::format("{} was built with --x-init random or --coverage; --rtl-plugin "
                    "takes a plugin of the default build (phongsim build-rtl)",
                    path.string()));
  }
  for (const char* field : {"top", "gflags"}) {
    if (info_field(info, field) != info_field(k.info, field)) {
      throw Error(fmt::format("{} was built with {} '{}', not '{}'", path.string(), field,
                              info_field(info, field), info_field(k.info, field)));
    }
  }
  std::istringstream in(info);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("file ", 0) != 0) continue;
    const std::string hash = line.substr(5, line.find(' ', 5) - 5);
    const fs::path file = line.substr(line.find(' ', 5) + 1);
    if (!fs::exists(file) || file_hash(file) != hash) {
      throw Error(
          fmt::format("{} was built from an older {} (changed or missing since); rebuild it",
                      path.string(), file.string()));
    }
  }
  return lib;
}

RtlLibrary::~RtlLibrary() {
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
