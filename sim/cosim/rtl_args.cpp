#include "sim/cosim/rtl_args.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>

#include "base/error.h"

namespace phongsim {
namespace fs = std::filesystem;
namespace {

// Where words come from: the command line, or a line of a file list, and what a relative path
// there is relative to.
struct Origin {
  std::string where;           // "--rtl", "files.f:12"
  fs::path base;               // relative paths: against this folder (empty: the current one)
  std::vector<fs::path> open;  // the lists being read, outermost first (a list may not recurse)
};

fs::path resolved(const Origin& o, const std::string& p) {
  const fs::path path(p);
  return path.is_absolute() || o.base.empty() ? path : o.base / path;
}

[[noreturn]] void fail(const Origin& o, const std::string& what) {
  throw Error(fmt::format("{}: {}", o.where, what));
}

bool header(const fs::path& p) {
  const std::string e = p.extension().string();
  return e == ".svh" || e == ".vh" || e == ".h" || e == ".inc";
}

// NAME or NAME=VALUE with NAME a macro name.
std::string define_of(const Origin& o, const std::string& text) {
  static const std::regex name(R"([A-Za-z_][A-Za-z0-9_$]*)");
  const std::string n = text.substr(0, text.find('='));
  if (!std::regex_match(n, name)) fail(o, fmt::format("'{}' is not a macro name", n));
  return text;
}

void add_dir(const Origin& o, const std::string& d, RtlSources& into) {
  const fs::path dir = resolved(o, d);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(o, fmt::format("{}: no such include folder", dir.string()));
  into.include_dirs.push_back(dir);
}

void add_words(std::span<const std::string> words, const Origin& o, RtlSources& into);

void add_list(const fs::path& path, bool relative_to_list, Origin o, RtlSources& into) {
  std::error_code ec;
  const fs::path canon = fs::weakly_canonical(fs::absolute(path), ec);
  if (std::find(o.open.begin(), o.open.end(), canon) != o.open.end()) {
    fail(o, fmt::format("{} includes itself", path.string()));
  }
  std::ifstream in(path);
  if (!in || fs::is_directory(path, ec)) {
    fail(o, fmt::format("{}: cannot read the file list", path.string()));
  }
  into.lists.push_back(path);
  o.open.push_back(canon);
  o.base = relative_to_list ? (path.parent_path().empty() ? fs::path(".") : path.parent_path())
                            : fs::path();
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    o.where = fmt::format("{}:{}", path.string(), number);
    // Comments: // to the end of the line, and # where a word would begin.
    if (const auto c = line.find("//"); c != std::string::npos) line.erase(c);
    std::vector<std::string> words;
    std::size_t at = 0;
    while (true) {
      at = line.find_first_not_of(" \t\r", at);
      if (at == std::string::npos || line[at] == '#') break;
      std::string word;
      if (line[at] == '"') {
        const auto end = line.find('"', at + 1);
        if (end == std::string::npos) fail(o, "an unterminated \"");
        word = line.substr(at + 1, end - at - 1);
        at = end + 1;
      } else {
        const auto end = line.find_first_of(" \t\r", at);
        word = line.substr(at, end == std::string::npos ? end : end - at);
        at = end;
      }
      // $VAR and ${VAR} from the environment.
      static const std::regex var(R"(\$\{([A-Za-z_][A-Za-z0-9_]*)\}|\$([A-Za-z_][A-Za-z0-9_]*))");
      std::string expanded;
      std::smatch m;
      std::string rest = word;
      while (std::regex_search(rest, m, var)) {
        const std::string name = m[1].matched ? m[1].str() : m[2].str();
        const char* value = std::getenv(name.c_str());
        if (value == nullptr) fail(o, fmt::format("${} is not set in the environment", name));
        expanded += m.prefix().str() + value;
        rest = m.suffix().str();
      }
      words.push_back(expanded + rest);
      if (at == std::string::npos) break;
    }
    add_words(words, o, into);
  }
}

void add_words(std::span<const std::string> words, const Origin& o, RtlSources& into) {
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    const auto value = [&](std::string_view option) -> std::string {
      if (w.size() > option.size()) return w.substr(option.size());  // -IDIR, -DNAME
      if (i + 1 == words.size()) fail(o, fmt::format("{} needs a value", w));
      return words[++i];
    };
    if (w.starts_with("+incdir+")) {
      std::size_t at = 8;
      while (at < w.size()) {
        const auto end = w.find('+', at);
        const std::string d = w.substr(at, end == std::string::npos ? end : end - at);
        if (!d.empty()) add_dir(o, d, into);
        if (end == std::string::npos) break;
        at = end + 1;
      }
    } else if (w.starts_with("+define+")) {
      std::size_t at = 8;
      while (at < w.size()) {
        const auto end = w.find('+', at);
        const std::string d = w.substr(at, end == std::string::npos ? end : end - at);
        if (!d.empty()) into.defines.push_back(define_of(o, d));
        if (end == std::string::npos) break;
        at = end + 1;
      }
    } else if (w.starts_with("+")) {
      fail(o, fmt::format("{}: only +incdir+ and +define+ are read", w));
    } else if (w.starts_with("-I")) {
      add_dir(o, value("-I"), into);
    } else if (w.starts_with("-D")) {
      into.defines.push_back(define_of(o, value("-D")));
    } else if (w == "-f" || w == "-F") {
      add_list(resolved(o, value(w)), w == "-F", o, into);
    } else if (w == "-v" || w == "-y") {
      fail(o, fmt::format("{}: library files and folders are not read; list the files", w));
    } else if (w.starts_with("-")) {
      fail(o, fmt::format("{}: not a file, and not an option of a file list (-f, -F, -I, -D, "
                          "+incdir+, +define+)",
                          w));
    } else if (header(w)) {  // an `include'd file: its folder is searched
      const fs::path h = resolved(o, w);
      std::error_code ec;
      if (!fs::is_regular_file(h, ec)) fail(o, fmt::format("{}: no such file", h.string()));
      into.include_dirs.push_back(h.parent_path().empty() ? fs::path(".") : h.parent_path());
    } else {
      into.files.push_back(resolved(o, w));
    }
  }
}

}  // namespace

void add_rtl_words(std::span<const std::string> words, RtlSources& into, const std::string& where) {
  add_words(words, Origin{where, {}, {}}, into);
}

void add_file_list(const fs::path& path, bool relative_to_list, RtlSources& into) {
  add_list(path, relative_to_list, Origin{relative_to_list ? "-F" : "-f", {}, {}}, into);
}

}  // namespace phongsim
