#pragma once
// Proximity queries on Pierce's double-precision wide BVH, run on the one traversal
// (proximity.h): closest point on the triangles to a query point, and enumeration of the
// triangles whose boxes overlap a query box.
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

#include "pierce/hit.h"
#include "pierce/proximity.h"
#include "pierce/scene.h"
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

// Calls f(const Triangle<T>&) (corners in the input's order) for every triangle in the leaves
// reached by descending through the child slots that pass `enter(const BBox<T>& box)` or, where
// the test needs to know the slot, `enter(box, const WideNode<T>& node, int slot)` (from the
// root's children down; a root leaf's triangles are all given). `stack` is scratch space reused
// between calls.
template <typename T, typename Enter, typename F>
void for_each_entered(const WideBvh<T>& bvh, NodeStack<T>& stack, Enter&& enter, F&& f) {
  struct Each : ProximityPolicy<T> {
    F& f;
    explicit Each(F& fn) : f(fn) {}
    T hi() const { return 0; }
    T cull_bound() const { return 0; }
    void leaf(const TriBlock<T>& b) {
      for (std::uint32_t m = b.valid; m != 0; m &= m - 1) {
        const int l = __builtin_ctz(m);
        f(b.triangle(l));
      }
    }
  } p{f};
  auto entered = [&](const WideNode<T>& n, T* key) {
    std::uint32_t mask = 0;
    for (int s = 0; s < kWideArity; ++s) {
      key[s] = 0;  // no order: every node entered is visited
      BBox<T> box;
      box.lo = {n.lo[0][s], n.lo[1][s], n.lo[2][s]};
      box.hi = {n.hi[0][s], n.hi[1][s], n.hi[2][s]};
      bool in;
      if constexpr (std::is_invocable_v<Enter&, const BBox<T>&, const WideNode<T>&, int>)
        in = enter(static_cast<const BBox<T>&>(box), n, s);
      else
        in = enter(static_cast<const BBox<T>&>(box));
      if (in) mask |= 1u << s;
    }
    return mask;
  };
  traverse_proximity(bvh, stack, entered, p);
}

// Whether closed boxes a and b overlap.
template <typename A, typename B>
bool boxes_overlap(const BBox<A>& a, const BBox<B>& b) {
  return double(a.lo.x) <= double(b.hi.x) && double(a.hi.x) >= double(b.lo.x) && double(a.lo.y) <= double(b.hi.y) &&
         double(a.hi.y) >= double(b.lo.y) && double(a.lo.z) <= double(b.hi.z) && double(a.hi.z) >= double(b.lo.z);
}

// Calls f(const Triangle<double>&) for every triangle whose box overlaps `box` (closed test).
template <typename F>
void for_each_overlapping(const WideBvhd& bvh, const BBoxd& box, NodeStack<double>& stack, F&& f) {
  auto overlaps = [&](const BBoxd& b) { return boxes_overlap(b, box); };
  for_each_entered(bvh, stack, overlaps, [&](const Triangle<double>& t) {
    BBoxd tb;
    tb.extend(t.v0), tb.extend(t.v1), tb.extend(t.v2);
    if (overlaps(tb)) f(t);
  });
}

// How far a float BVH's corners, and so its boxes, may lie from the scene's double coordinates:
// a float corner lies within |x| * 2^-24 of the double it rounds; twice that for the scene's
// largest coordinate, plus the smallest float.
inline double float_rounding_margin(const WideBvhf& bvh) {
  return bvh.scene_max_abs * 0x1p-23 + double(std::numeric_limits<float>::denorm_min());
}

// The same triangles as above, in double precision from `scene`, found on the float BVH built
// from it (Accel::wide()), so that a query needs no double BVH. Nodes are entered with `box`
// grown by float_rounding_margin(): every triangle whose double box overlaps `box` is reached
// (and its float box overlaps the grown one), then tested exactly. The calls come in the float
// BVH's order.
template <typename F>
void for_each_overlapping(const Scene& scene, const WideBvhf& bvh, const BBoxd& box, NodeStack<float>& stack, F&& f) {
  const double grow = float_rounding_margin(bvh);
  BBoxd entry = box;
  entry.lo = entry.lo - Vec3d{grow, grow, grow};
  entry.hi = entry.hi + Vec3d{grow, grow, grow};
  auto enter = [&](const BBoxf& b) { return boxes_overlap(b, entry); };
  for_each_entered(bvh, stack, enter, [&](const Triangle<float>& tf) {
    BBoxf fb;  // the float corners' box: it misses `entry` only if the double one misses `box`
    fb.extend(tf.v0), fb.extend(tf.v1), fb.extend(tf.v2);
    if (!boxes_overlap(fb, entry)) return;
    const Geometry& g = scene.geometry(tf.geom);
    const Tri& c = g.triangles[tf.prim];
    const Triangle<double> t{g.vertices[c[0]], g.vertices[c[1]], g.vertices[c[2]], tf.geom, tf.prim};
    BBoxd tb;
    tb.extend(t.v0), tb.extend(t.v1), tb.extend(t.v2);
    if (boxes_overlap(tb, box)) f(t);
  });
}

}  // namespace pierce::analysis
