// The RTL a user names, the way the RTL world names it: files and folders, file lists (-f, -F),
// include folders (+incdir+, -I) and defines (+define+, -D), as Verilator and the commercial
// simulators read them (docs/your-rtl.md, "File lists, include folders and defines").
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace phongsim {

// What the words name. Paths are as given or, inside a file list, resolved as the list says
// (relative to the list's folder for -F, to the current folder for -f).
struct RtlSources {
  std::vector<std::filesystem::path> files;         // SystemVerilog sources and folders, in order
  std::vector<std::filesystem::path> include_dirs;  // +incdir+ / -I, and folders of .svh given
  std::vector<std::string> defines;                 // NAME or NAME=VALUE, in order
  std::vector<std::filesystem::path> lists;         // the file lists read (inputs, not outputs)
};

// One word of an RTL description: a path (file or folder; a .svh/.vh header names its folder
// as an include folder), +incdir+DIR[+DIR...], +define+NAME[=VALUE][+...], -I DIR / -IDIR,
// -D NAME[=VALUE] / -DNAME, -f FILE, -F FILE. `words` is a sequence of them, the two-word forms
// as two words. In a file list: one or more per line, // and # comments, ${VAR} and $VAR taken
// from the environment, nested lists. Error naming the list and line for anything else (-v and
// -y libraries among it: list the files instead), a missing list, an undefined variable, or a
// list that includes itself.
// `where` names them in errors ("--rtl", "-D").
void add_rtl_words(std::span<const std::string> words, RtlSources& into,
                   const std::string& where = "--rtl");

// The file list `path` as -f (relative paths against the current folder) or -F (against the
// list's folder) reads it.
void add_file_list(const std::filesystem::path& path, bool relative_to_list, RtlSources& into);

}  // namespace phongsim
