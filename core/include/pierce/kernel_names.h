#pragma once
// Kernel names for the front ends, with the one message for an unknown name (the kernels' own
// names and parser are kernel_name / parse_kernel in kernel.h).
#include <string>
#include <string_view>
#include <vector>

#include "pierce/kernel.h"

namespace pierce {

// The names of kAllKernels, and with include_double those of kDoubleKernels after them.
std::vector<std::string> kernel_names(bool include_double = false);

// "epsilon, embree-restart, ..." (kAllKernels), for messages and help texts.
std::string kernel_name_list();

// The kernel named `name`; throws std::invalid_argument "unknown kernel 'x' (expected one of: ...)"
// (Python's bindings raise it as ValueError).
KernelKind parse_kernel_or_throw(std::string_view name);

}  // namespace pierce
