#include "pierce/simd/simd_level.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace pierce {

namespace {

SimdLevel detect() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_cpu_init();
  // libgcc's checks include the OS's XSAVE support for the wider registers.
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("fma") &&
      __builtin_cpu_supports("bmi2"))
    return SimdLevel::avx512;
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2"))
    return SimdLevel::avx2;
#endif
  return SimdLevel::scalar;
}

SimdLevel clamp(SimdLevel want) { return int(want) < int(best_simd_level()) ? want : best_simd_level(); }

SimdLevel from_environment() {
  const char* env = std::getenv("PIERCE_SIMD");
  if (env == nullptr || *env == '\0') return best_simd_level();
  if (const auto level = parse_simd_level(env)) return clamp(*level);
  std::fprintf(stderr, "pierce: ignoring PIERCE_SIMD=%s (expected scalar, avx2 or avx512)\n", env);
  return best_simd_level();
}

std::atomic<int>& current() {
  static std::atomic<int> level{int(from_environment())};
  return level;
}

}  // namespace

SimdLevel best_simd_level() {
  static const SimdLevel best = detect();
  return best;
}

SimdLevel simd_level() { return SimdLevel(current().load(std::memory_order_relaxed)); }

SimdLevel set_simd_level(SimdLevel level) {
  const SimdLevel set = clamp(level);
  current().store(int(set), std::memory_order_relaxed);
  return set;
}

std::string_view simd_level_name(SimdLevel level) {
  switch (level) {
    case SimdLevel::scalar: return "scalar";
    case SimdLevel::avx2: return "avx2";
    case SimdLevel::avx512: return "avx512";
  }
  return "?";
}

std::optional<SimdLevel> parse_simd_level(std::string_view name) {
  for (SimdLevel l : {SimdLevel::scalar, SimdLevel::avx2, SimdLevel::avx512})
    if (simd_level_name(l) == name) return l;
  return std::nullopt;
}

}  // namespace pierce
