#pragma once
// `nodecull` (Gribble 2016): N-closest hits. Hits go into a bounded max-heap; once it holds
// N hits, nodes entered beyond the N-th hit are culled. N comes from the max-hits hint
// (0 = all hits). If more than N hits are asked for, the next batch of N starts after the
// last hit returned, so the sequence is complete for any N.
#include <algorithm>
#include <limits>
#include <vector>

#include "pierce/kernels/bvh_common.h"

namespace pierce {

template <typename T>
class NodeCullKernel {
 public:
  explicit NodeCullKernel(const Bvh<T>& bvh, HitOrder order = {}) : bvh_(&bvh), order_(order) {}

  void begin(const Ray& ray, std::size_t max_hits = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    n_ = max_hits == 0 ? std::numeric_limits<std::size_t>::max() : max_hits;
    batch_.clear();
    pos_ = 0;
    have_last_ = false;
    exhausted_ = bvh_->empty() || !ray_.valid();
  }

  bool next(Hit& out) {
    if (pos_ == batch_.size()) {
      if (exhausted_) return false;
      collect();
      if (batch_.size() < n_) exhausted_ = true;  // a short batch holds every remaining hit
      if (batch_.empty()) return false;
    }
    out = batch_[pos_++];
    last_ = out;
    have_last_ = true;
    return true;
  }

  Counters counters;

 private:
  struct HitBefore {
    HitOrder order;
    bool operator()(const Hit& a, const Hit& b) const { return order.less(a, b); }
  };

  // The n_ closest hits after last_ into batch_, sorted.
  void collect() {
    batch_.clear();
    pos_ = 0;
    const HitBefore before{order_};
    const T lo = have_last_ ? std::max(ray_.tmin, T(last_.t)) : ray_.tmin;
    auto hi = [&] { return batch_.size() == n_ ? T(batch_.front().t) : ray_.tmax; };
    stack_.clear();
    const Span<T> root = slab(ray_, bvh_->nodes[0].box.lo, bvh_->nodes[0].box.hi);
    PIERCE_COUNT(counters, node_tests, 1);
    if (box_overlaps(ray_, root, lo, ray_.tmax)) stack_.push_back({root.tn, 0});
    while (!stack_.empty()) {
      const NodeEntry<T> e = stack_.back();
      stack_.pop_back();
      if (e.tn > hi()) continue;  // node culling
      PIERCE_COUNT(counters, traversal_steps, 1);
      const BvhNode<T>& n = bvh_->nodes[e.node];
      PIERCE_COUNT(counters, leaf_visits, n.is_leaf() ? 1 : 0);
      if (!n.is_leaf()) {
        visit_children(*bvh_, n, ray_, lo, hi(), counters,
                       [&](std::uint32_t c, T tn) { stack_.push_back({tn, c}); });
        continue;
      }
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Triangle<T>& tri = bvh_->tris[i];
        TriangleHit<T> th;
        PIERCE_COUNT(counters, prim_tests, 1);
        if (!intersect(ray_, tri.v0, tri.v1, tri.v2, lo, hi(), th)) continue;
        PIERCE_COUNT(counters, valid_hits, 1);
        const Hit key = order_key(tri, th);
        if (have_last_ && !order_.less(last_, key)) continue;
        if (batch_.size() == n_) {
          if (!order_.less(key, batch_.front())) continue;
          std::pop_heap(batch_.begin(), batch_.end(), before);  // max-heap: front is the N-th hit
          batch_.pop_back();
        }
        batch_.push_back(make_hit(tri, th));
        std::push_heap(batch_.begin(), batch_.end(), before);
      }
    }
    std::sort_heap(batch_.begin(), batch_.end(), before);
  }

  const Bvh<T>* bvh_;
  HitOrder order_;
  TraversalRay<T> ray_;
  std::size_t n_ = 0;
  std::vector<Hit> batch_;
  std::size_t pos_ = 0;
  Hit last_;
  bool have_last_ = false;
  bool exhausted_ = true;
  std::vector<NodeEntry<T>> stack_;
};

}  // namespace pierce
