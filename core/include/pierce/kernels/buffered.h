#pragma once
// `buffered` (Gribble, Naveros, Kerzner 2014) adapted to an object-partitioning BVH as the
// paper's footnote requires: nodes are traversed near-first from a stack, hits go into a
// fixed-size sorted buffer, and a buffered hit is released only once it is closer than
// every node still on the stack (the overlapping nodes are "resolved"). When the buffer
// overflows, the farthest hits are dropped and a later pass resumes after the last hit
// released; for the rest of the pass only hits ranking before the first one lost (the "cut")
// are buffered, so nothing found after a release can overtake a dropped hit.
// Memory is bounded by the buffer; the caller can stop at any hit (early exit).
#include <array>
#include <limits>
#include <vector>

#include "pierce/kernels/bvh_common.h"

namespace pierce {

template <typename T, std::size_t Capacity = 16>
class BufferedKernel {
 public:
  explicit BufferedKernel(const Bvh<T>& bvh, HitOrder order = {}) : bvh_(&bvh), order_(order) {}

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    have_last_ = false;
    start_pass();
  }

  bool next(Hit& out) {
    for (;;) {
      if (size_ > 0 && buf_[0].t < double(stack_min_tn())) {
        out = buf_[0];
        for (std::size_t i = 1; i < size_; ++i) buf_[i - 1] = buf_[i];
        --size_;
        last_ = out;
        have_last_ = true;
        return true;
      }
      if (stack_.empty()) {
        if (!truncated_) return false;
        start_pass();  // hits were dropped: resume after the last released hit
        continue;
      }
      step();
    }
  }

  Counters counters;

 private:
  void start_pass() {
    size_ = 0;
    truncated_ = false;
    have_cut_ = false;
    stack_.clear();
    if (bvh_->empty() || !ray_.valid()) return;
    const Span<T> root = slab(ray_, bvh_->nodes[0].box.lo, bvh_->nodes[0].box.hi);
    PIERCE_COUNT(counters, node_tests, 1);
    if (box_overlaps(ray_, root, lower(), ray_.tmax)) stack_.push_back({root.tn, 0});
  }

  T lower() const { return have_last_ ? std::max(ray_.tmin, T(last_.t)) : ray_.tmin; }
  T upper() const {
    const T u = size_ == Capacity ? T(buf_[Capacity - 1].t) : ray_.tmax;
    return have_cut_ && T(cut_.t) < u ? T(cut_.t) : u;
  }
  // A hit (or everything in a node, from `tn` on) left for a later pass.
  void lose(const Hit& key) {
    truncated_ = true;
    if (!have_cut_ || order_.less(key, cut_)) cut_ = key, have_cut_ = true;
  }
  static Hit node_key(T tn) {  // ranks before every hit at t >= tn, under either tie policy
    Hit h;
    h.t = double(tn), h.geom = 0, h.prim = 0, h.enter = false;
    return h;
  }
  T stack_min_tn() const {
    T m = std::numeric_limits<T>::infinity();
    for (const auto& e : stack_) m = e.tn < m ? e.tn : m;
    return m;
  }

  void step() {
    const NodeEntry<T> e = stack_.back();
    stack_.pop_back();
    if (e.tn > upper()) {  // everything in it would fall off the full buffer or lie past the cut
      lose(node_key(e.tn));
      return;
    }
    PIERCE_COUNT(counters, traversal_steps, 1);
    const BvhNode<T>& n = bvh_->nodes[e.node];
    PIERCE_COUNT(counters, leaf_visits, n.is_leaf() ? 1 : 0);
    if (!n.is_leaf()) {
      const T up = upper();
      visit_children(*bvh_, n, ray_, lower(), ray_.tmax, counters, [&](std::uint32_t c, T tn) {
        if (tn > up) {
          lose(node_key(tn));  // skipped only because the buffer is full: needed by a later pass
        } else {
          stack_.push_back({tn, c});
        }
      });
      return;
    }
    const T lo = lower();
    for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
      const Triangle<T>& tri = bvh_->tris[i];
      TriangleHit<T> th;
      PIERCE_COUNT(counters, prim_tests, 1);
      if (!intersect(ray_, tri.v0, tri.v1, tri.v2, lo, ray_.tmax, th)) continue;
      PIERCE_COUNT(counters, valid_hits, 1);
      const Hit key = order_key(tri, th);
      if (have_last_ && !order_.less(last_, key)) continue;
      insert(key, tri, th);
    }
  }

  void insert(const Hit& key, const Triangle<T>& tri, const TriangleHit<T>& th) {
    // At or past the cut it could be released before a lost hit that ranks first: a later pass finds it.
    if (have_cut_ && !order_.less(key, cut_)) return;
    if (size_ == Capacity) {
      if (!order_.less(key, buf_[Capacity - 1])) return lose(key);
      lose(buf_[Capacity - 1]);  // the farthest entry falls off
      --size_;
    }
    std::size_t i = size_;
    while (i > 0 && order_.less(key, buf_[i - 1])) {
      buf_[i] = buf_[i - 1];
      --i;
    }
    buf_[i] = make_hit(tri, th);
    ++size_;
  }

  const Bvh<T>* bvh_;
  HitOrder order_;
  TraversalRay<T> ray_;
  std::array<Hit, Capacity> buf_{};
  std::size_t size_ = 0;
  bool truncated_ = false;
  Hit cut_;  // first hit lost in this pass (by the tie order); buffered hits all rank before it
  bool have_cut_ = false;
  Hit last_;
  bool have_last_ = false;
  std::vector<NodeEntry<T>> stack_;
};

}  // namespace pierce
