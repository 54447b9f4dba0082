#include "pierce/analysis/bvh_query.h"

#include <algorithm>

namespace pierce::analysis {

Vec3d closest_point_on_triangle(Vec3d p, Vec3d a, Vec3d b, Vec3d c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

namespace {
// The nearest triangle so far bounds the search: a box farther than it is not entered.
struct Closest : ProximityPolicy<double> {
  Vec3d q;
  std::span<const std::uint32_t> exclude;
  ClosestPoint best;
  double hi() const { return best.dist2; }
  double cull_bound() const { return best.dist2; }
  void leaf(const TriBlock<double>& b) {
    double box2[kBlockLanes];
    lane_box_distances2(b, q, box2);
    for (std::uint32_t m = b.valid; m != 0; m &= m - 1) {
      const int l = __builtin_ctz(m);
      if (box2[l] > beyond_bound(best.dist2)) continue;
      const std::uint32_t geom = b.geom[l], prim = b.prim[l];
      if (std::find(exclude.begin(), exclude.end(), prim) != exclude.end()) continue;
      const Vec3d c = closest_point_on_triangle(q, b.input_corner(0, l), b.input_corner(1, l), b.input_corner(2, l));
      const Vec3d d = c - q;
      const double d2 = dot(d, d);
      // Among equally near triangles the lowest (geom, prim) wins, not the first the walk meets:
      // their closest points can differ in the last bits, and the answer must not depend on the
      // BVH's layout (the builder, the thread count).
      const bool first_of_tie =
          d2 == best.dist2 && (!best.found() || geom < best.geom || (geom == best.geom && prim < best.prim));
      if (d2 < best.dist2 || first_of_tie) {
        best.dist2 = d2;
        best.point = c;
        best.geom = geom;
        best.prim = prim;
      }
    }
  }
};
}  // namespace

ClosestPoint closest_point(const WideBvhd& bvh, Vec3d q, double max_dist2, std::span<const std::uint32_t> exclude,
                           NodeStack<double>& stack) {
  Closest p;
  p.q = q;
  p.exclude = exclude;
  p.best.dist2 = max_dist2;
  auto by_distance = [&](const WideNode<double>& n, double* key) {
    box_distances2(n, q, key);
    return 0xFFu;
  };
  traverse_proximity(bvh, stack, by_distance, p);
  return p.best;
}

}  // namespace pierce::analysis
