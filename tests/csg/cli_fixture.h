#pragma once
// A test fixture that runs the `pierce` executable (PIERCE_EXE) in a fresh temporary directory,
// for the CLI tests of shot, gqa, run and classify.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pierce::csgtest {

struct Outcome {
  int code = -1;
  std::string out, err;
};

class CliTest : public ::testing::Test {
 protected:
  // A directory per test (name prefix, pid, counter), so that tests may run in parallel.
  explicit CliTest(std::string prefix) : prefix_(std::move(prefix)) {}

  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = std::filesystem::temp_directory_path() /
           (prefix_ + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }

  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  // Runs `pierce ARGS` in the temporary directory.
  Outcome pierce(const std::string& args) const {
    const std::string out = path("stdout.txt"), err = path("stderr.txt");
    const std::string cmd = "cd '" + dir_.string() + "' && '" PIERCE_EXE "' " + args + " > '" + out + "' 2> '" + err + "'";
    const int status = std::system(cmd.c_str());
    Outcome r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read(out);
    r.err = read(err);
    return r;
  }

  // `pierce ARGS` fails as bad input (exit code 2) with `text` in its message.
  void expect_input_error(const std::string& args, const std::string& text) const {
    const Outcome r = pierce(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.err.find(text), std::string::npos) << args << " -> " << r.err;
  }

  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace pierce::csgtest
