#pragma once
// Per-triangle overlap arrays for heat maps (VTP output, VTK filters, FreeCAD colouring),
// combining the coplanar-pair search and the ray-based report.
#include <cstdint>
#include <vector>

#include "pierce/analysis/coplanar.h"
#include "pierce/analysis/ray_overlaps.h"

namespace pierce::analysis {

struct TriangleOverlapArrays {
  std::vector<std::size_t> tri_offset;           // triangle (g, p) is at tri_offset[g] + p
  std::vector<std::uint32_t> solid;              // SolidId
  std::vector<std::uint32_t> coplanar_count;     // coplanar overlapping partner triangles
  std::vector<std::int32_t> coplanar_partner;    // solid of a partner (another solid first), -1: none
  std::vector<std::uint32_t> coplanar_hits;      // ray crossings with another crossing within epsilon
  std::vector<std::uint32_t> interference_hits;  // ray crossings opening or closing an interference
  std::vector<std::uint32_t> overlap_count;      // coplanar_count + interference_hits

  std::size_t size() const { return solid.size(); }
};

// Either report may be null (its arrays are then zero).
TriangleOverlapArrays triangle_overlap_arrays(const Scene& scene, const CoplanarReport* coplanar,
                                              const RayOverlapReport* rays);

}  // namespace pierce::analysis
