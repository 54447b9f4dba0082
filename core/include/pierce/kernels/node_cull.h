#pragma once
// `nodecull` (Gribble 2016): N-closest hits. Hits go into a bounded max-heap; once it holds
// N hits, nodes entered beyond the N-th hit are culled. N comes from the max-hits hint
// (0 = all hits). If more than N hits are asked for, the next batch of N starts after the
// last hit returned, so the sequence is complete for any N.
#include <algorithm>
#include <limits>
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

template <typename T, class C = NoCounters>
class NodeCullKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  using Base::Base;

  void begin(const Ray& ray, std::size_t max_hits = 0) {
    this->prepare(ray);
    n_ = max_hits == 0 ? std::numeric_limits<std::size_t>::max() : max_hits;
    batch_.clear();
    pos_ = 0;
    resume_.clear();
    exhausted_ = !this->traceable();
  }

  bool next(Hit& out) {
    if (pos_ == batch_.size()) {
      if (exhausted_) return false;
      collect();
      if (batch_.size() < n_) exhausted_ = true;  // a short batch holds every remaining hit
      if (batch_.empty()) return false;
    }
    out = batch_[pos_++];
    resume_.set(out);
    return true;
  }

 private:
  struct HitBefore {
    HitOrder order;
    bool operator()(const Hit& a, const Hit& b) const { return order.less(a, b); }
  };

  // The N closest after the last one returned; once N are held, hi() is the N-th and culls farther nodes.
  struct Closest : TraversalPolicy<T> {
    NodeCullKernel& k;
    T lo_;
    Closest(NodeCullKernel& kernel, T lo) : k(kernel), lo_(lo) {}
    T lo() const { return lo_; }
    T hi() const { return k.batch_.size() == k.n_ ? T(k.batch_.front().t) : k.ray_.tmax; }
    T cull_bound() const { return hi(); }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) {
      const HitBefore before{k.order_};
      const HitKey key = order_key(b, l, h);
      if (k.resume_.done(k.order_, key)) return;
      if (k.batch_.size() == k.n_) {
        if (!k.order_.less(key, k.batch_.front())) return;
        std::pop_heap(k.batch_.begin(), k.batch_.end(), before);  // max-heap: front is the N-th hit
        k.batch_.pop_back();
      }
      k.batch_.push_back(make_hit(b, l, h));
      std::push_heap(k.batch_.begin(), k.batch_.end(), before);
    }
  };

  // The n_ closest hits after the last one returned into batch_, sorted.
  void collect() {
    batch_.clear();
    pos_ = 0;
    Closest p{*this, resume_.lower(this->ray_.tmin)};
    this->seed_root(p.lo(), this->ray_.tmax);
    this->run(p);
    std::sort_heap(batch_.begin(), batch_.end(), HitBefore{this->order_});
  }

  std::size_t n_ = 0;
  std::vector<Hit> batch_;
  std::size_t pos_ = 0;
  ResumeAfter resume_;
  bool exhausted_ = true;
};

}  // namespace pierce
