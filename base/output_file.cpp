#include "base/output_file.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "base/error.h"

namespace phongsim {

OutputFile::OutputFile(std::filesystem::path path) : path_(std::move(path)) {
  if (path_.empty()) throw Error("an output file name is empty");
  if (std::filesystem::is_directory(path_)) {
    throw Error(fmt::format("cannot write {}: it is a directory", path_.string()));
  }
  temp_ = path_;
  temp_ += fmt::format(".tmp.{}", getpid());
  file_ = std::fopen(temp_.c_str(), "wb");
  if (file_ == nullptr) {
    throw Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
  }
}

OutputFile::~OutputFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

void OutputFile::commit() {
  const bool ok = std::fflush(file_) == 0 && std::ferror(file_) == 0;
  const int err = errno;
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) throw Error(fmt::format("cannot write {}: {}", path_.string(), std::strerror(err)));
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec) throw Error(fmt::format("cannot write {}: {}", path_.string(), ec.message()));
  committed_ = true;
}

}  // namespace phongsim
