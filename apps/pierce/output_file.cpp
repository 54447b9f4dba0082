#include "output_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "pierce/error.h"

namespace pierce::cli {

namespace fs = std::filesystem;

void OutputFile::check_target(const std::string& path, bool force) {
  if (path.empty()) return;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_directory(st)) throw InputError(path + ": is a directory");
  if (fs::is_regular_file(st) && !force)
    throw InputError(path + ": file exists; not overwriting it without --force");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent, ec))
    throw InputError(path + ": directory " + parent.string() + " does not exist");
}

OutputFile::OutputFile(std::string path, bool force) : path_(std::move(path)), force_(force) {
  if (path_.empty()) {
    file_ = stdout;
    return;
  }
  check_target(path_, force_);
  std::error_code ec;
  const bool direct = fs::exists(path_, ec) && !fs::is_regular_file(path_, ec);
  temp_ = direct ? std::string() : path_ + ".pierce-tmp-" + std::to_string(::getpid());
  file_ = std::fopen(direct ? path_.c_str() : temp_.c_str(), "wb");
  if (!file_) throw InputError(path_ + ": cannot write (" + std::strerror(errno) + ")");
}

OutputFile::~OutputFile() {
  if (file_ && file_ != stdout) std::fclose(file_);
  if (!committed_ && !temp_.empty()) std::remove(temp_.c_str());
}

void OutputFile::commit() {
  const bool failed = std::fflush(file_) != 0 || std::ferror(file_);
  const int saved_errno = errno;
  if (file_ == stdout) {
    if (failed) throw std::runtime_error(std::string("writing to stdout failed (") + std::strerror(saved_errno) + ")");
    committed_ = true;
    return;
  }
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || close_failed)
    throw std::runtime_error(path_ + ": write failed (" + std::strerror(failed ? saved_errno : errno) + ")");
  if (!temp_.empty()) {
    // The target may have appeared while we were working.
    check_target(path_, force_);
    if (std::rename(temp_.c_str(), path_.c_str()) != 0)
      throw std::runtime_error(path_ + ": cannot move the result into place (" + std::strerror(errno) + ")");
  }
  committed_ = true;
}

}  // namespace pierce::cli
