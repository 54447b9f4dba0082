#pragma once
// `queue` (Wald et al. §4): front-to-back traversal with a priority queue of untraversed
// nodes and a priority queue of found hits. A hit is returned once it is strictly closer
// than every untraversed node; the state survives between next() calls.
#include <algorithm>
#include <vector>

#include "pierce/kernels/bvh_common.h"

namespace pierce {

template <typename T>
class QueueKernel {
 public:
  explicit QueueKernel(const Bvh<T>& bvh, HitOrder order = {}) : bvh_(&bvh), order_(order) {}

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    ray_ = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    nodes_.clear();
    hits_.clear();
    if (bvh_->empty() || !ray_.valid()) return;
    const Span<T> root = slab(ray_, bvh_->nodes[0].box.lo, bvh_->nodes[0].box.hi);
    PIERCE_COUNT(counters, node_tests, 1);
    if (box_overlaps(ray_, root, ray_.tmin, ray_.tmax)) push_node({root.tn, 0});
  }

  bool next(Hit& out) {
    for (;;) {
      // Strict: a node entered at exactly the hit's t may still hold a hit that ranks first.
      if (!hits_.empty() && (nodes_.empty() || hits_.front().t < double(nodes_.front().tn))) {
        std::pop_heap(hits_.begin(), hits_.end(), hit_after_);
        out = hits_.back();
        hits_.pop_back();
        return true;
      }
      if (nodes_.empty()) return false;
      std::pop_heap(nodes_.begin(), nodes_.end(), node_after);
      const std::uint32_t ni = nodes_.back().node;
      nodes_.pop_back();
      PIERCE_COUNT(counters, traversal_steps, 1);
      const BvhNode<T>& n = bvh_->nodes[ni];
      PIERCE_COUNT(counters, leaf_visits, n.is_leaf() ? 1 : 0);
      if (!n.is_leaf()) {
        visit_children(*bvh_, n, ray_, ray_.tmin, ray_.tmax, counters,
                       [&](std::uint32_t c, T tn) { push_node({tn, c}); });
        continue;
      }
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Triangle<T>& tri = bvh_->tris[i];
        TriangleHit<T> th;
        PIERCE_COUNT(counters, prim_tests, 1);
        if (!intersect(ray_, tri.v0, tri.v1, tri.v2, ray_.tmin, ray_.tmax, th)) continue;
        PIERCE_COUNT(counters, valid_hits, 1);
        hits_.push_back(make_hit(tri, th));
        std::push_heap(hits_.begin(), hits_.end(), hit_after_);
      }
    }
  }

  Counters counters;

 private:
  static bool node_after(const NodeEntry<T>& a, const NodeEntry<T>& b) { return a.tn > b.tn; }
  struct HitAfter {
    HitOrder order;
    bool operator()(const Hit& a, const Hit& b) const { return order.less(b, a); }
  };
  void push_node(NodeEntry<T> e) {
    nodes_.push_back(e);
    std::push_heap(nodes_.begin(), nodes_.end(), node_after);
  }

  const Bvh<T>* bvh_;
  HitOrder order_;
  HitAfter hit_after_{order_};
  TraversalRay<T> ray_;
  std::vector<NodeEntry<T>> nodes_;  // min-heap on tn
  std::vector<Hit> hits_;            // min-heap in hit order
};

}  // namespace pierce
