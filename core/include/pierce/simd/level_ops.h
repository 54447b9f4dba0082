#pragma once
// The operations the wide-BVH traversal (traverse.h) is written against, one object per
// instruction-set level, made once per traversal from the ray:
//  - node_hits: the node test of a node's eight children against [lo, hi]; the result (mask, entry
//    distances, child references) comes in the node's near-to-far order for the ray's octant;
//  - push_hits: the same test, with the children that pass stored onto a depth-first stack far to
//    near (hit_output.h); it also gives the slots of the stored children other than the nearest,
//    so the loop prefetches them by addresses read from the node;
//  - push_all: the same test, with every child that passes stored in slot order and no branch on
//    how many did (a breadth-first traversal's queue);
//  - tri_test: the triangle test of a leaf block's eight lanes (leaf_test.h).
// ScalarOps is the reference every level must match: the node test is slab(), and every lane goes
// to the exact scalar triangle test. SimdOps serves AVX2 and AVX-512 with one body; what differs
// between them (the pass mask, the stores) comes from the level's overloads of slot_hits and
// store_lanes. Its functions carry the AVX2 target and inline into either level's flattened
// traversal, where the AVX-512 overloads inline too.
#include <immintrin.h>

#include <cstdint>

#include "pierce/simd/hit_output.h"
#include "pierce/simd/leaf_test.h"
#include "pierce/simd/node_test.h"
#include "pierce/simd/ray_setup.h"
#include "pierce/simd/target.h"
#include "pierce/slab.h"
#include "pierce/wide_bvh.h"

namespace pierce::simd {

// The scalar path: every level reduces to this on CPUs without AVX2, and the double BVH uses it.
template <typename T>
struct ScalarOps {
  const TraversalRay<T>& r;
  int oct;
  ScalarOps(const TraversalRay<T>& ray, double /*scene_max_abs*/) : r(ray), oct(octant(ray)) {}

  std::uint32_t node_hits(const WideNode<T>& n, T lo, T hi, T* tn, NodeRef* child) const {
    return node_hits(n, n.order[oct], lo, hi, tn, child);
  }
  // The same, with the node's order for the ray's octant already read.
  std::uint32_t node_hits(const WideNode<T>& n, std::uint32_t order, T lo, T hi, T* tn, NodeRef* child) const {
    const std::uint32_t valid = order >> 24;
    std::uint32_t mask = 0;
    for (int k = 0; k < kWideArity; ++k) {
      const int s = WideNode<T>::slot_at_rank(order, k);
      if (!(valid >> s & 1)) continue;
      const Span<T> sp = slab(r, Vec3<T>(n.lo[0][s], n.lo[1][s], n.lo[2][s]), Vec3<T>(n.hi[0][s], n.hi[1][s], n.hi[2][s]));
      tn[k] = sp.tn;
      child[k] = n.child[s];
      if (box_overlaps(r, sp, lo, hi)) mask |= 1u << k;
    }
    return mask;
  }
  // The children that pass, stored at `top` far to near (the nearest last, also given in `nearest`,
  // so the loop can descend into it without reading it back); returns how many.
  // `others`: the slots of the stored children other than the nearest, for the caller's prefetch
  // (read from the node, which is in the cache, rather than from the entries just stored).
  std::uint32_t push_hits(const WideNode<T>& n, T lo, T hi, NodeEntry<T>* top, NodeEntry<T>& nearest,
                          std::uint32_t& others) const {
    T tn[kWideArity];
    NodeRef child[kWideArity];
    const std::uint32_t order = n.order[oct];
    const std::uint32_t mask = node_hits(n, order, lo, hi, tn, child);
    std::uint32_t count = 0;
    others = 0;
    for (int k = kWideArity - 1; k >= 0; --k)
      if (mask >> k & 1) {
        top[count++] = {tn[k], child[k]};
        others |= 1u << WideNode<T>::slot_at_rank(order, k);
      }
    if (count > 0) {
      nearest = top[count - 1];
      others &= ~(1u << WideNode<T>::slot_at_rank(order, __builtin_ctz(mask)));
    }
    return count;
  }
  // Every child that passes, stored at `top` in any order (a breadth-first traversal's queue); returns
  // the slots stored (as many entries as bits), for the caller's prefetch.
  std::uint32_t push_all(const WideNode<T>& n, T lo, T hi, NodeEntry<T>* top) const {
    T tn[kWideArity];
    NodeRef child[kWideArity];
    const std::uint32_t order = n.order[oct];
    std::uint32_t slots = 0;
    for (std::uint32_t m = node_hits(n, order, lo, hi, tn, child); m != 0; m &= m - 1) {
      const int k = __builtin_ctz(m);
      *top++ = {tn[k], child[k]};
      slots |= 1u << WideNode<T>::slot_at_rank(order, k);
    }
    return slots;
  }
  // Every lane to the scalar test.
  LeafLanes tri_test(const TriBlock<T>& b, T /*lo*/, T /*hi*/, BlockHits<T>& /*out*/) const { return {b.valid, 0}; }
};

template <class Level>
struct SimdOps {
  // The ray's SimdRay, read where it was made (a copy's wide loads of the fields just stored
  // would stall on store forwarding).
  const SimdRay& ray;
  explicit SimdOps(const SimdRay& prepared) : ray(prepared) {}

  // ScalarOps::node_hits.
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t node_hits(const WideNode<float>& n, float lo, float hi,
                                                                      float* tn_out, NodeRef* child_out) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn;
    const auto pass = slot_hits(Level{}, ray, n, order, lo, hi, tn);
    const __m256i rank = rank_slots(order);
    _mm256_store_ps(tn_out, _mm256_permutevar8x32_ps(tn, rank));
    _mm256_store_si256(reinterpret_cast<__m256i*>(child_out),
                       _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), rank));
    return pass.ranked(rank);
  }

  // ScalarOps::push_hits.
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t push_hits(const WideNode<float>& n, float lo, float hi,
                                                                      NodeEntry<float>* top, NodeEntry<float>& nearest,
                                                                      std::uint32_t& others) const {
    const std::uint32_t order = n.order[ray.oct];
    __m256 tn;
    const auto pass = slot_hits(Level{}, ray, n, order, lo, hi, tn);
    const std::uint32_t slots = pass.slots();
    if (slots == 0) return 0;
    if ((slots & (slots - 1)) == 0) {  // one child passes (most nodes of a first-hit ray): nothing to store
      const int s = __builtin_ctz(slots);
      nearest = {lane_tn(tn, s), n.child[s]};
      others = 0;
      return 1;
    }
    const __m256i rank = rank_slots_far_to_near(order);
    const std::uint32_t mask = pass.ranked(rank);
    tn = _mm256_permutevar8x32_ps(tn, rank);
    const __m256i child =
        _mm256_permutevar8x32_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), rank);
    const int near_lane = 31 - __builtin_clz(mask);
    others = slots & ~(1u << nearest_slot(order, near_lane));
    nearest = lane_entry(tn, child, near_lane);
    return store_lanes(Level{}, tn, child, mask, top);
  }

  // ScalarOps::push_all: every child that passes, in slot order, with no branch on how many do
  // (in a breadth-first traversal that count is what the branches would have to guess).
  __attribute__((target(PIERCE_AVX2_TARGET))) std::uint32_t push_all(const WideNode<float>& n, float lo, float hi,
                                                                     NodeEntry<float>* top) const {
    __m256 tn;
    const std::uint32_t slots = slot_hits(Level{}, ray, n, n.order[ray.oct], lo, hi, tn).slots();
    store_lanes(Level{}, tn, _mm256_load_si256(reinterpret_cast<const __m256i*>(n.child)), slots, top);
    return slots;
  }

  // ScalarOps::tri_test, with the lanes SimdRay::tri_test finishes (AVX2 instructions at both
  // levels: the classification has no use for mask registers).
  __attribute__((target(PIERCE_AVX2_TARGET))) LeafLanes tri_test(const TriBlock<float>& b, float lo, float hi,
                                                                 BlockHits<float>& out) const {
    return ray.tri_test(b, lo, hi, out);
  }
};

using Avx2Ops = SimdOps<Avx2>;
using Avx512Ops = SimdOps<Avx512>;

}  // namespace pierce::simd
