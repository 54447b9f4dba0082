#pragma once
// Pieces shared by the kernels on Pierce's own BVH.
#include <limits>

#include "pierce/bvh.h"
#include "pierce/counters.h"
#include "pierce/hit.h"
#include "pierce/ray.h"

namespace pierce {

template <typename T>
inline Hit make_hit(const Triangle<T>& tri, const TriangleHit<T>& th) {
  Hit h;
  h.t = double(th.t);
  h.geom = tri.geom;
  h.prim = tri.prim;
  h.u = float(th.u);
  h.v = float(th.v);
  h.ng = Vec3f(cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
  h.enter = th.enter;
  return h;
}

// Hit identity for ordering without the full record: everything HitOrder looks at.
template <typename T>
inline Hit order_key(const Triangle<T>& tri, const TriangleHit<T>& th) {
  Hit h;
  h.t = double(th.t);
  h.geom = tri.geom;
  h.prim = tri.prim;
  h.enter = th.enter;
  return h;
}

template <typename T>
struct NodeEntry {
  T tn;  // entry distance of the node
  std::uint32_t node;
};

// Tests both children of an inner node against [lo, hi]; calls visit(child, tn) farthest first,
// so that a stack pops the nearer child next.
template <typename T, typename Visit>
inline void visit_children(const Bvh<T>& bvh, const BvhNode<T>& n, const TraversalRay<T>& r, T lo, T hi,
                           Counters& c, Visit&& visit) {
  const std::uint32_t a = n.first, b = n.first + 1;
  const Span<T> sa = slab(r, bvh.nodes[a].box.lo, bvh.nodes[a].box.hi);
  const Span<T> sb = slab(r, bvh.nodes[b].box.lo, bvh.nodes[b].box.hi);
  PIERCE_COUNT(c, node_tests, 2);
  (void)c;
  const bool ha = box_overlaps(r, sa, lo, hi), hb = box_overlaps(r, sb, lo, hi);
  if (ha && hb) {
    if (sb.tn < sa.tn) {
      visit(a, sa.tn), visit(b, sb.tn);
    } else {
      visit(b, sb.tn), visit(a, sa.tn);
    }
  } else if (ha) {
    visit(a, sa.tn);
  } else if (hb) {
    visit(b, sb.tn);
  }
}

}  // namespace pierce
