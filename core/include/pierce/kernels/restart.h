#pragma once
// `restart` (Wald et al. §3): each next() is a closest-hit query for the first hit after
// the last one in the total order. No epsilon: ties at equal t are resolved by (geom, prim).
#include "pierce/kernels/wide_kernel.h"

namespace pierce {

template <typename T, class C = NoCounters>
class RestartKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  using Base::Base;

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) { this->prepare(ray); resume_.clear(); }

  bool next(Hit& out) {
    if (!this->traceable()) return false;
    Closest p{*this, resume_.lower(this->ray_.tmin), this->ray_.tmax};
    this->seed_root(p.lo_, p.hi_);
    this->run(p);
    if (p.block == nullptr) return false;
    out = make_hit(*p.block, p.lane, p.th);
    resume_.set(out);
    return true;
  }

 private:
  // The closest hit after the last one returned; hi shrinks to it, which culls farther nodes.
  struct Closest : TraversalPolicy<T> {
    const RestartKernel& k;
    T lo_, hi_;
    const TriBlock<T>* block = nullptr;
    int lane = 0;
    TriangleHit<T> th{};
    HitKey best{};
    Closest(const RestartKernel& kernel, T lo, T hi) : k(kernel), lo_(lo), hi_(hi) {}
    T lo() const { return lo_; }
    T hi() const { return hi_; }
    T cull_bound() const { return hi_; }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) {
      const HitKey key = order_key(b, l, h);
      if (k.resume_.done(k.order_, key)) return;
      if (block != nullptr && !k.order_.less(key, best)) return;
      best = key, block = &b, lane = l, th = h, hi_ = h.t;
    }
  };

  ResumeAfter resume_;
};

}  // namespace pierce
