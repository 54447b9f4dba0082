#pragma once
// An output file that never clobbers and never leaves half a result behind: refuses an existing
// regular file unless forced, writes to a temporary file next to the target and renames it into
// place on commit(). Without commit() (error, Ctrl-C) the temporary file is removed. Devices and
// pipes (e.g. /dev/null) are written directly. An empty path means stdout.
#include <cstdio>
#include <string>

namespace pierce::cli {

class OutputFile {
 public:
  // Throws InputError if `path` exists as a regular file and !force, or is a directory.
  static void check_target(const std::string& path, bool force);

  OutputFile(std::string path, bool force);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  std::FILE* stream() const { return file_; }
  // Flushes and moves the result into place; throws std::runtime_error on write errors.
  void commit();

 private:
  std::string path_, temp_;
  bool force_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

}  // namespace pierce::cli
