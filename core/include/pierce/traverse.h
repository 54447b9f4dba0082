#pragma once
// The one traversal of the wide BVH that every Pierce kernel runs, and the proximity queries
// (proximity.h) too, in the manner of madmann91/bvh v2's traverse(leaf_fn, inner_fn). What differs
// between kernels is a policy:
//  - the container of untraversed nodes: NodeStack (depth first, near child first) or NodeHeap
//    (front to back by entry distance, Wald et al. §4);
//  - the active range [lo(), hi()] for box and triangle tests, and cull_bound(): a node entered
//    beyond it is not traversed but handed to culled() (node culling, Gribble 2016; `buffered`
//    remembers that it lost something for a later pass, `queue` keeps the node itself);
//  - suspend(next_tn, pending): stop before the next node, keeping the state (queue, buffered;
//    only called where the policy sets kSuspends);
//  - node(ref, tn): Gribble's every-node callback, called for each node traversed;
//  - hit(block, lane, th): the leaf callback, called for every triangle the exact test accepts
//    within the active range.
// The counters are a policy too (counters.h): Counters counts the work, NoCounters compiles it out.
// Policies derive from TraversalPolicy, which gives the defaults.
//
// The traversal is written once and compiled for each instruction-set level (simd_level.h):
// traverse() picks the level's instantiation; the SIMD ones are compiled with the level's target
// attribute and flattened, so the node and leaf tests inline into the loop.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "pierce/counters.h"
#include "pierce/node_stack.h"
#include "pierce/prefetch_mode.h"
#include "pierce/simd/level_ops.h"
#include "pierce/simd/simd_level.h"
#include "pierce/wide_bvh.h"

namespace pierce {

template <typename T>
struct TraversalPolicy {
  // True if cull_bound() can be below hi() and children that pass the box test are to be checked
  // against it before they are pushed. Without it, a pending node is still checked when popped.
  static constexpr bool kCullsInRange = false;
  // True if suspend() can return true (it then sees the pending nodes).
  static constexpr bool kSuspends = false;
  // True if the policy's result does not depend on the order in which nodes are visited (`filter`
  // and `queue`'s gathering pass take every hit of a fixed range): children are then pushed
  // unranked, in slot order, with no branch on how many passed (push_all), and visited breadth
  // first (FifoCursor). A node taken beyond cull_bound() is still culled when popped.
  static constexpr bool kAnyOrder = false;
  void culled(NodeEntry<T> /*node*/) {}
  template <class Pending>
  bool suspend(T /*next_tn*/, const Pending& /*pending*/) const {
    return false;
  }
  void node(NodeRef /*ref*/, T /*tn*/) {}
};

// Pushes the root onto `pending` for a valid ray and a non-empty range, entered at lo. The scene's
// box is not tested: every child box lies inside it, so the root's node test (or, for a root leaf,
// each triangle's own box test) rejects whatever it would.
template <typename T, class Pending, class C>
inline void seed(const WideBvh<T>& bvh, const TraversalRay<T>& r, T lo, T hi, Pending& pending, C& /*counters*/) {
  if (bvh.empty() || !r.valid() || !(lo <= hi)) return;
  pending.push({lo, bvh.root});
}

// Pieces of the loop shared by both container kinds.
// A ray's leaf test: the exact triangle test of every triangle of the leaf's blocks.
template <class Ops, typename T, class Policy, class C>
inline void detail_leaf(const Ops& ops, const TriBlock<T>* blocks, NodeRef ref, const TraversalRay<T>& r, Policy& p,
                        C& c) {
  c.leaf_visits += 1;
  const std::uint32_t first = leaf_first_block(ref), end = first + leaf_block_count(ref);
  for (std::uint32_t b = first; b < end; ++b) {
    const TriBlock<T>& blk = blocks[b];
    c.prim_tests += std::uint64_t(__builtin_popcount(blk.valid));
    simd::BlockHits<T> finished;
    const simd::LeafLanes lanes = ops.tri_test(blk, p.lo(), p.hi(), finished);
    for (std::uint32_t todo = lanes.exact | lanes.hit; todo != 0; todo &= todo - 1) {
      const int l = __builtin_ctz(todo);
      TriangleHit<T> th;
      if (lanes.hit >> l & 1) {
        // Finished in SIMD against the range at the block's start, which the hits before it in
        // this block may have narrowed.
        th = simd::lane_hit(finished, l, blk.sum[l]);
        if (!(th.t >= p.lo() && th.t <= p.hi())) continue;
      } else if (!intersect_sorted(r, blk.corner(0, l), blk.corner(1, l), blk.corner(2, l), blk.sum[l], p.lo(),
                                   p.hi(), th)) {
        continue;
      }
      c.valid_hits += 1;
      p.hit(blk, l, th);
    }
  }
}

// The query of a proximity query (proximity.h), in place of the ray: its leaf test is the
// policy's, leaf(block) for each block of the leaf.
struct ProximityQuery {};
template <class Ops, typename T, class Policy, class C>
inline void detail_leaf(const Ops& /*ops*/, const TriBlock<T>* blocks, NodeRef ref, ProximityQuery /*query*/, Policy& p,
                        C& c) {
  c.leaf_visits += 1;
  const std::uint32_t first = leaf_first_block(ref), end = first + leaf_block_count(ref);
  for (std::uint32_t b = first; b < end; ++b) p.leaf(blocks[b]);
}

template <typename T, class Policy>
inline std::uint32_t detail_cull(Policy& p, std::uint32_t mask, const T* tn, const NodeRef* child) {
  const T cull = p.cull_bound();
  for (std::uint32_t m = mask; m != 0; m &= m - 1) {
    const int k = __builtin_ctz(m);
    if (tn[k] > cull) {
      p.culled(NodeEntry<T>{tn[k], child[k]});
      mask &= ~(1u << k);
    }
  }
  return mask;
}

// A child that passed the box test is asked for at once, while the nodes in front of it are
// processed: the lines a node test reads (the whole 256-byte float node), or those a leaf block's
// SIMD test reads (all but the ids). On a scene beyond the caches this hides much of the latency;
// within them it is only work, so the loop asks only where detail_prefetches() says so.
// The prefetch is an asm statement: GCC 12's dead-code elimination drops __builtin_prefetch here
// (the calls in the two branches below compiled to nothing, checked in the object code).
inline void detail_prefetch_line(const char* p) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetcht0 %0" : : "m"(*p));
#else
  __builtin_prefetch(p);
#endif
}
template <std::size_t... Line>
inline void detail_prefetch_lines(const char* p, std::index_sequence<Line...>) {
  (detail_prefetch_line(p + 64 * Line), ...);
}
template <typename T>
inline void detail_prefetch(const WideNode<T>* nodes, const TriBlock<T>* blocks, NodeRef ref) {
  if (is_leaf(ref)) {
    detail_prefetch_lines(reinterpret_cast<const char*>(&blocks[leaf_first_block(ref)]),
                          std::make_index_sequence<(offsetof(TriBlock<T>, geom) + 63) / 64>{});
  } else {
    detail_prefetch_lines(reinterpret_cast<const char*>(&nodes[ref]),
                          std::make_index_sequence<(offsetof(WideNode<T>, order) + 63) / 64>{});
  }
}
template <typename T>
inline void detail_prefetch(const WideNode<T>* nodes, const TriBlock<T>* blocks, std::uint32_t mask,
                            const NodeRef* child) {
  for (std::uint32_t m = mask; m != 0; m &= m - 1) detail_prefetch(nodes, blocks, child[__builtin_ctz(m)]);
}

// Whether a traversal of `bvh` prefetches the children it will visit (prefetch_mode.h: by the
// BVH's size unless PIERCE_PREFETCH or set_prefetch_mode() forces it). One decision per traversal.
template <class Policy, typename T>
inline bool detail_prefetches(const WideBvh<T>& bvh) {
  return prefetches(bvh.memory_bytes(), Policy::kAnyOrder);
}

// The pending nodes as the loop sees them. A stack is worked on through locals (buffer pointer and
// depth in registers) and written back whenever the policy looks at it and on return; a heap is
// used as it is.
template <typename T>
class StackCursor {
 public:
  static constexpr bool kOrdered = false;
  explicit StackCursor(NodeStack<T>& s) : s_(s), base_(s.data()), sp_(s.size()), cap_(s.capacity()) {}
  bool empty() const { return sp_ == 0; }
  T next_tn() const { return base_[sp_ - 1].tn; }
  NodeEntry<T> pop() { return base_[--sp_]; }
  void push(NodeEntry<T> e) { base_[sp_++] = e; }
  NodeEntry<T>* top() { return base_ + sp_; }
  void grow(std::size_t n) { sp_ += n; }
  const NodeStack<T>& sync() {
    s_.set_size(sp_);
    return s_;
  }

 private:
  NodeStack<T>& s_;
  NodeEntry<T>* base_;
  std::size_t sp_, cap_;
};

// The pending nodes of a kAnyOrder policy, first in first out, in the same buffer: pushed at the
// tail, taken from the head. Where the order does not matter, the node processed next is then the
// one asked for (prefetched) longest ago, so the traversal waits on memory as little as it can.
// Every entry is written once per ray (the head is not reused), so the buffer holds the nodes a
// ray visits, not a depth-first bound: it is compacted or doubled where it must be (ensure_room;
// the buffer keeps its size, so that happens at most a few times in a kernel's life).
template <typename T>
class FifoCursor {
 public:
  static constexpr bool kOrdered = false;
  explicit FifoCursor(NodeStack<T>& s) : s_(s), base_(s.data()), tail_(s.size()), cap_(s.capacity()) {}
  bool empty() const { return head_ == tail_; }
  T next_tn() const { return base_[head_].tn; }
  NodeEntry<T> pop() { return base_[head_++]; }
  void push(NodeEntry<T> e) { base_[tail_++] = e; }
  NodeEntry<T>* top() { return base_ + tail_; }
  void grow(std::size_t n) { tail_ += n; }
  // Room for the next node's children (a SIMD push writes a node's worth whatever passed).
  void ensure_room() {
    if (tail_ + 2 * kWideArity <= cap_) [[likely]]
      return;
    compact();
    if (tail_ + 2 * kWideArity <= cap_) return;
    s_.set_size(tail_);
    s_.reserve(2 * cap_);
    base_ = s_.data(), cap_ = s_.capacity();
  }
  // The pending nodes as a NodeStack (at its bottom, oldest first).
  const NodeStack<T>& sync() {
    compact();
    s_.set_size(tail_);
    return s_;
  }

 private:
  void compact() {
    if (head_ == 0) return;
    std::copy(base_ + head_, base_ + tail_, base_);
    tail_ -= head_, head_ = 0;
  }
  NodeStack<T>& s_;
  NodeEntry<T>* base_;
  std::size_t head_ = 0, tail_, cap_;
};

template <typename T>
class HeapCursor {
 public:
  static constexpr bool kOrdered = true;
  explicit HeapCursor(NodeHeap<T>& h) : h_(h) {}
  bool empty() const { return h_.empty(); }
  T next_tn() const { return h_.next_tn(); }
  NodeEntry<T> pop() { return h_.pop(); }
  void push(NodeEntry<T> e) { h_.push(e); }
  const NodeHeap<T>& sync() { return h_; }

 private:
  NodeHeap<T>& h_;
};

// The cursor over a policy's container: a stack depth first, or first in first out for a
// kAnyOrder policy; a heap as it is.
template <class Policy, typename T>
auto cursor_for(NodeStack<T>& s) {
  if constexpr (Policy::kAnyOrder) {
    return FifoCursor<T>(s);
  } else {
    return StackCursor<T>(s);
  }
}
template <class Policy, typename T>
HeapCursor<T> cursor_for(NodeHeap<T>& h) {
  return HeapCursor<T>(h);
}

// The traversal loop with the node tests of `Ops` and the leaf test of `query`: a ray's exact
// triangle test (TraversalRay), or the policy's own (ProximityQuery). Returns true when every
// pending node is done, false when the policy suspended it (the next node is back on `container`).
template <class Ops, typename T, class Query, class Container, class Policy, class C>
inline bool traverse_with(const Ops& ops, const WideBvh<T>& bvh, const Query& query, Container& container, Policy& p,
                          C& c) {
  const WideNode<T>* const nodes = bvh.nodes.data();
  const TriBlock<T>* const blocks = bvh.blocks.data();
  auto pending = cursor_for<Policy>(container);
  const bool prefetch = detail_prefetches<Policy>(bvh);
  NodeEntry<T> cur{};
  bool have = false;  // `cur` is a child descended into directly, not taken from `pending`
  for (;;) {
    if (!have) {
      if (pending.empty()) {
        pending.sync();
        return true;
      }
      if constexpr (Policy::kSuspends)
        if (p.suspend(pending.next_tn(), pending.sync())) return false;
      cur = pending.pop();
    } else if constexpr (Policy::kSuspends) {
      if (p.suspend(cur.tn, pending.sync())) {
        pending.push(cur);
        pending.sync();
        return false;
      }
    }
    have = false;
    if (cur.tn > p.cull_bound()) {
      p.culled(cur);
      continue;
    }
    c.traversal_steps += 1;
    p.node(cur.ref, cur.tn);

    if (is_leaf(cur.ref)) {
      detail_leaf<Ops>(ops, blocks, cur.ref, query, p, c);
      continue;
    }
    const WideNode<T>& node = nodes[cur.ref];
    c.node_tests += std::uint64_t(__builtin_popcount(node.valid()));
    if constexpr (!decltype(pending)::kOrdered && !Policy::kCullsInRange) {
      if constexpr (Policy::kAnyOrder) {
        // Breadth first (FifoCursor): every child that passes joins the queue's tail in slot order,
        // unranked, prefetched, and the node processed next is the oldest pending one. No branch
        // on how many passed: breadth first that count is unpredictable, and a branch guessing it
        // costs about a tenth of `filter`'s time (`pierce_bench_kernels --kernels filter`).
        pending.ensure_room();
        const std::uint32_t slots = ops.push_all(node, p.lo(), p.hi(), pending.top());
        if (prefetch) detail_prefetch(nodes, blocks, slots, node.child);
        pending.grow(std::size_t(__builtin_popcount(slots)));
        continue;
      }
      // Depth first: every child that passes goes onto the stack far to near in SIMD stores, and
      // the nearest (the last stored) is descended into at once (taken from the registers, not
      // read back; the stack keeps the others). The others are prefetched; the nearest is read at
      // once anyway.
      std::uint32_t others;
      const std::uint32_t n = ops.push_hits(node, p.lo(), p.hi(), pending.top(), cur, others);
      if (n == 0) continue;
      // The addresses come from the node, not from the entries just stored: a load from a wide
      // store still in flight waits for it.
      if (prefetch) detail_prefetch(nodes, blocks, others, node.child);
      pending.grow(n - 1);
      have = true;
      continue;
    }
    alignas(32) T tn[kWideArity];
    alignas(32) NodeRef child[kWideArity];
    // Bit k: the child ranked k-th near to far for this octant passed; tn and child in that order.
    std::uint32_t mask = ops.node_hits(node, p.lo(), p.hi(), tn, child);
    if constexpr (Policy::kCullsInRange) mask = detail_cull(p, mask, tn, child);
    if (mask == 0) continue;
    if (prefetch) detail_prefetch(nodes, blocks, mask, child);
    if constexpr (decltype(pending)::kOrdered) {
      // Descend into the nearest child directly unless a pending node is nearer still.
      int nearest = __builtin_ctz(mask);
      for (std::uint32_t m = mask & (mask - 1); m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        if (tn[k] < tn[nearest]) {
          pending.push({tn[nearest], child[nearest]});
          nearest = k;
        } else {
          pending.push({tn[k], child[k]});
        }
      }
      cur = {tn[nearest], child[nearest]};
      if (!pending.empty() && pending.next_tn() < cur.tn) {
        pending.push(cur);
        cur = pending.pop();
      }
    } else {
      // Far to near, so the next nearest is popped first; the nearest is descended into directly.
      while (mask & (mask - 1)) {
        const int k = 31 - __builtin_clz(mask);
        pending.push({tn[k], child[k]});
        mask ^= 1u << k;
      }
      const int k = __builtin_ctz(mask);
      cur = {tn[k], child[k]};
    }
    have = true;
  }
}

namespace detail {

// The SimdRay a SIMD level's traversal reads: `prepared` if the caller made it (WideKernel::prepare,
// once per ray), else `made` from r.
__attribute__((target(PIERCE_AVX2_TARGET))) inline const simd::SimdRay& simd_ray_for(const TraversalRay<float>& r,
                                                                                  double scene_max_abs,
                                                                                  const simd::SimdRay* prepared,
                                                                                  simd::SimdRay& made) {
  if (prepared != nullptr) return *prepared;
  made.assign(r, scene_max_abs);
  return made;
}

template <typename T, class Pending, class Policy, class C>
__attribute__((target(PIERCE_AVX2_TARGET), flatten)) bool traverse_avx2(const WideBvh<T>& bvh, const TraversalRay<T>& r,
                                                                        const simd::SimdRay* prepared,
                                                                        Pending& pending, Policy& p, C& c) {
  simd::SimdRay made;
  return traverse_with(simd::Avx2Ops(simd_ray_for(r, bvh.scene_max_abs, prepared, made)), bvh, r, pending, p, c);
}

template <typename T, class Pending, class Policy, class C>
__attribute__((target(PIERCE_AVX512_TARGET), flatten)) bool traverse_avx512(const WideBvh<T>& bvh,
                                                                            const TraversalRay<T>& r,
                                                                            const simd::SimdRay* prepared,
                                                                            Pending& pending, Policy& p, C& c) {
  simd::SimdRay made;
  return traverse_with(simd::Avx512Ops(simd_ray_for(r, bvh.scene_max_abs, prepared, made)), bvh, r, pending, p, c);
}

// The traversal at `level`; `prepared` (or null) is read only at a SIMD level (simd_ray_for).
template <typename T, class Pending, class Policy, class C>
inline bool traverse_at(SimdLevel level, const WideBvh<T>& bvh, const TraversalRay<T>& r,
                        const simd::SimdRay* prepared, Pending& pending, Policy& p, C& c) {
  if constexpr (std::is_same_v<T, float>) {
    if (level == SimdLevel::avx512) return traverse_avx512(bvh, r, prepared, pending, p, c);
    if (level == SimdLevel::avx2) return traverse_avx2(bvh, r, prepared, pending, p, c);
  }
  return traverse_with(simd::ScalarOps<T>(r, bvh.scene_max_abs), bvh, r, pending, p, c);
}

}  // namespace detail

// Runs the traversal at `level` (the SIMD paths exist for float; double runs the scalar one).
template <typename T, class Pending, class Policy, class C>
inline bool traverse(SimdLevel level, const WideBvh<T>& bvh, const TraversalRay<T>& r, Pending& pending, Policy& p,
                     C& c) {
  return detail::traverse_at(level, bvh, r, nullptr, pending, p, c);
}

// Everything HitOrder looks at, without the rest of the record.
template <typename T>
inline HitKey order_key(const TriBlock<T>& b, int lane, const TriangleHit<T>& th) {
  return {double(th.t), b.geom[lane], b.prim[lane], th.enter};
}

// The hit record for a triangle of a leaf block; geometric normal from the input's corners.
template <typename T>
inline Hit make_hit(const TriBlock<T>& b, int lane, const TriangleHit<T>& th) {
  const Vec3<T> v0 = b.input_corner(0, lane);
  return hit_of(order_key(b, lane, th), float(th.u), float(th.v),
                Vec3f(cross(b.input_corner(1, lane) - v0, b.input_corner(2, lane) - v0)));
}

}  // namespace pierce
