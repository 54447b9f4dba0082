#pragma once
// Traversal counters (Gribble 2016) as a policy of the traversal: a kernel instantiated with
// Counters counts its work; one instantiated with NoCounters (the default) compiles every count to
// nothing, so the counting variant exists in every build at no cost to the others.
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
  Counters& operator-=(const Counters& o) {
    node_tests -= o.node_tests, traversal_steps -= o.traversal_steps, leaf_visits -= o.leaf_visits;
    prim_tests -= o.prim_tests, valid_hits -= o.valid_hits;
    return *this;
  }
  friend Counters operator-(Counters a, const Counters& b) { return a -= b; }
  Counters totals() const { return *this; }
};

// A count that is never kept.
struct IgnoredCount {
  template <typename N>
  constexpr IgnoredCount& operator+=(N) {
    return *this;
  }
};

// The counter policy of the kernels that do not count: the same fields, all ignored.
struct NoCounters {
  IgnoredCount node_tests, traversal_steps, prim_tests, valid_hits, leaf_visits;
  Counters totals() const { return {}; }
};

}  // namespace pierce
