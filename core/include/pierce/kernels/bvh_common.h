#pragma once
// Hit records for a float/double triangle (the Embree-based kernels; the wide-BVH kernels use
// the leaf-block versions in traverse.h).
#include <limits>

#include "pierce/bvh.h"
#include "pierce/counters.h"
#include "pierce/hit.h"
#include "pierce/ray.h"

namespace pierce {

// Hit identity for ordering without the full record: everything HitOrder looks at.
template <typename T>
inline HitKey order_key(const Triangle<T>& tri, const TriangleHit<T>& th) {
  return {double(th.t), tri.geom, tri.prim, th.enter};
}

template <typename T>
inline Hit make_hit(const Triangle<T>& tri, const TriangleHit<T>& th) {
  return hit_of(order_key(tri, th), float(th.u), float(th.v), Vec3f(cross(tri.v1 - tri.v0, tri.v2 - tri.v0)));
}

}  // namespace pierce
