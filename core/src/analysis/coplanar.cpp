#include "pierce/analysis/coplanar.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "pierce/analysis/bvh_query.h"
#include "pierce/exact_predicates.h"
#include "pierce/analysis/polygon2d.h"
#include "pierce/bvh_builder.h"
#include "pierce/parallel_for_items.h"

namespace pierce::analysis {

namespace {

struct TriGeom {
  Vec3d v[3];
  Vec3d n;  // unit normal (double)
  double area;
};

TriGeom tri_geom(const Triangle<double>& t) {
  TriGeom g{{t.v0, t.v1, t.v2}, cross(t.v1 - t.v0, t.v2 - t.v0), 0};
  const double len = length(g.n);
  g.area = 0.5 * len;
  g.n = len > 0 ? g.n * (1.0 / len) : Vec3d{};
  return g;
}

// Corners of a triangle projected by dropping coordinate `axis`, counter-clockwise.
void project_ccw(const TriGeom& t, int axis, Vec2d out[3]) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  for (int k = 0; k < 3; ++k) out[k] = {t.v[k][i], t.v[k][j]};
  if (orient2d(out[0], out[1], out[2]) < 0) std::swap(out[1], out[2]);
}

// Interiors of two counter-clockwise triangles overlap unless an edge line of one has the
// other entirely on its closed outer side (separating axis for convex polygons).
bool interiors_overlap(const Vec2d a[3], const Vec2d b[3]) {
  auto separates = [](const Vec2d t[3], const Vec2d o[3]) {
    for (int e = 0; e < 3; ++e) {
      const Vec2d p = t[e], q = t[(e + 1) % 3];
      if (orient2d(p, q, o[0]) <= 0 && orient2d(p, q, o[1]) <= 0 && orient2d(p, q, o[2]) <= 0) return true;
    }
    return false;
  };
  return !separates(a, b) && !separates(b, a);
}

bool exactly_coplanar_overlap(const TriGeom& a, const TriGeom& b) {
  for (int k = 0; k < 3; ++k)
    if (orient3d(a.v[0], a.v[1], a.v[2], b.v[k]) != 0) return false;
  const int axis = std::abs(a.n.x) > std::abs(a.n.y) ? (std::abs(a.n.x) > std::abs(a.n.z) ? 0 : 2)
                                                     : (std::abs(a.n.y) > std::abs(a.n.z) ? 1 : 2);
  Vec2d pa[3], pb[3];
  project_ccw(a, axis, pa);
  project_ccw(b, axis, pb);
  if (orient2d(pa[0], pa[1], pa[2]) == 0 || orient2d(pb[0], pb[1], pb[2]) == 0) return false;
  return interiors_overlap(pa, pb);
}

double max_plane_distance(const TriGeom& plane, const TriGeom& t) {
  double d = 0;
  for (const Vec3d& p : t.v) d = std::max(d, std::abs(dot(p - plane.v[0], plane.n)));
  return d;
}

// Overlap of b's projection onto a's plane with a: area and centroid (3D, in a's plane).
double overlap_area(const TriGeom& a, const TriGeom& b, Vec3d& centroid) {
  Vec3d u = std::abs(a.n.x) < 0.6 ? cross(a.n, Vec3d{1, 0, 0}) : cross(a.n, Vec3d{0, 1, 0});
  u = u * (1.0 / length(u));
  const Vec3d v = cross(a.n, u);
  auto to2d = [&](Vec3d p) { return Vec2d{dot(p - a.v[0], u), dot(p - a.v[0], v)}; };
  std::vector<Vec2d> pa{to2d(a.v[0]), to2d(a.v[1]), to2d(a.v[2])};
  std::vector<Vec2d> pb{to2d(b.v[0]), to2d(b.v[1]), to2d(b.v[2])};
  if (signed_area(pa) < 0) std::swap(pa[1], pa[2]);
  if (signed_area(pb) < 0) std::swap(pb[1], pb[2]);
  const std::vector<Vec2d> poly = clip_convex(pb, pa);
  const double area = poly.size() >= 3 ? std::abs(signed_area(poly)) : 0.0;
  Vec2d c{};
  for (const Vec2d& p : poly) c.x += p.x, c.y += p.y;
  if (!poly.empty()) c.x /= double(poly.size()), c.y /= double(poly.size());
  centroid = a.v[0] + u * c.x + v * c.y;
  return area;
}

bool key_less(const Triangle<double>& a, const Triangle<double>& b) {
  return a.geom != b.geom ? a.geom < b.geom : a.prim < b.prim;
}

}  // namespace

CoplanarReport find_coplanar_overlaps(const Scene& scene, const CoplanarOptions& opts, const Progress& progress) {
  if (!(opts.tolerance >= 0) || !std::isfinite(opts.tolerance))
    throw std::invalid_argument("coplanar overlaps: tolerance must be finite and >= 0");
  CoplanarReport rep;
  rep.tolerance = opts.tolerance;
  const WideBvhd bvh = build_wide_bvh<double>(scene);
  // Its (non-degenerate) triangles, each tested against those whose boxes overlap its own.
  std::vector<Triangle<double>> tris;
  tris.reserve(bvh.triangles);
  for (const TriBlock<double>& b : bvh.blocks)
    for (std::uint32_t m = b.valid; m != 0; m &= m - 1) tris.push_back(b.triangle(__builtin_ctz(m)));
  const std::size_t total = tris.size();
  struct Local {
    std::vector<CoplanarPair> pairs;
    NodeStack<double> stack;
  };
  tbb::enumerable_thread_specific<Local> locals;
  const bool completed = parallel_for_items(total, 256, locals, progress, [&](Local& L, std::size_t i) {
    const Triangle<double>& ta = tris[i];
    const TriGeom a = tri_geom(ta);
    if (a.n == Vec3d{}) return;
    BBoxd box;
    box.extend(ta.v0), box.extend(ta.v1), box.extend(ta.v2);
    box.lo = box.lo - Vec3d{opts.tolerance, opts.tolerance, opts.tolerance};
    box.hi = box.hi + Vec3d{opts.tolerance, opts.tolerance, opts.tolerance};
    for_each_overlapping(bvh, box, L.stack, [&](const Triangle<double>& tb) {
      if (!key_less(ta, tb)) return;
      const TriGeom b = tri_geom(tb);
      if (b.n == Vec3d{}) return;
      // Cheap rejection: far from each other's planes (with slack for rounding).
      const double slack = opts.tolerance + 1e-9 * (max_abs(ta.v0) + max_abs(tb.v0));
      if (max_plane_distance(a, b) > slack || max_plane_distance(b, a) > slack) return;
      CoplanarPair p{ta.geom, ta.prim, tb.geom, tb.prim, 0, {}, false, dot(a.n, b.n) > 0};
      p.exact = exactly_coplanar_overlap(a, b);
      if (!p.exact && opts.tolerance == 0) return;
      p.area = overlap_area(a, b, p.centroid);
      if (!p.exact && !(p.area > opts.min_area_rel * std::min(a.area, b.area))) return;
      L.pairs.push_back(p);
    });
  });
  if (!completed) {
    rep.completed = false;
    return rep;
  }
  for (auto& L : locals) rep.pairs.insert(rep.pairs.end(), L.pairs.begin(), L.pairs.end());
  std::sort(rep.pairs.begin(), rep.pairs.end(), [](const CoplanarPair& x, const CoplanarPair& y) {
    return std::tie(x.geom_a, x.prim_a, x.geom_b, x.prim_b) < std::tie(y.geom_a, y.prim_a, y.geom_b, y.prim_b);
  });
  std::map<std::pair<std::uint32_t, std::uint32_t>, CoplanarSolidPair> per;
  std::map<std::pair<std::uint32_t, std::uint32_t>, double> largest;
  for (const CoplanarPair& p : rep.pairs) {
    const auto key = std::minmax(p.geom_a, p.geom_b);
    CoplanarSolidPair& s = per[{key.first, key.second}];
    s.a = key.first;
    s.b = key.second;
    ++s.pairs;
    s.exact_pairs += p.exact;
    s.same_facing += p.same_facing;
    s.opposite_facing += !p.same_facing;
    s.area += p.area;
    double& best = largest[{key.first, key.second}];
    if (s.pairs == 1 || p.area > best) best = p.area, s.where = p.centroid;
  }
  for (auto& [k, s] : per) rep.solid_pairs.push_back(s);
  return rep;
}

}  // namespace pierce::analysis
