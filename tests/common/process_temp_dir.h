#pragma once
// A temporary directory for the files one test program writes: named after the program and its
// process id (test programs run in parallel), created on first use and removed when the program
// ends.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace pierce::test {

// `prefix` names the program; every call must pass the same one.
inline const std::filesystem::path& process_temp_dir(const std::string& prefix) {
  // Removing it in a static's destructor runs after the last test, however the tests end.
  struct RemovedAtExit {
    std::filesystem::path dir;
    ~RemovedAtExit() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  };
  static const RemovedAtExit temp = [&] {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return RemovedAtExit{dir};
  }();
  return temp.dir;
}

}  // namespace pierce::test
