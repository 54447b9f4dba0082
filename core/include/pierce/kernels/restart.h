#pragma once
// `restart` (Wald et al. §3): each next() is a closest-hit query for the first hit after
// the last one in the total order. No epsilon: ties at equal t are resolved by (geom, prim).
#include <vector>

#include "pierce/kernels/bvh_common.h"

namespace pierce {

template <typename T>
class RestartKernel {
 public:
  explicit RestartKernel(const Bvh<T>& bvh, HitOrder order = {}) : bvh_(&bvh), order_(order) {}

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    have_last_ = false;
  }

  bool next(Hit& out) {
    if (bvh_->empty() || !ray_.valid()) return false;
    Hit best;
    T lo = ray_.tmin;
    if (have_last_) lo = std::max(lo, T(last_.t));
    T hi = ray_.tmax;
    stack_.clear();
    const Span<T> root = slab(ray_, bvh_->nodes[0].box.lo, bvh_->nodes[0].box.hi);
    PIERCE_COUNT(counters, node_tests, 1);
    if (box_overlaps(ray_, root, lo, hi)) stack_.push_back({root.tn, 0});
    while (!stack_.empty()) {
      const NodeEntry<T> e = stack_.back();
      stack_.pop_back();
      if (e.tn > hi) continue;  // culled by the current closest hit
      PIERCE_COUNT(counters, traversal_steps, 1);
      const BvhNode<T>& n = bvh_->nodes[e.node];
      PIERCE_COUNT(counters, leaf_visits, n.is_leaf() ? 1 : 0);
      if (!n.is_leaf()) {
        visit_children(*bvh_, n, ray_, lo, hi, counters,
                       [&](std::uint32_t c, T tn) { stack_.push_back({tn, c}); });
        continue;
      }
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Triangle<T>& tri = bvh_->tris[i];
        TriangleHit<T> th;
        PIERCE_COUNT(counters, prim_tests, 1);
        if (!intersect(ray_, tri.v0, tri.v1, tri.v2, lo, hi, th)) continue;
        PIERCE_COUNT(counters, valid_hits, 1);
        const Hit key = order_key(tri, th);
        if (have_last_ && !order_.less(last_, key)) continue;
        if (best.valid() && !order_.less(key, best)) continue;
        best = make_hit(tri, th);
        hi = th.t;
      }
    }
    if (!best.valid()) return false;
    last_ = best;
    have_last_ = true;
    out = best;
    return true;
  }

  Counters counters;

 private:
  const Bvh<T>* bvh_;
  HitOrder order_;
  TraversalRay<T> ray_;
  Hit last_;
  bool have_last_ = false;
  std::vector<NodeEntry<T>> stack_;
};

}  // namespace pierce
