#pragma once
// Proximity queries on Pierce's double-precision wide BVH, run on the one traversal
// (proximity.h): closest point on the triangles to a query point, and enumeration of the
// triangles whose boxes overlap a query box.
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "pierce/hit.h"
#include "pierce/proximity.h"
#include "pierce/wide_bvh.h"

namespace pierce::analysis {

// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3d closest_point_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c);

struct ClosestPoint {
  double dist2 = std::numeric_limits<double>::infinity();
  Vec3d point;
  std::uint32_t geom = kInvalidId, prim = kInvalidId;
  bool found() const { return prim != kInvalidId; }
};

// Nearest point to `q` on the BVH's triangles within squared distance `max_dist2`, skipping the
// primitives listed in `exclude` (ids of Triangle::prim; small, searched linearly). Of equally
// near triangles, the one with the lowest (geom, prim) gives the point, whatever the BVH's layout.
// `stack` is scratch space reused between calls.
ClosestPoint closest_point(const WideBvhd& bvh, Vec3d q, double max_dist2, std::span<const std::uint32_t> exclude,
                           NodeStack<double>& stack);

// Calls f(const Triangle<double>&) (corners in the input's order) for every triangle in the leaves
// reached by descending through the nodes whose box passes `enter(const BBoxd&)` (from the root's
// children down; a root leaf's triangles are all given). `stack` is scratch space reused between
// calls.
template <typename Enter, typename F>
void for_each_entered(const WideBvhd& bvh, NodeStack<double>& stack, Enter&& enter, F&& f) {
  struct Each : ProximityPolicy<double> {
    F& f;
    explicit Each(F& fn) : f(fn) {}
    double hi() const { return 0; }
    double cull_bound() const { return 0; }
    void leaf(const TriBlock<double>& b) {
      for (std::uint32_t m = b.valid; m != 0; m &= m - 1) {
        const int l = __builtin_ctz(m);
        f(b.triangle(l));
      }
    }
  } p{f};
  auto entered = [&](const WideNode<double>& n, double* key) {
    std::uint32_t mask = 0;
    for (int s = 0; s < kWideArity; ++s) {
      key[s] = 0;  // no order: every node entered is visited
      BBoxd box;
      box.lo = {n.lo[0][s], n.lo[1][s], n.lo[2][s]};
      box.hi = {n.hi[0][s], n.hi[1][s], n.hi[2][s]};
      if (enter(static_cast<const BBoxd&>(box))) mask |= 1u << s;
    }
    return mask;
  };
  traverse_proximity(bvh, stack, entered, p);
}

// Calls f(const Triangle<double>&) for every triangle whose box overlaps `box` (closed test).
template <typename F>
void for_each_overlapping(const WideBvhd& bvh, const BBoxd& box, NodeStack<double>& stack, F&& f) {
  auto overlaps = [&](const BBoxd& b) {
    return b.lo.x <= box.hi.x && b.hi.x >= box.lo.x && b.lo.y <= box.hi.y && b.hi.y >= box.lo.y &&
           b.lo.z <= box.hi.z && b.hi.z >= box.lo.z;
  };
  for_each_entered(bvh, stack, overlaps, [&](const Triangle<double>& t) {
    BBoxd tb;
    tb.extend(t.v0), tb.extend(t.v1), tb.extend(t.v2);
    if (overlaps(tb)) f(t);
  });
}

}  // namespace pierce::analysis
