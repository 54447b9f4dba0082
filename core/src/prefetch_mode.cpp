#include "pierce/prefetch_mode.h"

#include <cstdio>
#include <cstdlib>

namespace pierce {

namespace {

PrefetchMode from_environment() {
  const char* env = std::getenv("PIERCE_PREFETCH");
  if (env == nullptr || *env == '\0') return PrefetchMode::automatic;
  if (const auto mode = parse_enum<PrefetchMode>(env)) return *mode;
  std::fprintf(stderr, "pierce: ignoring PIERCE_PREFETCH=%s (expected %s)\n", env,
               enum_name_list<PrefetchMode>().c_str());
  return PrefetchMode::automatic;
}

}  // namespace

// Initialised when the library is loaded, before any traversal can run; until then (zero) it
// reads as `automatic`.
std::atomic<int> detail::g_prefetch_mode{int(from_environment())};

void set_prefetch_mode(PrefetchMode mode) { detail::g_prefetch_mode.store(int(mode), std::memory_order_relaxed); }

}  // namespace pierce
