#pragma once
// Per-solid mesh diagnostics for `pierce info`: size, closedness, non-manifold and flipped
// edges, degenerate and duplicated triangles, bounds, area and enclosed volume.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pierce/scene.h"

namespace pierce::analysis {

struct SolidReport {
  std::uint32_t geom = 0;
  std::string name, source;
  std::size_t vertices = 0;          // as stored
  std::size_t welded_vertices = 0;   // distinct positions
  std::size_t triangles = 0;
  std::size_t degenerate = 0;        // zero area (never hit by the kernels)
  std::size_t duplicates = 0;        // repeat an earlier triangle's corners
  std::size_t edges = 0, boundary_edges = 0, non_manifold_edges = 0, inconsistent_edges = 0;
  bool closed = false;               // no boundary and no non-manifold edge
  bool consistently_oriented = false;  // closed and every edge run both ways
  BBoxd bounds;
  double area = 0;
  double volume = 0;  // signed, by the divergence theorem: < 0 means inward-facing winding;
                      // meaningful for closed meshes only
};

std::vector<SolidReport> mesh_report(const Scene& scene);

}  // namespace pierce::analysis
