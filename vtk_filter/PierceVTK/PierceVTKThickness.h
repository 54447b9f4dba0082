#pragma once
// vtkPierceThickness's conversions: filter settings to ThicknessOptions, results to VTK arrays
// on the solids' surfaces and to a per-solid statistics table.
#include "pierce/analysis/thickness.h"

class vtkTable;

namespace pierce_vtk {

struct Surfaces;

struct ThicknessSettings {
  int method = 0;     // vtkPierceThickness::Methods
  int sample_at = 0;  // vtkPierceThickness::SampleLocations
  double max_distance = 0.0;  // <= 0: unlimited
  double min_thickness = 0.0;
  int cone_rays = 30;
  double cone_angle = 120.0;
  int cone_aggregate = 0;  // vtkPierceThickness::ConeAggregates
};

pierce::analysis::ThicknessOptions ToThicknessOptions(const ThicknessSettings& settings);

// Point (per vertex) or cell (per face) arrays Thickness, Thin, ThicknessStatus, SolidId on each
// solid's surface; Thickness becomes the active scalars.
void AttachThickness(const pierce::analysis::ThicknessResult& result, Surfaces& surfaces);

// One row per solid: SolidId, Name, Elements, Valid, NoExit, NoNormal, Thin, Min, Max, Mean and
// the percentiles as P<q>.
void WriteThicknessTable(const pierce::analysis::ThicknessResult& result, vtkTable* table);

}  // namespace pierce_vtk
