#include "sim/cosim/rtl_flags.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <regex>
#include <sstream>

#include "base/error.h"

namespace phongsim {
namespace {

// Verilator options (one dash, as Verilator also reads two) that take a count and change only
// how the C++ is generated, compiled or traced.
constexpr std::array<std::string_view, 15> kCountOptions = {"-threads",
                                                            "-threads-max-mvtasks",
                                                            "-output-split",
                                                            "-output-split-cfuncs",
                                                            "-output-split-ctrace",
                                                            "-unroll-count",
                                                            "-unroll-stmts",
                                                            "-inline-mult",
                                                            "-reloop-limit",
                                                            "-build-jobs",
                                                            "-verilate-jobs",
                                                            "-trace-depth",
                                                            "-trace-max-array",
                                                            "-trace-max-width",
                                                            "-trace-threads"};

// Options without a value that change only the C++ or the waveform's detail.
constexpr std::array<std::string_view, 4> kPlainOptions = {"-trace-structs", "-trace-params",
                                                           "-trace-underscore", "-Wall"};

// Options a user might reach for that change the simulation's semantics, with what to use.
std::string_view semantics(std::string_view option) {
  if (option == "-x-assign" || option == "-x-initial" || option == "-x-initial-edge") {
    return "it changes how X values simulate (phongsim's --x-init chooses them)";
  }
  if (option == "-no-assert" || option == "-assert") {
    return "the RTL's assertions are part of every check";
  }
  if (option.starts_with("-G") || option.starts_with("-pvalue") || option.starts_with("-D") ||
      option.starts_with("-U") || option.starts_with("-I") || option == "-y" || option == "-v" ||
      option == "-f" || option == "-F" || option.starts_with("-top") || option == "-exe" ||
      option.starts_with("-prefix") || option == "-Mdir" || option == "-o" || option == "-cc" ||
      option == "-sc" || option == "-lib-create" || option.starts_with("-l")) {
    return "it would change the design (its parameters, macros, sources and top come from the "
           "configuration and --rtl)";
  }
  return "";
}

// A compiler flag (the value of -CFLAGS or -LDFLAGS) from a list of flags that change only how
// the plugin's C++ is optimized, debugged or linked: never a define, an include, a file, a
// plugin, a profile, or a flag that changes what the C++ means (-ffast-math, -fwrapv, ...).
bool compiler_flag_allowed(const std::string& flag) {
  static const std::regex allowed(
      R"(-O[0-3sg]?|-g[0-3]?|-pipe|-s|-march=[A-Za-z0-9_.-]+|-mtune=[A-Za-z0-9_.-]+|)"
      R"(-fno-plt|-f(no-)?omit-frame-pointer|-f(no-)?lto|-flto=(auto|[0-9]+)|)"
      R"(-f(no-)?unroll-loops|-f(no-)?tree-vectorize|-f(no-)?inline-functions|)"
      R"(-fno-semantic-interposition|-f(no-)?stack-protector(-strong|-all)?|)"
      R"(-frandom-seed=[A-Za-z0-9_.-]+|-fuse-ld=(bfd|gold|lld|mold)|-W(no-)?[a-z][a-z0-9-]*)");
  return std::regex_match(flag, allowed);
}

bool digits(const std::string& s) {
  return !s.empty() && s.size() <= 9 &&
         std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::vector<std::string> verilator_extra_flags(std::string_view text) {
  std::istringstream in{std::string(text)};
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  std::vector<std::string> flags;
  const auto refuse = [](const std::string& arg, std::string_view why) {
    return Error(fmt::format("PHONGSIM_VERILATOR_FLAGS: {} is refused: {}", arg, why));
  };
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (w.starts_with("+")) {
      throw refuse(w, "a + option (+define+, +incdir+, ...) would change the design");
    }
    if (!w.starts_with("-") || w == "-" || w == "--") {
      throw refuse(w, "not an option: sources come from --rtl and the configuration");
    }
    // Verilator reads --name as -name.
    const std::string option = w.starts_with("--") ? w.substr(1) : w;
    if (const std::string_view why = semantics(option.substr(0, option.find('='))); !why.empty()) {
      throw refuse(w, why);
    }
    if (option.find('=') != std::string::npos) {
      throw refuse(w, "give the value as the next word (--threads 2)");
    }
    static const std::regex optimization(R"(-O([0-3]|[A-Za-z]+)|-f(no-)?[a-z][a-z0-9-]*)");
    static const std::regex warning(R"(-W(no-|warn-|error-)?[A-Za-z][A-Za-z0-9_-]*)");
    if (std::regex_match(option, optimization) || std::regex_match(option, warning) ||
        std::find(kPlainOptions.begin(), kPlainOptions.end(), option) != kPlainOptions.end()) {
      flags.push_back(w);
      continue;
    }
    if (std::find(kCountOptions.begin(), kCountOptions.end(), option) != kCountOptions.end()) {
      if (i + 1 == words.size() || !digits(words[i + 1])) {
        throw refuse(w, "it takes a count (e.g. " + w + " 2)");
      }
      flags.push_back(w);
      flags.push_back(words[++i]);
      continue;
    }
    if (option == "-CFLAGS" || option == "-LDFLAGS") {
      if (i + 1 == words.size() || !compiler_flag_allowed(words[i + 1])) {
        throw refuse(
            fmt::format("{} {}", w, i + 1 == words.size() ? "" : words[i + 1]),
            "only compiler optimization and debugging flags (-O2, -march=native, -fno-plt, "
            "-g, ...): defines, include folders, files, linker options and flags that change "
            "what the C++ means could change what is simulated");
      }
      flags.push_back(w);
      flags.push_back(words[++i]);
      continue;
    }
    throw refuse(w,
                 "not on the list of options known to leave the design unchanged "
                 "(docs/cosim.md#rtl-builds-keyed-by-what-was-compiled)");
  }
  return flags;
}

std::vector<std::string> verilator_env_flags() {
  const char* env = std::getenv("PHONGSIM_VERILATOR_FLAGS");
  return verilator_extra_flags(env != nullptr ? env : "");
}

}  // namespace phongsim
