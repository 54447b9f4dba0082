#pragma once
// `filter` (Amstutz et al. 2015, all hits): one traversal gathers every hit in [tmin, tmax],
// sorted once in the total order; next() walks the sorted list.
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
    hits_.clear();
    pos_ = 0;
    this->prepare(ray);
    this->gather_sorted(hits_);
  }

  // begin(ray), then every next() hit (up to max_hits, 0 = all) appended to `out`: gathered and
  // sorted there, not copied over from the kernel's own list.
  void collect(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
    hits_.clear();
    pos_ = 0;
    const std::size_t first = out.size();
    this->prepare(ray);
    this->gather_sorted(out);
    if (max_hits != 0 && out.size() - first > max_hits) out.resize(first + max_hits);
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
