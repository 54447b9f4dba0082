#pragma once
// `filter` (Amstutz et al. 2015, all hits): one traversal gathers every hit in [tmin, tmax],
// sorted once in the total order; next() walks the sorted list.
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

template <typename T, class C = NoCounters>
class AllHitsKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  using Base::Base;

  void begin(const Ray& ray, std::size_t max_hits = 0) { begin_into(ray, max_hits, hits_); }

  // begin(), with every hit appended to `out` and sorted there instead of held for next()
  // (HitIterator::collect: no copy through next()). Always true: the hits are all in `out`.
  bool begin_into(const Ray& ray, std::size_t /*max_hits*/, std::vector<Hit>& out) {
    hits_.clear();
    pos_ = 0;
    this->prepare(ray);
    const std::size_t first = out.size();
    this->gather_in_range(out);
    sort_hits(out.begin() + std::ptrdiff_t(first), out.end(), this->order_);
    return true;
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
