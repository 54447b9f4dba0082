#pragma once
// Proximity queries on the wide BVH (closest point, the boxes a query enters, the nearest point in
// a half-space) run on the one traversal of traverse.h, as the kernels do. What differs is the
// policy, as for the kernels:
//  - the node test (ProximityOps): `test(node, key)` gives each of the node's eight child boxes a
//    key (a squared distance, say) in key[slot] and returns the slots the query enters; those
//    with a key at most hi() are ranked by key, near first, and taken depth first from the stack,
//    nearest first. The test sees the node's boxes as stored (structure of arrays), so a query
//    can write it as a loop over the slots that the compiler vectorises;
//  - hi(): a child whose key exceeds it is not entered; cull_bound() (the same value): a pending
//    node whose key exceeds the bound as it stands when the node is popped is skipped, since the
//    bound (the best distance so far) may have shrunk after it was pushed;
//  - leaf(block): the leaf test, called for each triangle block of a leaf entered.
// Keys in T: rounding to nearest is monotone, so d <= b gives fl(d) <= fl(b) and a float key never
// skips a box that the exact key would enter.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "pierce/counters.h"
#include "pierce/traverse.h"

namespace pierce {

// The node test of a proximity query. Test: std::uint32_t(const WideNode<T>&, T key[kWideArity]).
template <typename T, class Test>
struct ProximityOps {
  Test& test;

  // The children entered with a key at most hi, ranked by key (ties in slot order): key[k] and
  // child[k] for rank k, bit k of the result set for each.
  std::uint32_t node_hits(const WideNode<T>& n, T /*lo*/, T hi, T* key, NodeRef* child) const {
    alignas(64) T by_slot[kWideArity];
    const std::uint32_t entered = test(n, by_slot) & n.valid();
    int count = 0;
    for (std::uint32_t m = entered; m != 0; m &= m - 1) {
      const int s = __builtin_ctz(m);
      const T k = by_slot[s];
      if (!(k <= hi)) continue;
      int i = count++;
      for (; i > 0 && key[i - 1] > k; --i) key[i] = key[i - 1], child[i] = child[i - 1];
      key[i] = k, child[i] = n.child[s];
    }
    return (1u << count) - 1u;  // count <= 8
  }
};

// The defaults of a proximity query's policy (see the top of this file); a query derives from it
// and gives hi(), cull_bound() and leaf(const TriBlock<T>&).
template <typename T>
struct ProximityPolicy : TraversalPolicy<T> {
  // The node test ranks and bounds the children itself (node_hits), and the bound shrinks.
  static constexpr bool kCullsInRange = true;
  T lo() const { return -std::numeric_limits<T>::infinity(); }
};

// Runs a proximity query over `bvh` from the root (its children are the first boxes tested; a
// root leaf goes straight to the leaf test), then every node the node test enters, nearest key
// first. `stack` is scratch space reused between calls.
template <typename T, class Test, class Policy>
void traverse_proximity(const WideBvh<T>& bvh, NodeStack<T>& stack, Test&& test, Policy& p) {
  if (bvh.empty() || !(T(0) <= p.hi())) return;
  stack.reserve(bvh.stack_capacity());
  stack.clear();
  stack.push({T(0), bvh.root});
  const ProximityOps<T, std::remove_reference_t<Test>> ops{test};
  NoCounters counters;
  traverse_with(ops, bvh, ProximityQuery{}, stack, p, counters);
}

// How far x lies outside [lo, hi] (0 inside): the per-axis gap of a point-to-box distance, branch
// free, for the node's slots and a block's lanes alike.
template <typename P>
inline P axis_gap(P x, P lo, P hi) {
  return std::max(std::max(lo - x, x - hi), P(0));
}

// Squared distance from q to each child box of n, by slot (+inf for an empty slot). Branch free
// over the slots, so the compiler vectorises it.
template <typename T, typename P>
inline void box_distances2(const WideNode<T>& n, const Vec3<P>& q, P* d2) {
  for (int s = 0; s < kWideArity; ++s) {
    P d = 0;
    for (int a = 0; a < 3; ++a) {
      const P e = axis_gap(q[a], P(n.lo[a][s]), P(n.hi[a][s]));
      d += e * e;
    }
    d2[s] = d;
  }
}

// Squared distance from q to each lane's triangle box in block b (padding lanes: whatever their
// zeroed corners give; callers look only at valid lanes). Branch free over the lanes, so the
// compiler vectorises it: a leaf test measures a triangle only where its box is within the bound.
template <typename T, typename P>
inline void lane_box_distances2(const TriBlock<T>& b, const Vec3<P>& q, P* d2) {
  for (int l = 0; l < kBlockLanes; ++l) {
    P d = 0;
    for (int a = 0; a < 3; ++a) {
      const P v0 = P(b.v[0][a][l]), v1 = P(b.v[1][a][l]), v2 = P(b.v[2][a][l]);
      const P e = axis_gap(q[a], std::min(std::min(v0, v1), v2), std::max(std::max(v0, v1), v2));
      d += e * e;
    }
    d2[l] = d;
  }
}

// The bound a leaf test compares a triangle's box distance with: a closest point at a box corner
// can come out an ulp or two below the box's own rounded distance, so a triangle is skipped only
// where its box lies clearly beyond.
inline double beyond_bound(double bound2) { return bound2 * (1 + 0x1p-30); }

}  // namespace pierce
