#pragma once
// `queue` (Wald et al. §4): front-to-back traversal with a priority queue of untraversed
// nodes and a priority queue of found hits. A hit is returned once it is strictly closer
// than every untraversed node; the state survives between next() calls.
#include <algorithm>
#include <vector>

#include "pierce/hit.h"
#include "pierce/traverse.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class QueueKernel {
 public:
  explicit QueueKernel(const WideBvh<T>& bvh, HitOrder order = {})
      : bvh_(&bvh), order_(order), simd_(simd_level()) {
    nodes_.reserve(4 * bvh.stack_capacity());
    hits_.reserve(16);
  }

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    nodes_.clear();
    hits_.clear();
    seed(*bvh_, ray_, ray_.tmin, ray_.tmax, nodes_, counters);
  }

  bool next(Hit& out) {
    Gather p{*this};
    for (;;) {
      // Strict: a node entered at exactly the hit's t may still hold a hit that ranks first.
      if (!hits_.empty() && (nodes_.empty() || hits_.front().t < double(nodes_.next_tn()))) {
        std::pop_heap(hits_.begin(), hits_.end(), hit_after_);
        out = hits_.back();
        hits_.pop_back();
        return true;
      }
      if (nodes_.empty()) return false;
      traverse(simd_, *bvh_, ray_, nodes_, p, counters);  // until a hit is ready or nothing is left
    }
  }

  C counters;

 private:
  struct HitAfter {
    HitOrder order;
    bool operator()(const Hit& a, const Hit& b) const { return order.less(b, a); }
  };
  // Every hit goes into the hit heap; traversal stops once the closest one is safe to return.
  struct Gather : TraversalPolicy<T> {
    static constexpr bool kSuspends = true;
    QueueKernel& k;
    explicit Gather(QueueKernel& kernel) : k(kernel) {}
    T lo() const { return k.ray_.tmin; }
    T hi() const { return k.ray_.tmax; }
    T cull_bound() const { return k.ray_.tmax; }
    template <class Pending>
    bool suspend(T next_tn, const Pending&) const {
      return !k.hits_.empty() && k.hits_.front().t < double(next_tn);
    }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) {
      k.hits_.push_back(make_hit(b, l, h));
      std::push_heap(k.hits_.begin(), k.hits_.end(), k.hit_after_);
    }
  };

  const WideBvh<T>* bvh_;
  HitOrder order_;
  HitAfter hit_after_{order_};
  SimdLevel simd_;
  TraversalRay<T> ray_;
  NodeHeap<T> nodes_;
  std::vector<Hit> hits_;  // min-heap in hit order
};

}  // namespace pierce
