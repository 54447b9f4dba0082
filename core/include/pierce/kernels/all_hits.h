#pragma once
// `filter` (Amstutz et al. 2015, all hits): one traversal gathers every hit in [tmin, tmax],
// sorted once in the total order; next() walks the sorted list.
#include <algorithm>
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class AllHitsKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  explicit AllHitsKernel(const WideBvh<T>& bvh, HitOrder order = {}) : Base(bvh, order) {}

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    this->prepare(ray);
    hits_.clear();
    pos_ = 0;
    this->seed_root(this->ray_.tmin, this->ray_.tmax);
    GatherInRange<T> p{this->ray_, hits_};
    this->run(p);
    std::sort(hits_.begin(), hits_.end(), this->order_);
  }

  bool next(Hit& out) {
    if (pos_ >= hits_.size()) return false;
    out = hits_[pos_++];
    return true;
  }

 private:
  std::vector<Hit> hits_;
  std::size_t pos_ = 0;
};

}  // namespace pierce
