#pragma once
// vtkPierceOverlaps's work: the coplanar-pair and ray-interference analyses run on the scene,
// their per-triangle arrays attached to the solids' surfaces, and the solid-pair table.
#include <optional>

#include "pierce/analysis/overlaps.h"
#include "pierce/analysis/solid_pairs.h"

class vtkFieldData;
class vtkTable;

namespace pierce_vtk {

class ProgressBridge;
struct Surfaces;

struct OverlapSettings {
  bool find_coplanar = true;
  double tolerance = 0.0;
  int rays_per_axis = 128;  // 0: no ray analysis
  double epsilon_rel = 1e-5;
  double clearance = 0.0;  // the Clearance array's cap (with the rays)
};

struct OverlapResults {
  std::optional<pierce::analysis::CoplanarReport> coplanar;
  std::optional<pierce::analysis::RayOverlapReport> rays;
  std::optional<pierce::analysis::SolidPairReport> pairs;  // with the rays
};

// False when cancelled. Throws std::invalid_argument on bad settings (from the analyses).
bool RunOverlaps(const pierce::Scene& scene, const OverlapSettings& settings, ProgressBridge& progress,
                 OverlapResults& out);

// Cell arrays (see vtkPierceOverlaps) on each solid's surface; OverlapCount is the active scalars.
void AttachOverlaps(const OverlapResults& results, Surfaces& surfaces);

// Field data: the coplanar-ray statistic (when the ray analysis ran), and the pairs of solids by
// kind (PairKind "clash" | "contact" | "clearance", PairSolidA, PairSolidB, PairGap, PairDepth,
// PairOverlapLength, PairVolume, PairPoint, PairPointB; NaN where a field does not apply), one
// tuple per pair in the order of pierce::analysis::SolidPairReport.
void AddOverlapStatistics(const OverlapResults& results, vtkFieldData* field_data);

// One row per solid pair and kind: interference, contact, coplanar.
void WriteOverlapTable(const OverlapResults& results, const Surfaces& surfaces, vtkTable* table);

}  // namespace pierce_vtk
