#pragma once
// main() of the benchmarks, written once: runs the benchmark and turns an exception into
// "error: <what>" on stderr and exit status 1.
#include <exception>
#include <iostream>

namespace pierce::bench {

template <class Run>
int guarded_main(int argc, char** argv, Run run) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace pierce::bench
