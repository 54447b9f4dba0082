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

#include "pierce/hit.h"
#include "pierce/traverse.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters, std::size_t Capacity = 16>
class BufferedKernel {
 public:
  explicit BufferedKernel(const WideBvh<T>& bvh, HitOrder order = {})
      : bvh_(&bvh), order_(order), simd_(simd_level()) {
    stack_.reserve(bvh.stack_capacity());
  }

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    have_last_ = false;
    start_pass();
  }

  bool next(Hit& out) {
    Buffer p{*this};
    for (;;) {
      if (size_ > 0 && buf_[0].t < double(stack_.min_tn())) {
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
      traverse(simd_, *bvh_, ray_, stack_, p, counters);  // until a hit is resolved or nothing is left
    }
  }

  C counters;

 private:
  struct Buffer : TraversalPolicy<T> {
    static constexpr bool kCullsInRange = true;
    static constexpr bool kSuspends = true;
    BufferedKernel& k;
    explicit Buffer(BufferedKernel& kernel) : k(kernel) {}
    T lo() const { return k.lower(); }
    T hi() const { return k.ray_.tmax; }
    // A node entered beyond it would only add hits that fall off the full buffer or lie past the
    // cut: it is needed by a later pass.
    T cull_bound() const { return k.upper(); }
    void culled(T tn) { k.lose(node_key(tn)); }
    template <class Pending>
    bool suspend(T next_tn, const Pending& pending) const {
      if (k.size_ == 0) return false;
      const T m = pending.min_tn();
      return k.buf_[0].t < double(next_tn < m ? next_tn : m);
    }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) {
      const Hit key = order_key(b, l, h);
      if (k.have_last_ && !k.order_.less(k.last_, key)) return;
      k.insert(key, b, l, h);
    }
  };

  void start_pass() {
    size_ = 0;
    truncated_ = false;
    have_cut_ = false;
    stack_.clear();
    seed(*bvh_, ray_, lower(), ray_.tmax, stack_, counters);
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

  void insert(const Hit& key, const TriBlock<T>& b, int lane, const TriangleHit<T>& th) {
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
    buf_[i] = make_hit(b, lane, th);
    ++size_;
  }

  const WideBvh<T>* bvh_;
  HitOrder order_;
  SimdLevel simd_;
  TraversalRay<T> ray_;
  std::array<Hit, Capacity> buf_{};
  std::size_t size_ = 0;
  bool truncated_ = false;
  Hit cut_;  // first hit lost in this pass (by the tie order); buffered hits all rank before it
  bool have_cut_ = false;
  Hit last_;
  bool have_last_ = false;
  NodeStack<T> stack_;
};

}  // namespace pierce
