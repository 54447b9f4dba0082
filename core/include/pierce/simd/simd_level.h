#pragma once
// Which SIMD code paths the wide-BVH kernels run: chosen once at run time from the CPU (one
// binary runs on any x86-64), overridable with the environment variable PIERCE_SIMD
// (scalar | avx2 | avx512) or set_simd_level(), e.g. to test every path on one machine.
#include <optional>
#include <string_view>

namespace pierce {

enum class SimdLevel : int { scalar = 0, avx2 = 1, avx512 = 2 };

// The best level this CPU (and OS) supports.
SimdLevel best_simd_level();
// The level in use: PIERCE_SIMD or set_simd_level(), clamped to best_simd_level().
SimdLevel simd_level();
// Sets the level in use (clamped to best_simd_level()); returns the level actually set.
SimdLevel set_simd_level(SimdLevel level);

std::string_view simd_level_name(SimdLevel level);
std::optional<SimdLevel> parse_simd_level(std::string_view name);

}  // namespace pierce
