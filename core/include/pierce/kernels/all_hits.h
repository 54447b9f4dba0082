#pragma once
// `filter` (Amstutz et al. 2015, all hits): one traversal gathers every hit in [tmin, tmax],
// sorted once in the total order; next() walks the sorted list.
#include <algorithm>
#include <vector>

#include "pierce/hit.h"
#include "pierce/traverse.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class AllHitsKernel {
 public:
  explicit AllHitsKernel(const WideBvh<T>& bvh, HitOrder order = {})
      : bvh_(&bvh), order_(order), simd_(simd_level()) {
    stack_.reserve(bvh.stack_capacity());
  }

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    const TraversalRay<T> r = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    hits_.clear();
    pos_ = 0;
    stack_.clear();
    seed(*bvh_, r, r.tmin, r.tmax, stack_, counters);
    Gather p{r, hits_};
    traverse(simd_, *bvh_, r, stack_, p, counters);
    std::sort(hits_.begin(), hits_.end(), order_);
  }

  bool next(Hit& out) {
    if (pos_ >= hits_.size()) return false;
    out = hits_[pos_++];
    return true;
  }

  C counters;

 private:
  struct Gather : TraversalPolicy<T> {
    const TraversalRay<T>& r;
    std::vector<Hit>& hits;
    Gather(const TraversalRay<T>& ray, std::vector<Hit>& out) : r(ray), hits(out) {}
    T lo() const { return r.tmin; }
    T hi() const { return r.tmax; }
    T cull_bound() const { return r.tmax; }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) { hits.push_back(make_hit(b, l, h)); }
  };

  const WideBvh<T>* bvh_;
  HitOrder order_;
  SimdLevel simd_;
  NodeStack<T> stack_;
  std::vector<Hit> hits_;
  std::size_t pos_ = 0;
};

}  // namespace pierce
