#pragma once
// Traversal counters (Gribble 2016): compiled in only with -DPIERCE_COUNTERS=ON.
#include <cstdint>

namespace pierce {

struct Counters {
  std::uint64_t node_tests = 0;       // ray/box tests
  std::uint64_t traversal_steps = 0;  // nodes popped and processed
  std::uint64_t prim_tests = 0;       // ray/triangle tests
  std::uint64_t valid_hits = 0;       // triangle tests that hit inside the active range
  std::uint64_t leaf_visits = 0;      // leaves among traversal_steps (the rest are inner nodes)
  Counters& operator+=(const Counters& o) {
    node_tests += o.node_tests, traversal_steps += o.traversal_steps, leaf_visits += o.leaf_visits;
    prim_tests += o.prim_tests, valid_hits += o.valid_hits;
    return *this;
  }
};

#ifdef PIERCE_WITH_COUNTERS
inline constexpr bool kCountersEnabled = true;
#define PIERCE_COUNT(c, field, n) ((c).field += (n))
#else
inline constexpr bool kCountersEnabled = false;
#define PIERCE_COUNT(c, field, n) ((void)0)
#endif

}  // namespace pierce
