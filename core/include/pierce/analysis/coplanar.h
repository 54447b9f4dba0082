#pragma once
// Triangle pairs that lie in the same plane and overlap there: duplicated faces (same facing)
// and coincident faces of touching solids (opposite facing), per solid pair, with the area
// they share. "Exact" pairs are decided with exact predicates (the four corners exactly
// coplanar, interiors overlapping in exact arithmetic); with a tolerance, pairs whose corners
// lie within that distance of each other's planes and whose overlap area (in the first
// triangle's plane) is not negligible are reported too.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pierce/progress.h"
#include "pierce/scene.h"

namespace pierce::analysis {

struct CoplanarOptions {
  double tolerance = 0;        // absolute distance; 0 reports exactly coplanar pairs only
  double min_area_rel = 1e-9;  // tolerance pairs: ignore overlaps below this share of the smaller triangle
};

struct CoplanarPair {
  std::uint32_t geom_a = 0, prim_a = 0, geom_b = 0, prim_b = 0;  // (geom_a, prim_a) < (geom_b, prim_b)
  double area = 0;       // overlap area (clipped in triangle a's plane)
  Vec3d centroid;        // of the overlap region
  bool exact = false;    // exactly coplanar with overlapping interiors
  bool same_facing = false;  // normals agree: a duplicated face; otherwise a contact
};

struct CoplanarSolidPair {
  std::uint32_t a = 0, b = 0;  // a <= b (a == b: inside one solid)
  std::size_t pairs = 0, exact_pairs = 0, same_facing = 0, opposite_facing = 0;
  double area = 0;  // summed over triangle pairs
  Vec3d where;      // centroid of the largest triangle-pair overlap
};

struct CoplanarReport {
  double tolerance = 0;
  std::vector<CoplanarPair> pairs;  // sorted by (geom_a, prim_a, geom_b, prim_b)
  std::vector<CoplanarSolidPair> solid_pairs;  // sorted by (a, b)
  bool completed = true;
};

// Degenerate triangles (zero area) take no part. Throws std::invalid_argument on a negative
// or non-finite tolerance.
CoplanarReport find_coplanar_overlaps(const Scene& scene, const CoplanarOptions& opts = {},
                                      const Progress& progress = {});

}  // namespace pierce::analysis
