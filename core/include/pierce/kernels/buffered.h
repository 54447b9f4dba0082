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

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

template <typename T, class C = NoCounters, std::size_t Capacity = 16>
class BufferedKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  using Base::Base;

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    this->prepare(ray);
    resume_.clear();
    start_pass();
  }

  bool next(Hit& out) {
    Buffer p{*this};
    for (;;) {
      if (size_ > 0 && buf_[0].t < double(this->pending_.min_tn())) {
        out = buf_[0];
        for (std::size_t i = 1; i < size_; ++i) buf_[i - 1] = buf_[i];
        --size_;
        resume_.set(out);
        return true;
      }
      if (this->pending_.empty()) {
        if (!truncated_) return false;
        start_pass();  // hits were dropped: resume after the last released hit
        continue;
      }
      this->run(p);  // until a hit is resolved or nothing is left
    }
  }

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
    void culled(NodeEntry<T> node) { k.lose(node_key(node.tn)); }
    template <class Pending>
    bool suspend(T next_tn, const Pending& pending) const {
      if (k.size_ == 0) return false;
      const T m = pending.min_tn();
      return k.buf_[0].t < double(next_tn < m ? next_tn : m);
    }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) {
      const HitKey key = order_key(b, l, h);
      if (k.resume_.done(k.order_, key)) return;
      k.insert(key, b, l, h);
    }
  };

  void start_pass() {
    size_ = 0;
    truncated_ = false;
    have_cut_ = false;
    this->seed_root(lower(), this->ray_.tmax);
  }

  T lower() const { return resume_.lower(this->ray_.tmin); }
  T upper() const {
    const T u = size_ == Capacity ? T(buf_[Capacity - 1].t) : this->ray_.tmax;
    return have_cut_ && T(cut_.t) < u ? T(cut_.t) : u;
  }
  // A hit (or everything in a node, from `tn` on) left for a later pass.
  void lose(const HitKey& key) {
    truncated_ = true;
    if (!have_cut_ || this->order_.less(key, cut_)) cut_ = key, have_cut_ = true;
  }
  static HitKey node_key(T tn) {  // ranks before every hit at t >= tn, under either tie policy
    return {double(tn), 0, 0, false};
  }

  void insert(const HitKey& key, const TriBlock<T>& b, int lane, const TriangleHit<T>& th) {
    // At or past the cut it could be released before a lost hit that ranks first: a later pass finds it.
    if (have_cut_ && !this->order_.less(key, cut_)) return;
    if (size_ == Capacity) {
      if (!this->order_.less(key, buf_[Capacity - 1])) return lose(key);
      lose(key_of(buf_[Capacity - 1]));  // the farthest entry falls off
      --size_;
    }
    std::size_t i = size_;
    while (i > 0 && this->order_.less(key, buf_[i - 1])) {
      buf_[i] = buf_[i - 1];
      --i;
    }
    buf_[i] = make_hit(b, lane, th);
    ++size_;
  }

  std::array<Hit, Capacity> buf_{};
  std::size_t size_ = 0;
  bool truncated_ = false;
  HitKey cut_{};  // first hit lost in this pass (by the tie order); buffered hits all rank before it
  bool have_cut_ = false;
  ResumeAfter resume_;
};

}  // namespace pierce
