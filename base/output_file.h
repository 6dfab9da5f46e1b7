// Every file phongsim writes goes through here, so that an output is complete or absent, never
// half-written, and never replaces what it must not.
//
// OutputFile — one output. Where it goes depends on what the destination is:
//  - `-` is standard output; `/dev/stdout`, `/dev/stderr`, `/dev/fd/N` and `/proc/self/fd/N` are
//    that descriptor (whatever it is: a pipe, a terminal, a redirected file);
//  - a symbolic link is followed: its target is written (atomically, as below), the link stays;
//  - a regular file, or a name that does not exist yet, is written atomically: to a temporary
//    sibling `<path>.phongsim-tmp-XXXXXX` (base/temporaries.h) that commit() renames over it (an
//    existing file keeps its permissions); a failure before commit() leaves the destination as
//    it was;
//  - a FIFO or a character device (/dev/null, a terminal) is written in place, never replaced;
//  - a directory, block device or socket is refused.
// The descriptors, FIFOs and devices are streams: get() writes to them as the content comes (a
// FIFO is opened here, waiting for its reader), with no copy anywhere; what a failure leaves in a
// stream cannot be taken back. A writer that needs a path (a waveform, a figure drawn by another
// program) asks temp_path(): for a stream, a temporary file in the temp directory, copied into
// the stream by commit(). Opening checks the destination, so a command can refuse an
// unwritable output before its work.
//
// OutputSet — several files that belong together (a render, a sweep plan): complete or absent
// as a set, named by a manifest written last.
#pragma once

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/temporaries.h"

namespace phongsim {

class OutputFile {
 public:
  // Throws Error("cannot write <path>: <reason>").
  explicit OutputFile(std::filesystem::path path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  [[nodiscard]] std::FILE* get() const { return file_; }
  // A path to write the content to instead of get() (for writers that need one, e.g. a waveform
  // or a figure drawn by another program): the atomic temporary, or for a stream a temporary file
  // copied into it by commit().
  [[nodiscard]] const std::filesystem::path& temp_path();
  // The destination as given.
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  // True when the destination is this process's standard output (`-`, /dev/stdout, ...): a
  // command then prints its own messages to stderr.
  [[nodiscard]] bool is_stdout() const { return fd_ == 1; }

  void commit();  // throws Error when the data cannot be flushed or moved into place

 private:
  [[nodiscard]] bool stream() const { return fd_ >= 0 || in_place_; }

  std::filesystem::path path_;     // as given
  std::filesystem::path target_;   // symbolic links resolved (atomic and in-place kinds)
  std::optional<OwnedTemp> temp_;  // the atomic kind's sibling; a stream's temp_path() file
  std::FILE* file_ = nullptr;
  int fd_ = -1;             // written through this descriptor (stdout, /dev/fd/N)
  bool in_place_ = false;   // a FIFO or character device
  bool owns_file_ = false;  // file_ is ours to close (not stdout/stderr)
  bool committed_ = false;
  std::string claim_;  // this process's claim on the destination (no two outputs to one place)
};

// Whether two paths name the same destination (the same file, or both standard output); for
// refusing `--json X --trace X` or `--in v.csv --out v.csv` up front.
[[nodiscard]] bool same_destination(const std::filesystem::path& a, const std::filesystem::path& b);

// Throws Error("<option a> and <option b> name the same file <path>") when two of the named
// outputs (or an output and an input) are one destination. Empty paths are skipped.
void check_distinct(const std::vector<std::pair<std::string, std::filesystem::path>>& named);

// The same for a command's outputs among themselves and against each of its inputs (symbolic
// links and ".." resolved): an output may never replace what the command reads. Inputs are not
// compared with each other.
void check_outputs(const std::vector<std::pair<std::string, std::filesystem::path>>& outputs,
                   const std::vector<std::pair<std::string, std::filesystem::path>>& inputs);

// Files in one directory that appear together or not at all. add() opens each as an OutputFile
// (its temporary beside it, sub-directories made as needed); commit() renames them all into
// place and then writes DIR/manifest.json naming them ({"schema": "phongsim/1", "sets":
// {"<set>": [files...]}}). It also removes the files that the manifest listed under `replaces`
// (this set's earlier run, and what it makes stale) and this set no longer writes. Before
// commit() the directory is as it was; directories the set created are removed again.
class OutputSet {
 public:
  // `dir` is created if missing. `set` names this group in the manifest ("render", "sweep
  // plan"); `replaces` the groups it supersedes (itself included).
  OutputSet(std::filesystem::path dir, std::string set, std::vector<std::string> replaces);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Names the set and what it replaces later than construction (before commit()), for a set
  // whose name depends on the work done after its directory was checked.
  void rename(std::string set, std::vector<std::string> replaces) {
    set_ = std::move(set);
    replaces_ = std::move(replaces);
  }
  // A file of the set, `relative` to the directory. Error for a name given twice.
  OutputFile& add(const std::filesystem::path& relative);
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }
  // The set's files, relative, in the order added.
  [[nodiscard]] std::vector<std::filesystem::path> files() const;

  void commit();

 private:
  std::filesystem::path dir_;
  std::string set_;
  std::vector<std::string> replaces_;
  std::vector<std::pair<std::filesystem::path, std::unique_ptr<OutputFile>>> files_;
  std::vector<std::filesystem::path> created_dirs_;  // made by this set, deepest last
  std::vector<TempRegistration> created_registrations_;
  bool committed_ = false;
};

// The files a directory's manifest lists under `set` (relative paths; empty when none).
[[nodiscard]] std::vector<std::filesystem::path> manifest_files(const std::filesystem::path& dir,
                                                                std::string_view set);

}  // namespace phongsim
