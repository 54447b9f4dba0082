#pragma once
// One exception type for bad input: the message names the source (file, line or element) and the problem.
#include <stdexcept>
#include <string>

namespace pierce {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace pierce
