#pragma once
// `queue` (Wald et al. §4): front-to-back traversal with a priority queue of untraversed
// nodes and a priority queue of found hits. A hit is returned once it is strictly closer
// than every untraversed node; the state survives between next() calls.
#include <algorithm>
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class QueueKernel : public WideKernel<T, C, NodeHeap<T>> {
  using Base = WideKernel<T, C, NodeHeap<T>>;

 public:
  explicit QueueKernel(const WideBvh<T>& bvh, HitOrder order = {}) : Base(bvh, order) { hits_.reserve(16); }

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    this->prepare(ray);
    hits_.clear();
    this->seed_root(this->ray_.tmin, this->ray_.tmax);
  }

  bool next(Hit& out) {
    Gather p{*this};
    for (;;) {
      // Strict: a node entered at exactly the hit's t may still hold a hit that ranks first.
      if (!hits_.empty() && (this->pending_.empty() || hits_.front().t < double(this->pending_.next_tn()))) {
        std::pop_heap(hits_.begin(), hits_.end(), hit_after_);
        out = hits_.back();
        hits_.pop_back();
        return true;
      }
      if (this->pending_.empty()) return false;
      this->run(p);  // until a hit is ready or nothing is left
    }
  }

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

  HitAfter hit_after_{this->order_};
  std::vector<Hit> hits_;  // min-heap in hit order
};

}  // namespace pierce
