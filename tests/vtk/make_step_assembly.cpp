// Writes the test STEP assembly (step_assembly.h) to the path given: the fixture of the pvbatch
// tests.
#include <exception>
#include <iostream>

#include "step_assembly.h"

int main(int argc, char** argv) {
  // An option (--help) is not a file to write.
  if (argc != 2 || argv[1][0] == '-') {
    std::cerr << "usage: " << argv[0] << " OUT.step\n";
    return 2;
  }
  try {
    pierce::test_models::write_step_assembly(argv[1]);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
