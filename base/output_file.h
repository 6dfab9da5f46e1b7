// An output file that appears only when complete: written to a temporary sibling and renamed
// over the destination on commit(); removed if the program fails first. Opening it up front
// also checks early that the destination is writable.
#pragma once

#include <cstdio>
#include <filesystem>

namespace phongsim {

class OutputFile {
 public:
  // Throws Error("cannot write <path>: <reason>").
  explicit OutputFile(std::filesystem::path path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  [[nodiscard]] std::FILE* get() const { return file_; }
  // Where the content goes until commit (for writers that need a path, e.g. a waveform).
  [[nodiscard]] const std::filesystem::path& temp_path() const { return temp_; }

  void commit();  // throws Error when the data cannot be flushed or moved into place

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace phongsim
