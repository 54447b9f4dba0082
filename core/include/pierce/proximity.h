#pragma once
// Proximity queries on the wide BVH (closest point, the boxes a query enters, the nearest point in
// a half-space) run on the one traversal of traverse.h, as the kernels do. What differs is the
// policy, as for the kernels:
//  - the node test (ProximityOps): `enter(box, key)` says whether the query enters a child box and
//    gives it a key (a squared distance, say); the children entered are ranked by key, near first,
//    and taken depth first from the stack, nearest first;
//  - hi(): a child whose key exceeds it is not entered; cull_bound() (the same value): a pending
//    node whose key exceeds the bound as it stands when the node is popped is skipped, since the
//    bound (the best distance so far) may have shrunk after it was pushed;
//  - leaf(block): the leaf test, called for each triangle block of a leaf entered.
// Keys in T: rounding to nearest is monotone, so d <= b gives fl(d) <= fl(b) and a float key never
// skips a box that the exact key would enter.
#include <cstdint>
#include <limits>
#include <type_traits>

#include "pierce/counters.h"
#include "pierce/traverse.h"

namespace pierce {

// The node test of a proximity query. Enter: bool(const BBox<T>&, T& key).
template <typename T, class Enter>
struct ProximityOps {
  Enter& enter;

  // The children entered with a key at most hi, ranked by key (ties in slot order): key[k] and
  // child[k] for rank k, bit k of the result set for each.
  std::uint32_t node_hits(const WideNode<T>& n, T /*lo*/, T hi, T* key, NodeRef* child) const {
    const std::uint32_t valid = n.valid();
    int count = 0;
    for (int s = 0; s < kWideArity; ++s) {
      if (!(valid >> s & 1)) continue;
      BBox<T> box;
      box.lo = {n.lo[0][s], n.lo[1][s], n.lo[2][s]};
      box.hi = {n.hi[0][s], n.hi[1][s], n.hi[2][s]};
      T k{};
      if (!enter(static_cast<const BBox<T>&>(box), k) || !(k <= hi)) continue;
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

// Runs a proximity query over `bvh`: from the root if `enter` takes the BVH's bounds, then every
// node it enters, nearest key first. `stack` is scratch space reused between calls.
template <typename T, class Enter, class Policy>
void traverse_proximity(const WideBvh<T>& bvh, NodeStack<T>& stack, Enter&& enter, Policy& p) {
  if (bvh.empty()) return;
  stack.reserve(bvh.stack_capacity());
  stack.clear();
  T key{};
  if (!enter(static_cast<const BBox<T>&>(bvh.bounds), key) || !(key <= p.hi())) return;
  stack.push({key, bvh.root});
  const ProximityOps<T, std::remove_reference_t<Enter>> ops{enter};
  NoCounters counters;
  traverse_with(ops, bvh, ProximityQuery{}, stack, p, counters);
}

}  // namespace pierce
