#pragma once
// `filter` (Amstutz et al. 2015, all hits): one traversal gathers every hit in [tmin, tmax],
// sorted once in the total order; next() walks the sorted list.
#include <algorithm>
#include <vector>

#include "pierce/kernels/bvh_common.h"

namespace pierce {

template <typename T>
class AllHitsKernel {
 public:
  explicit AllHitsKernel(const Bvh<T>& bvh, HitOrder order = {}) : bvh_(&bvh), order_(order) {}

  void begin(const Ray& ray, std::size_t /*max_hits*/ = 0) {
    const TraversalRay<T> r = TraversalRay<T>::make(ray, bvh_->scene_max_abs);
    hits_.clear();
    pos_ = 0;
    if (bvh_->empty() || !r.valid()) return;
    stack_.clear();
    const Span<T> root = slab(r, bvh_->nodes[0].box.lo, bvh_->nodes[0].box.hi);
    PIERCE_COUNT(counters, node_tests, 1);
    if (box_overlaps(r, root, r.tmin, r.tmax)) stack_.push_back(0);
    while (!stack_.empty()) {
      const BvhNode<T>& n = bvh_->nodes[stack_.back()];
      stack_.pop_back();
      PIERCE_COUNT(counters, traversal_steps, 1);
      PIERCE_COUNT(counters, leaf_visits, n.is_leaf() ? 1 : 0);
      if (!n.is_leaf()) {
        visit_children(*bvh_, n, r, r.tmin, r.tmax, counters, [&](std::uint32_t c, T) { stack_.push_back(c); });
        continue;
      }
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) {
        const Triangle<T>& tri = bvh_->tris[i];
        TriangleHit<T> th;
        PIERCE_COUNT(counters, prim_tests, 1);
        if (!intersect(r, tri.v0, tri.v1, tri.v2, r.tmin, r.tmax, th)) continue;
        PIERCE_COUNT(counters, valid_hits, 1);
        hits_.push_back(make_hit(tri, th));
      }
    }
    std::sort(hits_.begin(), hits_.end(), order_);
  }

  bool next(Hit& out) {
    if (pos_ >= hits_.size()) return false;
    out = hits_[pos_++];
    return true;
  }

  Counters counters;

 private:
  const Bvh<T>* bvh_;
  HitOrder order_;
  std::vector<std::uint32_t> stack_;
  std::vector<Hit> hits_;
  std::size_t pos_ = 0;
};

}  // namespace pierce
