#pragma once
// Thin and thick walls as regions: the findings of a thickness map (compute_thickness fills
// them when ThicknessOptions::min_thickness > 0 or max_thickness is finite).
//
//  - rule: a sample is thin when its thickness is finite and strictly below min_thickness, thick
//    when it is finite and strictly above max_thickness (a wall of exactly the threshold is
//    neither); values are compared as measured, never rounded;
//  - grouping: thin (thick) samples connected on the surface of one solid form a region (per
//    vertex: vertices joined by a triangle edge, coincident vertices welded; per face: triangles
//    sharing an edge or a vertex), and a region is joined with the region its rays exit in (the
//    samples of the exit triangle: the triangle the ray leaves through for the ray method on a
//    mesh, else the triangle of the same solid closest to point - normal * thickness), so both
//    sides of a thin floor are one region;
//  - area: both sides of the wall. The exit triangles and, per face, the region's triangles,
//    with their one-ring neighbours (per vertex only around exit triangles longer than half the
//    region's size: elsewhere the samples there show the area), and per vertex the triangles
//    around the region's vertices (their one-ring already) are subdivided (4-way, at edge midpoints) where the flag of the
//    sub-triangles' centroids changes, each centroid traced like a ray sample along its
//    triangle's inward normal (ray_exit_distance, on the mesh), and the flagged sub-triangles'
//    areas summed, each for the region of its triangle's samples, else of the samples where its
//    ray exits (so a coarse face under two floors gives each its share); a triangle whose samples
//    all lie in the region (per vertex its corners; per face itself and the triangles around its
//    corners) counts whole. Refinement feeds the area only: the per-sample results are those of
//    the samples.
#include <cstdint>
#include <vector>

#include "pierce/vec3.h"

namespace pierce::analysis {

struct ThicknessRegion {
  std::uint32_t solid = 0;  // geometry id
  bool thick = false;       // a thick region (thickness above max_thickness), else a thin one
  double thickness = 0;     // the region's extreme: minimum (thin) or maximum (thick) thickness
  Vec3d point;              // the sample point of that extreme sample (the lowest x, y, z among equals)
  Vec3d exit;               // where its ray leaves: point - normal * thickness
  double area = 0;          // flagged surface area, both sides of the wall
  std::size_t samples = 0;  // sample points in the region (coincident vertices count once)
  // CAD input with exact surfaces: the B-rep faces (ExactSurfaces::face_of) of the triangles
  // that hold flagged area, ascending; empty for meshes.
  std::vector<std::uint32_t> faces;
};

}  // namespace pierce::analysis
