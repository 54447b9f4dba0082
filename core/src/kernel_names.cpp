#include "pierce/kernel_names.h"

#include <stdexcept>

namespace pierce {

std::vector<std::string> kernel_names(bool include_double) {
  std::vector<std::string> names;
  for (const KernelKind k : kAllKernels) names.emplace_back(kernel_name(k));
  if (include_double)
    for (const KernelKind k : kDoubleKernels) names.emplace_back(kernel_name(k));
  return names;
}

std::string kernel_name_list() {
  std::string s;
  for (const KernelKind k : kAllKernels) s += (s.empty() ? "" : ", ") + std::string(kernel_name(k));
  return s;
}

KernelKind parse_kernel_or_throw(std::string_view name) {
  if (const std::optional<KernelKind> k = parse_kernel(name)) return *k;
  throw std::invalid_argument("unknown kernel '" + std::string(name) + "' (expected one of: " + kernel_name_list() +
                              ")");
}

}  // namespace pierce
