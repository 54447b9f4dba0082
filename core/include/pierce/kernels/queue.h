#pragma once
// `queue` (Wald et al. §4): a hit is returned once it is strictly closer than every untraversed
// node, so the caller can stop at any hit and pays only for the nodes in front of it; the state
// survives between next() calls.
//
// The paper keeps every untraversed node in a priority queue. Here the queue holds only the nodes
// that cannot matter yet: the traversal runs depth first on the stack, near child first, and a
// node entered beyond the bound is not traversed but moved onto the heap. The bound is the N-th
// nearest hit held but not yet returned, N the max_hits hint (without one, N = 1: the nearest hit,
// as in `restart`, so a caller that stops early pays for the nodes in front of that hit only).
// Every node in front of the bound must be traversed anyway, so the heap sees only the few
// deferred subtrees instead of every child of every node; a next() that needs more pops the
// nearest deferred node and runs the same depth-first pass from it.
// Why the hits come out complete and in order: when a pass ends, every node not traversed is on
// the heap; the nearest hit held is returned only while it is strictly nearer than the nearest
// node on the heap (a node entered at exactly its t may hold a hit that ranks first).
#include <algorithm>
#include <vector>

#include "pierce/kernels/wide_kernel.h"

namespace pierce {

// C: the counter policy (counters.h).
template <typename T, class C = NoCounters>
class QueueKernel : public WideKernel<T, C> {
  using Base = WideKernel<T, C>;

 public:
  explicit QueueKernel(const WideBvh<T>& bvh, HitOrder order = {}) : Base(bvh, order) {
    hits_.reserve(16);
    deferred_.reserve(4 * bvh.stack_capacity());
  }

  void begin(const Ray& ray, std::size_t max_hits = 0) {
    this->prepare(ray);
    hits_.clear();
    pos_ = 0;
    depth_ = max_hits == 0 ? 1 : max_hits;
    bound_ = this->ray_.tmax;
    deferred_.clear();
    // The first pass, from the root (what the first next() would do, without the heap).
    this->seed_root(this->ray_.tmin, this->ray_.tmax);
    Descend p{*this};
    this->run(p);
  }

  bool next(Hit& out) {
    for (;;) {
      if (pos_ < hits_.size() && (deferred_.empty() || hits_[pos_].t < double(deferred_.next_tn()))) {
        out = hits_[pos_++];
        update_bound();
        return true;
      }
      if (deferred_.empty()) return false;
      this->pending_.clear();
      this->pending_.push(deferred_.pop());
      Descend p{*this};
      this->run(p);  // depth first from the nearest deferred node, deferring what lies beyond the bound
    }
  }

 private:
  // Every hit is held in order; a node entered beyond the depth_-th held hit not yet returned is
  // deferred. Children are pushed onto the stack unchecked (the fast SIMD push) and checked when
  // popped.
  struct Descend : TraversalPolicy<T> {
    QueueKernel& k;
    explicit Descend(QueueKernel& kernel) : k(kernel) {}
    T lo() const { return k.ray_.tmin; }
    T hi() const { return k.ray_.tmax; }
    T cull_bound() const { return k.bound_; }
    void culled(NodeEntry<T> node) { k.deferred_.push(node); }
    void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) { k.hold(make_hit(b, l, h)); }
  };

  // Inserted in order; the depth-first pass meets hits roughly near to far, so from the back.
  void hold(const Hit& h) {
    std::size_t i = hits_.size();
    hits_.push_back(h);
    while (i > pos_ && this->order_.less(h, hits_[i - 1])) {
      hits_[i] = hits_[i - 1];
      --i;
    }
    hits_[i] = h;
    update_bound();
  }
  void update_bound() {
    bound_ = hits_.size() - pos_ >= depth_ ? T(hits_[pos_ + depth_ - 1].t) : this->ray_.tmax;
  }

  std::vector<Hit> hits_;  // held hits in hit order; those before pos_ were returned
  std::size_t pos_ = 0;
  std::size_t depth_ = 1;  // the bound is the depth_-th held hit not yet returned
  T bound_ = 0;            // its t (tmax while fewer are held)
  NodeHeap<T> deferred_;   // nodes entered beyond the bound, nearest first
};

}  // namespace pierce
