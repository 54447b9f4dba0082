#pragma once
// VTK XML PolyData (.vtp) written by hand, so Pierce needs no VTK: triangles with point and cell
// data arrays, inline binary (base64, little-endian, UInt64 headers), as ParaView and VTK's
// vtkXMLPolyDataReader read it.
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pierce/scene.h"

namespace pierce::cli {

using DataArray = std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::uint32_t>,
                               std::vector<std::uint8_t>>;

struct PolyData {
  std::vector<Vec3d> points;
  std::vector<Tri> triangles;
  std::vector<std::pair<std::string, DataArray>> point_data;  // one value per point
  std::vector<std::pair<std::string, DataArray>> cell_data;   // one value per triangle
};

// Throws std::invalid_argument if an array's length does not match; returns false on write errors.
bool write_vtp(std::FILE* out, const PolyData& data);

}  // namespace pierce::cli
