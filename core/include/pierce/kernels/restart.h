#pragma once
// `restart` (Wald et al. §3): each next() is a closest-hit query for the first hit after
// the last one in the total order. No epsilon: ties at equal t are resolved by (geom, prim).
#include "pierce/hit.h"
#include "pierce/traverse.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class RestartKernel {
 public:
  explicit RestartKernel(const WideBvh<T>& bvh, HitOrder order = {})
      : bvh_(&bvh), order_(order), simd_(simd_level()) {
    stack_.reserve(bvh.stack_capacity());
  }

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    have_last_ = false;
  }

  bool next(Hit& out) {
    if (bvh_->empty() || !ray_.valid()) return false;
    Closest p{*this, have_last_ ? std::max(ray_.tmin, T(last_.t)) : ray_.tmin, ray_.tmax};
    stack_.clear();
    seed(*bvh_, ray_, p.lo_, p.hi_, stack_, counters);
    traverse(simd_, *bvh_, ray_, stack_, p, counters);
    if (p.block == nullptr) return false;
    out = make_hit(*p.block, p.lane, p.th);
    last_ = out;
    have_last_ = true;
    return true;
  }

  C counters;

 private:
  // The closest hit after last_; hi shrinks to it, which culls farther nodes.
  struct Closest : TraversalPolicy<T> {
    const RestartKernel& k;
    T lo_, hi_;
    const TriBlock<T>* block = nullptr;
    int lane = 0;
    TriangleHit<T> th{};
    Hit best;
    Closest(const RestartKernel& kernel, T lo, T hi) : k(kernel), lo_(lo), hi_(hi) {}
    T lo() const { return lo_; }
    T hi() const { return hi_; }
    T cull_bound() const { return hi_; }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) {
      const Hit key = order_key(b, l, h);
      if (k.have_last_ && !k.order_.less(k.last_, key)) return;
      if (block != nullptr && !k.order_.less(key, best)) return;
      best = key, block = &b, lane = l, th = h, hi_ = h.t;
    }
  };

  const WideBvh<T>* bvh_;
  HitOrder order_;
  SimdLevel simd_;
  TraversalRay<T> ray_;
  Hit last_;
  bool have_last_ = false;
  NodeStack<T> stack_;
};

}  // namespace pierce
