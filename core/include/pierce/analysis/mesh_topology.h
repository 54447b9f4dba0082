#pragma once
// Topology helpers on one geometry: vertices welded by exact position (STL stores three
// vertices per facet), edge incidence, and outward normals.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "pierce/scene.h"

namespace pierce::analysis {

// For each vertex, the lowest index of a vertex at exactly the same position (-0 == +0).
std::vector<std::uint32_t> weld_by_position(const std::vector<Vec3d>& vertices);

struct EdgeStats {
  std::size_t edges = 0;          // distinct undirected edges between welded vertices
  std::size_t boundary = 0;       // used by one triangle
  std::size_t non_manifold = 0;   // used by more than two triangles
  std::size_t inconsistent = 0;   // used by two triangles running it the same way (flipped winding)
};

// Edges of all triangles (degenerate ones included: they are part of the surface's topology).
EdgeStats edge_stats(const Geometry& g, const std::vector<std::uint32_t>& weld);

// Number of triangles that repeat an earlier triangle's welded vertex set (any winding).
std::size_t duplicate_triangles(const Geometry& g, const std::vector<std::uint32_t>& weld);

// For each triangle, the lowest index of a triangle with the same welded corners (any order).
std::vector<std::uint32_t> first_occurrence(const Geometry& g, const std::vector<std::uint32_t>& weld);

// Unit normal (v1-v0)x(v2-v0) of triangle i in double; zero for a degenerate triangle.
Vec3d face_normal(const Geometry& g, std::size_t i);

// Unit outward normal per vertex: angle-weighted mean of the normals of the non-degenerate
// triangles around its welded position, each distinct welded triangle counted once (so
// duplicated faces do not tilt it); zero where there is none or the normals cancel.
std::vector<Vec3d> vertex_normals(const Geometry& g, const std::vector<std::uint32_t>& weld);

}  // namespace pierce::analysis
