#pragma once
// The ray input of vtkPierceRayClassify as pierce::Rays.
//
//  - Line and polyline cells of a vtkPolyData: one ray per cell, from its first to its last point
//    (a finite segment; vtkLineSource gives one).
//  - Otherwise every point of the data set (a grid, a plane source, a point cloud) is a ray
//    origin; the direction is the point's vector in `direction_array` when given, else
//    `default_direction`; the ray runs `max_length` far (infinity when <= 0).
// Directions are normalised, so t is a distance. Rays without a usable direction (zero or
// non-finite) or with a non-finite origin are skipped and counted.
#include <cstddef>
#include <string>
#include <vector>

#include <vtkType.h>

#include "pierce/ray.h"

class vtkDataArray;
class vtkDataSet;

namespace pierce_vtk {

struct RayInput {
  std::vector<pierce::Ray> rays;
  std::vector<vtkIdType> source_ids;  // the cell (segments) or point (origins) each ray came from
  bool from_cells = false;
  std::size_t skipped = 0;
};

// False with `error` when the data set holds no points, or the direction array is not a
// 3-component point array. Distributed runs: `id_offset` is added to the source ids (the ray
// input elements of the ranks before this one, so that RayId is the serial id), and with
// `skip_ghosts` cells or points flagged in vtkGhostType are not rays (their owner shoots them);
// an empty piece is then no error.
bool ExtractRays(vtkDataSet* data, const double default_direction[3], vtkDataArray* direction_array,
                 double max_length, RayInput& out, std::string& error, vtkIdType id_offset = 0,
                 bool skip_ghosts = false);

}  // namespace pierce_vtk
