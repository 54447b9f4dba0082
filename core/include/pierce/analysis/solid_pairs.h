#pragma once
// Contact, clash and clearance between solids: every pair of solids that comes within a distance D
// of each other, classified by how they meet.
//  - clash: their interiors overlap, as the ray-grid interference (ray_overlaps.h) sees it. `depth`
//    is how far one must move to clear the other: over the grid's three axes, the smallest of the
//    longest overlap interval along that axis's rays (InterferencePair::penetration); `point` and
//    `point_b` are where one such interval enters and leaves both solids. `overlap_length` is the
//    longest overlap along any ray, `volume` the shared volume estimated as gqa does for one axis:
//    the sum over rays of overlap length times the ray's cell area, along the depth's axis (its
//    rays measure the overlap's thin dimension exactly; across a thin overlap the other axes' cells
//    can be as wide as the overlap).
//  - contact: no interference, but faces of the two lie on one another: an exactly coplanar
//    overlapping triangle pair (coplanar.h, exact predicates, so it holds however each side's face
//    is tessellated), or a ray crossing from one into the other at a shared surface. gap = 0.
//  - clearance: neither, and the smallest distance between their triangles is below D (strictly):
//    `gap` is that distance, `point` (on solid_a) and `point_b` (on solid_b) the closest points
//    (of equally near pairs, the lexicographically smallest).
//    Distances are triangle-triangle distances computed in double precision, candidates pruned with
//    box queries on the scene's double BVH (each triangle's box grown by D). Solids meeting only
//    along an edge or at a point have gap 0 and are reported as clearance when D > 0.
// Pairs farther apart than D are not reported; D = 0 reports clash and contact only. Fields that do
// not apply to a kind are NaN.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "pierce/analysis/coplanar.h"
#include "pierce/analysis/ray_overlaps.h"
#include "pierce/enum_names.h"

namespace pierce::analysis {

enum class PairKind { clash, contact, clearance };
constexpr EnumTable<PairKind, 3> enum_table(PairKind) {
  using enum PairKind;
  return {"pair kind", {{clash, "clash"}, {contact, "contact"}, {clearance, "clearance"}}};
}

struct SolidPairOptions {
  double clearance = 0;  // D: absolute distance, >= 0
  int grid_n = 128;      // interference rays: grid_n x grid_n along each axis (axis_grid_rays)
  KernelKind kernel = kDefaultKernel;  // any exact kernel gives the same result
  double tie_tolerance_rel = 1e-6;     // as RayOverlapOptions::tie_tolerance_rel
  // Also SolidPairReport::triangle_clearance, the per-triangle map. Without it only each pair's
  // least distance is searched for, which costs a fraction of the map.
  bool triangle_clearance = true;
};

struct SolidPair {
  std::uint32_t solid_a = 0, solid_b = 0;  // geometry ids, solid_a < solid_b
  PairKind kind = PairKind::clearance;
  double gap = 0;             // contact: 0; clearance: the distance; clash: NaN
  double depth = 0;           // clash only (NaN otherwise)
  double overlap_length = 0;  // clash only
  double volume = 0;          // clash only
  Vec3d point;    // clash: entry of the depth interval; contact: a point of the shared surface;
                  // clearance: closest point on solid_a
  Vec3d point_b;  // clash: exit of the depth interval; clearance: closest point on solid_b;
                  // contact: NaN
};

struct SolidPairReport {
  double clearance = 0;  // D
  // Clash first (deepest first), then contact, then clearance (smallest gap first); ties by (a, b).
  std::vector<SolidPair> pairs;
  // Per triangle (g, p) at tri_offset[g] + p: distance to the nearest other solid, capped at D;
  // 0 for triangles in exact coplanar contact with another solid or opening or closing an
  // interference along the rays. Degenerate triangles get D. Empty when not asked for.
  std::vector<std::size_t> tri_offset;
  std::vector<double> triangle_clearance;
  bool completed = true;
};

// Runs the exact coplanar search and the interference rays itself. Throws std::invalid_argument
// for a negative or non-finite clearance, grid_n <= 0 or a non-exact kernel.
SolidPairReport analyse_solid_pairs(const Accel& accel, const SolidPairOptions& opts = {},
                                    const Progress& progress = {});

// The same from reports already computed: `rays` must come from analyse_ray_overlaps on
// axis_grid_rays(scene.bounds(), grid_n) (all three axes) with keep_intervals; only the exact
// pairs of `coplanar` are used, so any coplanar tolerance will do. `triangle_clearance`: as
// SolidPairOptions::triangle_clearance.
SolidPairReport classify_solid_pairs(const Accel& accel, const CoplanarReport& coplanar,
                                     const RayOverlapReport& rays, int grid_n, double clearance,
                                     bool triangle_clearance, const Progress& progress = {});

// Distance, in double precision, between triangles (a0, a1, a2) and (b0, b1, b2) with the closest
// points on each: 0 when they intersect (an edge of one crosses the other, or coplanar overlap).
struct TrianglePairDistance {
  double dist2 = 0;
  Vec3d on_a, on_b;
};
TrianglePairDistance triangle_distance(const Vec3d a[3], const Vec3d b[3]);

}  // namespace pierce::analysis

