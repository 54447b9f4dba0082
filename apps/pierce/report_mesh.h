#pragma once
// What the 3D view of `pierce report` shows: the scene's triangles with the values the view
// colours them by. A large model is shown with fewer triangles (vertex clustering on a uniform grid,
// Rossignac and Borrel 1993: the vertices of each solid in one grid cell become one, at their
// mean; triangles left with fewer than three distinct corners disappear), the cell grown until at
// most `max_triangles` remain. Only the picture is coarsened: the report's tables come from the
// full results. Positions are quantised to 16 bits per axis over the scene's bounds.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "pierce/scene.h"

namespace pierce::cli {

// Per-triangle kinds of the clearance / clash map (the JS page names them in this order).
enum class PairCategory : std::uint8_t { free = 0, clearance = 1, contact = 2, clash = 3 };

struct DisplayInput {
  const Scene* scene = nullptr;
  // Thickness per vertex (per_vertex) or per triangle, thickness[g][element]; an empty vector for
  // a geometry not sampled, NaN where a sample has no thickness.
  bool per_vertex = true;
  std::vector<std::vector<double>> thickness;
  // The clearance / clash map, per triangle (g, p) at tri_offset[g] + p; empty for none.
  std::vector<std::size_t> tri_offset;
  std::vector<PairCategory> pair_category;
  std::vector<double> pair_gap;  // distance to the nearest other solid, for clearance triangles
};

struct DisplayMesh {
  std::size_t triangles_model = 0;
  double cell = 0;  // the clustering grid's cell; 0 when every triangle is shown
  Vec3d origin, scale;  // position = origin + quantised * scale, per axis
  std::vector<std::uint16_t> positions;  // 3 per vertex
  std::vector<std::uint32_t> triangles;  // 3 per triangle
  std::vector<std::uint16_t> triangle_solid;  // geometry id (65535 for ids beyond)
  // Thickness per shown vertex (per_vertex: the smallest of its cluster's, so thin spots stay
  // visible) or per shown triangle (its own).
  bool per_vertex = true;
  std::vector<float> thickness;
  std::vector<std::uint8_t> pair_category;  // per shown triangle; empty for none
  std::vector<float> pair_gap;

  std::size_t triangles_shown() const { return triangles.size() / 3; }
};

DisplayMesh make_display_mesh(const DisplayInput& in, std::size_t max_triangles);

// The mesh as the page reads it: arrays base64-encoded, little-endian.
nlohmann::ordered_json display_mesh_json(const DisplayMesh& m);

}  // namespace pierce::cli
