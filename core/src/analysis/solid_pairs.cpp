#include "pierce/analysis/solid_pairs.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "pierce/analysis/bvh_query.h"
#include "pierce/exact_predicates.h"
#include "pierce/parallel_for_items.h"

namespace pierce::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Closest2 {
  double dist2 = std::numeric_limits<double>::infinity();
  Vec3d on_a, on_b;
  void offer(double d2, Vec3d a, Vec3d b) {
    if (d2 < dist2) dist2 = d2, on_a = a, on_b = b;
  }
};

// Closest points of segments p1q1 and p2q2 (Ericson, Real-Time Collision Detection, 5.1.9).
void closest_on_segments(Vec3d p1, Vec3d q1, Vec3d p2, Vec3d q2, Closest2& best) {
  const Vec3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
  double s = 0, t = 0;
  if (a > 0 && e > 0) {
    const double b = dot(d1, d2), c = dot(d1, r), denom = a * e - b * b;
    s = denom > 0 ? clamp01((b * f - c * e) / denom) : 0;
    t = (b * s + f) / e;
    if (t < 0) t = 0, s = clamp01(-c / a);
    else if (t > 1) t = 1, s = clamp01((b - c) / a);
  } else if (a > 0) {
    s = clamp01(-dot(d1, r) / a);
  } else if (e > 0) {
    t = clamp01(f / e);
  }
  const Vec3d p = p1 + d1 * s, q = p2 + d2 * t, d = p - q;
  best.offer(dot(d, d), p, q);
}

// Where segment pq crosses the interior or boundary of triangle t (Moller-Trumbore); false when it
// does not or lies in the triangle's plane (coplanar contact is found by the other features).
bool segment_crosses(Vec3d p, Vec3d q, const Vec3d t[3], Vec3d& at) {
  const Vec3d d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0];
  const Vec3d h = cross(d, e2);
  const double det = dot(e1, h);
  if (det == 0) return false;
  const double inv = 1 / det;
  const Vec3d s = p - t[0];
  const double u = dot(s, h) * inv;
  if (u < 0 || u > 1) return false;
  const Vec3d g = cross(s, e1);
  const double v = dot(d, g) * inv;
  if (v < 0 || u + v > 1) return false;
  const double w = dot(e2, g) * inv;
  if (w < 0 || w > 1) return false;
  at = p + d * w;
  return true;
}

// Whether the corners of q lie strictly on one side of p's plane (false if p is degenerate).
bool strictly_beside(const Vec3d p[3], const Vec3d q[3]) {
  const int s = orient3d(p[0], p[1], p[2], q[0]);
  return s != 0 && orient3d(p[0], p[1], p[2], q[1]) == s && orient3d(p[0], p[1], p[2], q[2]) == s;
}

bool is_degenerate_triangle(const Vec3d t[3]) {
  const Vec3d n = cross(t[1] - t[0], t[2] - t[0]);
  return !(dot(n, n) > 0);
}

}  // namespace

TrianglePairDistance triangle_distance(const Vec3d a[3], const Vec3d b[3]) {
  // Intersecting triangles: an edge of one crosses the other (or, coplanar, an edge crosses an edge
  // or a corner lies inside, which the features below find at distance 0). Triangles on strict
  // sides of one's plane (decided exactly) cannot intersect, and skip the crossing tests.
  if (!strictly_beside(a, b) && !strictly_beside(b, a))
    for (int k = 0; k < 3; ++k) {
      Vec3d at;
      if (segment_crosses(a[k], a[(k + 1) % 3], b, at) || segment_crosses(b[k], b[(k + 1) % 3], a, at))
        return {0, at, at};
    }
  // Otherwise the closest points are a corner and the other triangle, or two edges.
  Closest2 best;
  for (int k = 0; k < 3; ++k) {
    const Vec3d pb = closest_point_on_triangle(a[k], b[0], b[1], b[2]), db = pb - a[k];
    best.offer(dot(db, db), a[k], pb);
    const Vec3d pa = closest_point_on_triangle(b[k], a[0], a[1], a[2]), da = pa - b[k];
    best.offer(dot(da, da), pa, b[k]);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) closest_on_segments(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], best);
  return {best.dist2, best.on_a, best.on_b};
}

namespace {

// One triangle's nearest point in one other solid.
struct Near {
  std::uint32_t other = 0;
  double dist2 = 0;
  Vec3d on_self, on_other;
};

// Nearer, or as near with the lexicographically smaller points: one closest pair whatever the
// order in which the candidates come.
bool nearer(const Near& x, const Near& y) {
  return std::tuple(x.dist2, x.on_self.x, x.on_self.y, x.on_self.z, x.on_other.x, x.on_other.y, x.on_other.z) <
         std::tuple(y.dist2, y.on_self.x, y.on_self.y, y.on_self.z, y.on_other.x, y.on_other.y, y.on_other.z);
}

void corners(const Geometry& g, std::uint32_t p, Vec3d out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = g.vertices[g.triangles[p][k]];
}

constexpr std::uint32_t kMixedSolids = kInvalidId;

// The solid below each child slot of the BVH (index node * kWideArity + slot), or kMixedSolids
// where the subtree holds triangles of more than one solid or the slot is unused. Writes the
// slots below `ref` and returns the solid of `ref`'s subtree.
std::uint32_t solid_below(const WideBvhf& bvh, NodeRef ref, std::vector<std::uint32_t>& slot_solid) {
  std::uint32_t solid = kInvalidId - 1;  // none seen yet
  auto merge = [&](std::uint32_t g) { solid = solid == kInvalidId - 1 || solid == g ? g : kMixedSolids; };
  if (is_leaf(ref)) {
    for (std::uint32_t b = leaf_first_block(ref), e = b + leaf_block_count(ref); b < e; ++b)
      for (std::uint32_t m = bvh.blocks[b].valid; m != 0; m &= m - 1) merge(bvh.blocks[b].geom[__builtin_ctz(m)]);
  } else {
    const WideNode<float>& n = bvh.nodes[ref];
    for (int k = 0; k < kWideArity; ++k)
      if (n.valid() >> k & 1u) merge(slot_solid[std::size_t(ref) * kWideArity + std::size_t(k)] = solid_below(bvh, n.child[k], slot_solid));
  }
  return solid;
}

// Squared distance between two boxes (0 where they overlap): a lower bound on the squared
// distance between anything inside them.
double box_distance2(const BBoxd& a, const BBoxd& b) {
  double d2 = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const double gap = std::max({a.lo[k] - b.hi[k], b.lo[k] - a.hi[k], 0.0});
    d2 += gap * gap;
  }
  return d2;
}

// A triangle of another solid near a leaf's triangles: its corners, box and plane (unit normal
// n, offset w: dot(n, x) = w in the plane; found when first needed).
struct Candidate {
  std::uint32_t geom, prim;
  Vec3d c[3];
  BBoxd box;
  Vec3d n;
  double w = 0;
  bool has_plane = false;
};

// The plane of triangle t as (unit normal, offset); a zero normal where the corners are too
// close to collinear for the rounded normal to be trusted to 1e-12.
std::pair<Vec3d, double> plane_of(const Vec3d t[3]) {
  const Vec3d e1 = t[1] - t[0], e2 = t[2] - t[0], c = cross(e1, e2);
  const double len = length(c);
  if (!(len > 1e-4 * length(e1) * length(e2))) return {Vec3d{}, 0.0};
  const Vec3d n = c * (1 / len);
  return {n, dot(n, t[0])};
}

// How far the corners of q all lie on one side of the plane (n, w), less `slack`; 0 if they do
// not. With a slack above the rounding of the dot products it bounds the distance between q and
// anything in that plane from below.
double plane_gap(Vec3d n, double w, const Vec3d q[3], double slack) {
  const double s0 = dot(n, q[0]) - w, s1 = dot(n, q[1]) - w, s2 = dot(n, q[2]) - w;
  const double gap = s0 > 0 && s1 > 0 && s2 > 0 ? std::min({s0, s1, s2})
                     : s0 < 0 && s1 < 0 && s2 < 0 ? -std::max({s0, s1, s2})
                                                  : 0.0;
  return std::max(gap - slack, 0.0);
}

// One of those candidates for one triangle: a lower bound on its squared distance (from the
// boxes), and its index.
struct Bounded {
  double bound;
  std::uint32_t candidate;
};

struct PairsWorker {
  NodeStack<float> stack;
  std::vector<Candidate> candidates;
  std::vector<Bounded> bounded;
  std::unordered_map<std::uint64_t, double> pair_best;  // (lower solid, higher) -> least dist2 seen
};

// For every triangle, points in other solids within distance `d` (strictly), enough for two
// exact minima: with `per_triangle`, the triangle's distance to the nearest other solid (the
// least of its entries), and always each pair's distance and points, measured from its lower
// solid's triangles (the nearest of their entries for the higher solid; without `per_triangle`
// only higher solids are searched).
// Triangle i is at tri_offset[g] + p. The float BVH is queried once per leaf block and solid, with
// the box of the block's triangles of that solid grown by d (for_each_overlapping's rule), and
// the subtrees of that solid skipped. Each triangle measures exactly the candidates whose lower
// bound (boxes, then either triangle's plane) lies below d, nearest bound first, while the bound
// can still reach the triangle's nearest so far or, for a higher solid, the least distance this
// thread has seen for the pair: a candidate at either minimum is never skipped. Entries keep the
// nearer() points, so neither minimum nor its points depend on the BVH's layout, the order of
// the candidates or the threads.
bool nearest_per_triangle(const Accel& accel, const std::vector<std::size_t>& tri_offset, double d, bool per_triangle,
                          std::vector<std::vector<Near>>& near, const Progress& progress) {
  const Scene& scene = accel.scene();
  const WideBvhf& bvh = accel.wide();
  std::vector<std::uint32_t> slot_solid(bvh.nodes.size() * kWideArity, kMixedSolids);
  if (!bvh.empty()) solid_below(bvh, bvh.root, slot_solid);
  const double grow = d + float_rounding_margin(bvh);
  const double d2 = d * d;
  // Above the rounding of plane_gap's dot products for the scene's coordinates and well-shaped
  // planes (plane_of), and far below any clearance worth asking for.
  const double slack = 1e-10 * (bvh.scene_max_abs + scene.scale());
  near.assign(tri_offset.back(), {});
  auto box_of = [&](std::uint32_t geom, std::uint32_t prim, Vec3d c[3]) {
    corners(scene.geometry(geom), prim, c);
    BBoxd b;
    for (int k = 0; k < 3; ++k) b.extend(c[k]);
    return b;
  };
  tbb::enumerable_thread_specific<PairsWorker> workers;
  return parallel_for_items(bvh.empty() ? 0 : bvh.blocks.size(), 16, workers, progress, [&](PairsWorker& w, std::size_t blk) {
    const TriBlock<float>& block = bvh.blocks[blk];
    std::uint32_t todo = block.valid;
    while (todo != 0) {
      const std::uint32_t g = block.geom[__builtin_ctz(todo)];
      std::uint32_t lanes = 0;
      BBoxd entry;
      Vec3d c[3];
      for (std::uint32_t m = todo; m != 0; m &= m - 1)
        if (const int l = __builtin_ctz(m); block.geom[l] == g) lanes |= 1u << l, entry.extend(box_of(g, block.prim[l], c));
      todo &= ~lanes;
      const BBoxd lanes_box = entry;
      entry.lo = entry.lo - Vec3d{grow, grow, grow};
      entry.hi = entry.hi + Vec3d{grow, grow, grow};
      // The subtrees worth entering: not of solid g alone (nor, without per_triangle, of a lower one).
      auto enter = [&](const BBoxf& b, const WideNode<float>& node, int slot) {
        const std::uint32_t below = slot_solid[std::size_t(&node - bvh.nodes.data()) * kWideArity + std::size_t(slot)];
        return below != g && (per_triangle || below == kMixedSolids || below > g) && boxes_overlap(b, entry);
      };
      w.candidates.clear();
      for_each_entered(bvh, w.stack, enter, [&](const Triangle<float>& tf) {
        if (tf.geom == g || (!per_triangle && tf.geom < g)) return;
        Candidate k;
        k.geom = tf.geom, k.prim = tf.prim;
        k.box = box_of(tf.geom, tf.prim, k.c);
        if (!boxes_overlap(k.box, entry)) return;
        // Without the map, a candidate farther from all the lanes than the pair's least distance
        // so far can reach no minimum.
        if (!per_triangle) {
          const auto seen = w.pair_best.find(std::uint64_t(g) << 32 | tf.geom);
          if (seen != w.pair_best.end() && box_distance2(lanes_box, k.box) > seen->second) return;
        }
        w.candidates.push_back(k);
      });
      for (std::uint32_t m = lanes; m != 0; m &= m - 1) {
        const std::uint32_t prim = block.prim[__builtin_ctz(m)];
        Vec3d a[3];
        const BBoxd box = box_of(g, prim, a);
        if (is_degenerate_triangle(a)) continue;
        const auto [n, off] = plane_of(a);
        w.bounded.clear();
        for (std::uint32_t j = 0; j < w.candidates.size(); ++j)
          if (const double bound = box_distance2(box, w.candidates[j].box); bound < d2) w.bounded.push_back({bound, j});
        std::sort(w.bounded.begin(), w.bounded.end(), [](const Bounded& x, const Bounded& y) {
          return std::tie(x.bound, x.candidate) < std::tie(y.bound, y.candidate);
        });
        std::vector<Near>& mine = near[tri_offset[g] + prim];
        double nearest = std::numeric_limits<double>::infinity();  // of this triangle, so far
        // Whether a candidate in solid h with this bound can still reach a minimum.
        auto wanted = [&](double bound, std::uint32_t h) {
          if (!(bound < d2)) return false;
          if (per_triangle && bound <= nearest) return true;
          if (h < g) return false;
          const auto seen = w.pair_best.find(std::uint64_t(g) << 32 | h);
          return seen == w.pair_best.end() || bound <= seen->second;
        };
        for (const Bounded& bounded : w.bounded) {
          Candidate& k = w.candidates[bounded.candidate];
          if (!wanted(bounded.bound, k.geom)) continue;
          if (!k.has_plane) std::tie(k.n, k.w) = plane_of(k.c), k.has_plane = true;
          const double gap = std::max(plane_gap(n, off, k.c, slack), plane_gap(k.n, k.w, a, slack));
          if (!wanted(gap * gap, k.geom)) continue;
          const Vec3d* b = k.c;
          const TrianglePairDistance td = triangle_distance(a, b);
          if (!(td.dist2 < d2)) continue;
          nearest = std::min(nearest, td.dist2);
          if (k.geom > g) {
            const auto [seen, fresh] = w.pair_best.try_emplace(std::uint64_t(g) << 32 | k.geom, td.dist2);
            if (!fresh) seen->second = std::min(seen->second, td.dist2);
          }
          auto it = std::find_if(mine.begin(), mine.end(), [&](const Near& x) { return x.other == k.geom; });
          const Near found{k.geom, td.dist2, td.on_a, td.on_b};
          if (it == mine.end()) {
            mine.push_back(found);
          } else if (nearer(found, *it)) {
            *it = found;
          }
        }
      }
    }
  });
}

using PairKey = std::pair<std::uint32_t, std::uint32_t>;

SolidPair clash_pair(const InterferencePair& p) {
  SolidPair s;
  s.solid_a = p.a, s.solid_b = p.b;
  s.kind = PairKind::clash;
  s.gap = kNaN;
  s.depth = std::isnan(p.penetration) ? p.max_depth : p.penetration;
  s.overlap_length = p.max_depth;
  s.volume = 0;
  s.point = p.max_depth_entry;
  s.point_b = {kNaN, kNaN, kNaN};
  return s;
}

SolidPair contact_pair(std::uint32_t a, std::uint32_t b, Vec3d where) {
  SolidPair s;
  s.solid_a = a, s.solid_b = b;
  s.kind = PairKind::contact;
  s.gap = 0;
  s.depth = s.overlap_length = s.volume = kNaN;
  s.point = where;
  s.point_b = {kNaN, kNaN, kNaN};
  return s;
}

// Clash volume and the interval where the depth occurs, from the kept intervals (ray r of the grid
// runs along axis r / grid_n^2).
void measure_clashes(const Scene& scene, const RayOverlapReport& rays, int grid_n, std::vector<SolidPair>& clashes) {
  std::map<PairKey, std::size_t> index;
  for (std::size_t k = 0; k < clashes.size(); ++k) index[{clashes[k].solid_a, clashes[k].solid_b}] = k;
  const double area[3] = {axis_grid_cell_area(scene.bounds(), grid_n, 0),
                          axis_grid_cell_area(scene.bounds(), grid_n, 1),
                          axis_grid_cell_area(scene.bounds(), grid_n, 2)};
  const std::size_t per_axis = std::size_t(grid_n) * std::size_t(grid_n);
  std::vector<std::array<double, 3>> volume(clashes.size(), {0.0, 0.0, 0.0});
  std::vector<std::array<const Interference*, 3>> longest(clashes.size(), {nullptr, nullptr, nullptr});
  for (const Interference& x : rays.intervals) {
    const auto it = index.find({x.a, x.b});
    const auto axis = std::size_t(x.ray / per_axis);
    if (it == index.end() || axis > 2) continue;
    volume[it->second][axis] += x.depth * area[axis];  // each ray stands for its cell
    const Interference*& l = longest[it->second][axis];
    if (!l || x.depth > l->depth) l = &x;
  }
  // The depth axis: the one whose longest interval is shortest (the first such axis). Its rays
  // cross the overlap where it is thinnest, measuring that thickness exactly along each ray and
  // seeing the overlap's widest cross-section, so its volume is the estimate kept: the other
  // axes' cells can be as wide as a thin overlap, misplacing its faces by up to a cell.
  for (std::size_t k = 0; k < clashes.size(); ++k) {
    int best = -1;
    for (int axis = 0; axis < 3; ++axis)
      if (longest[k][axis] && (best < 0 || longest[k][axis]->depth < longest[k][best]->depth)) best = axis;
    if (best < 0) continue;
    clashes[k].point = longest[k][best]->entry;
    clashes[k].point_b = longest[k][best]->exit;
    clashes[k].volume = volume[k][best];
  }
}

}  // namespace

SolidPairReport classify_solid_pairs(const Accel& accel, const CoplanarReport& coplanar,
                                     const RayOverlapReport& rays, int grid_n, double clearance,
                                     bool triangle_clearance, const Progress& progress) {
  if (!(clearance >= 0) || !std::isfinite(clearance))
    throw std::invalid_argument("solid pairs: clearance must be a finite number >= 0");
  if (grid_n <= 0) throw std::invalid_argument("solid pairs: grid_n must be > 0");
  const Scene& scene = accel.scene();
  SolidPairReport r;
  r.clearance = clearance;
  r.tri_offset.push_back(0);
  for (const Geometry& g : scene.geometries()) r.tri_offset.push_back(r.tri_offset.back() + g.triangles.size());

  // Clash: interference along the rays.
  std::vector<SolidPair> clashes;
  std::set<PairKey> decided;  // pairs already given a kind
  for (const InterferencePair& p : rays.interferences) {
    clashes.push_back(clash_pair(p));
    decided.insert({p.a, p.b});
  }
  measure_clashes(scene, rays, grid_n, clashes);

  // Contact: exactly coplanar overlapping faces of two solids, or rays crossing a shared surface.
  // The point: the centroid of the largest exact overlap, else the first ray crossing.
  std::map<PairKey, std::pair<double, Vec3d>> touching;
  for (const CoplanarPair& p : coplanar.pairs) {
    if (!p.exact || p.geom_a == p.geom_b) continue;
    const PairKey key{std::min(p.geom_a, p.geom_b), std::max(p.geom_a, p.geom_b)};
    auto [it, fresh] = touching.try_emplace(key, p.area, p.centroid);
    if (!fresh && p.area > it->second.first) it->second = {p.area, p.centroid};
  }
  for (const ContactPair& p : rays.contacts) touching.try_emplace({p.a, p.b}, -1.0, p.where);
  std::vector<SolidPair> contacts;
  for (const auto& [key, v] : touching)
    if (!decided.count(key)) {
      contacts.push_back(contact_pair(key.first, key.second, v.second));
      decided.insert(key);
    }

  // Clearance: the nearest triangles of the remaining pairs.
  if (triangle_clearance) r.triangle_clearance.assign(r.tri_offset.back(), clearance);
  std::map<PairKey, SolidPair> nearest;
  if (clearance > 0) {
    std::vector<std::vector<Near>> near;
    if (!nearest_per_triangle(accel, r.tri_offset, clearance, triangle_clearance, near, progress)) {
      r.completed = false;
      return r;
    }
    for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
      for (std::size_t i = r.tri_offset[g]; i < r.tri_offset[g + 1]; ++i)
        for (const Near& x : near[i]) {
          if (triangle_clearance) r.triangle_clearance[i] = std::min(r.triangle_clearance[i], std::sqrt(x.dist2));
          if (x.other < g) continue;  // the pair is measured from its lower solid's triangles
          auto [it, fresh] = nearest.try_emplace({g, x.other});
          SolidPair& s = it->second;
          if (fresh || nearer(x, Near{x.other, s.gap, s.point, s.point_b})) {
            s.solid_a = g, s.solid_b = x.other;
            s.kind = PairKind::clearance;
            s.gap = x.dist2;  // squared until the end
            s.depth = s.overlap_length = s.volume = kNaN;
            s.point = x.on_self, s.point_b = x.on_other;
          }
        }
  }
  // Contact and clash make a triangle's clearance 0 where it takes part in them.
  if (triangle_clearance) {
    for (const CoplanarPair& p : coplanar.pairs)
      if (p.exact && p.geom_a != p.geom_b)
        r.triangle_clearance[r.tri_offset[p.geom_a] + p.prim_a] = r.triangle_clearance[r.tri_offset[p.geom_b] + p.prim_b] = 0;
    if (rays.interference_hits.size() == r.triangle_clearance.size())
      for (std::size_t i = 0; i < r.triangle_clearance.size(); ++i)
        if (rays.interference_hits[i] > 0) r.triangle_clearance[i] = 0;
  }

  std::vector<SolidPair> gaps;
  for (auto& [key, s] : nearest)
    if (!decided.count(key)) {
      s.gap = std::sqrt(s.gap);
      gaps.push_back(s);
    }

  auto by_pair = [](const SolidPair& x, const SolidPair& y) {
    return std::pair(x.solid_a, x.solid_b) < std::pair(y.solid_a, y.solid_b);
  };
  std::stable_sort(clashes.begin(), clashes.end(), [&](const SolidPair& x, const SolidPair& y) {
    return x.depth != y.depth ? x.depth > y.depth : by_pair(x, y);
  });
  std::stable_sort(gaps.begin(), gaps.end(), [&](const SolidPair& x, const SolidPair& y) {
    return x.gap != y.gap ? x.gap < y.gap : by_pair(x, y);
  });
  r.pairs = std::move(clashes);
  r.pairs.insert(r.pairs.end(), contacts.begin(), contacts.end());  // already by (a, b)
  r.pairs.insert(r.pairs.end(), gaps.begin(), gaps.end());
  return r;
}

SolidPairReport analyse_solid_pairs(const Accel& accel, const SolidPairOptions& opts, const Progress& progress) {
  if (opts.grid_n <= 0) throw std::invalid_argument("solid pairs: grid_n must be > 0");
  if (!(opts.clearance >= 0) || !std::isfinite(opts.clearance))
    throw std::invalid_argument("solid pairs: clearance must be a finite number >= 0");
  const CoplanarReport coplanar = find_coplanar_overlaps(accel.scene(), {}, progress);
  if (!coplanar.completed) return {opts.clearance, {}, {}, {}, false};
  RayOverlapOptions ro;
  ro.kernel = opts.kernel;
  ro.tie_tolerance_rel = opts.tie_tolerance_rel;
  ro.keep_intervals = true;
  const RayOverlapReport rays =
      analyse_ray_overlaps(accel, axis_grid_rays(accel.scene().bounds(), opts.grid_n), ro, progress);
  if (!rays.completed) return {opts.clearance, {}, {}, {}, false};
  return classify_solid_pairs(accel, coplanar, rays, opts.grid_n, opts.clearance, opts.triangle_clearance, progress);
}

}  // namespace pierce::analysis
