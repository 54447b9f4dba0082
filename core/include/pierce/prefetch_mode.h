#pragma once
// Whether the wide-BVH traversal prefetches the children it is going to visit (traverse.h).
// Where the BVH stays in the caches a prefetch is only work; where it outgrows them, it hides the
// latency. `automatic` (the default) decides by the BVH's size (prefetches_by_size); `always` and
// `never` force it either way, so that a bench can measure both on the same scene
// (pierce_bench_kernels --prefetch) and the tests run the prefetching loop on small scenes too.
// Chosen once from the environment variable PIERCE_PREFETCH (auto | always | never), or set with
// set_prefetch_mode(). It changes the time a traversal takes, never what it finds.
#include <atomic>
#include <cstddef>

#include "pierce/enum_names.h"

namespace pierce {

enum class PrefetchMode : int { automatic = 0, always = 1, never = 2 };
constexpr EnumTable<PrefetchMode, 3> enum_table(PrefetchMode) {
  using enum PrefetchMode;
  return {"prefetch mode", {{automatic, "auto"}, {always, "always"}, {never, "never"}}};
}

namespace detail {
// The mode in use, read by every traversal (one relaxed load, inline: no call per traversal).
extern std::atomic<int> g_prefetch_mode;
}  // namespace detail

// The mode in use: PIERCE_PREFETCH or set_prefetch_mode(); `automatic` if neither says otherwise.
inline PrefetchMode prefetch_mode() { return PrefetchMode(detail::g_prefetch_mode.load(std::memory_order_relaxed)); }
// Sets the mode for every traversal that starts after it, on every thread.
void set_prefetch_mode(PrefetchMode mode);

// The automatic choice for a BVH of `bvh_bytes` (WideBvh::memory_bytes): prefetch beyond 16 MiB
// depth first, beyond 8 MiB breadth first (`any_order`: the node processed next is the one asked
// for longest ago, so more of each prefetch's latency is hidden and it pays on smaller BVHs).
// `pierce_bench_kernels --prefetch always,never` on a Zen 4 (1 MB L2) shows the prefetch costing up
// to 8 % on CGAL's meshes and blob (up to 5.2 MiB) and up to 22 % on hairball (6.3 MiB), and paying
// up to 35 % on blob at 7 and 8 subdivisions (19.6 and 79.7 MiB, `--blob-subdivisions`) and on the
// shell (99.7 MiB); depth first, the bound lies somewhere between 6.3 and 19.6 MiB. Fixed sizes
// rather than the cache sizes: a VM cannot report those reliably at run time.
inline bool prefetches_by_size(std::size_t bvh_bytes, bool any_order) {
  constexpr std::size_t kMiB = std::size_t(1) << 20;
  return bvh_bytes > (any_order ? 8 : 16) * kMiB;
}

// Whether a traversal of a BVH of `bvh_bytes` prefetches, in the mode in use.
inline bool prefetches(std::size_t bvh_bytes, bool any_order) {
  switch (prefetch_mode()) {
    case PrefetchMode::always: return true;
    case PrefetchMode::never: return false;
    case PrefetchMode::automatic: break;
  }
  return prefetches_by_size(bvh_bytes, any_order);
}

}  // namespace pierce
