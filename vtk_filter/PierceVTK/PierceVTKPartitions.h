#pragma once
// vtkPierceRayClassify's work: rays traced through the scene (exact kernel, leave-before-enter
// order), partitions built per ray, and written as line segments and a table.
#include <cstddef>
#include <vector>

#include "pierce/analysis/ray_partitions.h"
#include "pierce/scene.h"

class vtkPolyData;
class vtkTable;

namespace pierce_vtk {

class ProgressBridge;
struct RayInput;
struct Surfaces;

struct ClassifiedRays {
  std::vector<std::size_t> ray_begin;  // partitions of ray i: [ray_begin[i], ray_begin[i + 1])
  std::vector<pierce::Partition> partitions;
  std::vector<std::uint32_t> solids;   // Partition::first indexes this
  std::size_t inconsistent_rays = 0;   // rays with unmatched leaves or unclosed solids
};

// False when cancelled through `progress`.
bool ClassifyRays(const pierce::Scene& scene, const std::vector<pierce::Ray>& rays, ProgressBridge& progress,
                  ClassifiedRays& out);

// Segments (output 0) and table (output 1) of vtkPierceRayClassify; see its header for the arrays.
void WritePartitions(const ClassifiedRays& classified, const RayInput& rays, const Surfaces& surfaces,
                     bool include_gaps, vtkPolyData* segments, vtkTable* table);

}  // namespace pierce_vtk
