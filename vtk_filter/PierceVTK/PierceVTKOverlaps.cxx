#include "PierceVTKOverlaps.h"

#include <cmath>
#include <limits>
#include <string>

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include "PierceVTKProgress.h"
#include "PierceVTKSurfaces.h"
#include "pierce/enum_names.h"
#include "pierce/kernel.h"

namespace pierce_vtk {

namespace pa = pierce::analysis;

namespace {

template <typename Array>
vtkSmartPointer<Array> NewArray(const char* name, vtkIdType n = 0, int components = 1) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  if (n > 0) a->SetNumberOfTuples(n);
  return a;
}

vtkSmartPointer<vtkDoubleArray> OneValue(const char* name, double value) {
  auto a = NewArray<vtkDoubleArray>(name);
  a->InsertNextValue(value);
  return a;
}

}  // namespace

bool RunOverlaps(const pierce::Scene& scene, const OverlapSettings& settings, ProgressBridge& progress,
                 OverlapResults& out) {
  out = OverlapResults{};
  const bool with_rays = settings.rays_per_axis > 0;
  if (settings.find_coplanar) {
    progress.SetRange(0.0, with_rays ? 0.3 : 1.0);
    pa::CoplanarOptions options;
    options.tolerance = settings.tolerance;
    out.coplanar = pa::find_coplanar_overlaps(scene, options, progress.Callback());
    if (!out.coplanar->completed || progress.CheckAbort()) return false;
  }
  if (with_rays) {
    progress.SetRange(settings.find_coplanar ? 0.3 : 0.0, 0.9);
    const pierce::Accel accel(scene);
    pa::RayOverlapOptions options;
    options.epsilon_rel = settings.epsilon_rel;
    options.keep_intervals = true;  // the solid pairs measure clashes from the intervals
    const std::vector<pierce::Ray> rays = pa::axis_grid_rays(scene.bounds(), settings.rays_per_axis);
    out.rays = pa::analyse_ray_overlaps(accel, rays, options, progress.Callback());
    if (!out.rays->completed || progress.CheckAbort()) return false;
    // The pairs take only the exact coplanar pairs: the report above when there is one.
    progress.SetRange(0.9, 1.0);
    const pa::CoplanarReport exact = out.coplanar ? pa::CoplanarReport{} : pa::find_coplanar_overlaps(scene);
    out.pairs = pa::classify_solid_pairs(accel, out.coplanar ? *out.coplanar : exact, *out.rays,
                                         settings.rays_per_axis, settings.clearance, /*triangle_clearance=*/true,
                                         progress.Callback());
    if (!out.pairs->completed || progress.CheckAbort()) return false;
  }
  return true;
}

void AttachOverlaps(const OverlapResults& results, Surfaces& surfaces) {
  const pa::TriangleOverlapArrays a = pa::triangle_overlap_arrays(
    surfaces.scene, results.coplanar ? &*results.coplanar : nullptr, results.rays ? &*results.rays : nullptr);
  for (std::size_t s = 0; s < surfaces.solids.size(); ++s) {
    const Solid& solid_piece = surfaces.solids[s];
    vtkPolyData* surface = solid_piece.surface;
    const vtkIdType n = surface->GetNumberOfCells();
    auto solid = NewArray<vtkIntArray>("SolidId", n);
    auto overlap = NewArray<vtkIntArray>("OverlapCount", n);
    auto coplanar = NewArray<vtkIntArray>("CoplanarCount", n);
    auto partner = NewArray<vtkIntArray>("CoplanarPartner", n);
    auto coplanar_hits = NewArray<vtkIntArray>("CoplanarHits", n);
    auto interference_hits = NewArray<vtkIntArray>("InterferenceHits", n);
    const std::size_t base = a.tri_offset[solid_piece.id];
    for (vtkIdType c = 0; c < n; ++c) {
      const std::size_t i = base + std::size_t(PrimOfCell(solid_piece, c));
      solid->SetValue(c, int(a.solid[i]));
      overlap->SetValue(c, int(a.overlap_count[i]));
      coplanar->SetValue(c, int(a.coplanar_count[i]));
      partner->SetValue(c, a.coplanar_partner[i]);
      coplanar_hits->SetValue(c, int(a.coplanar_hits[i]));
      interference_hits->SetValue(c, int(a.interference_hits[i]));
    }
    vtkCellData* cd = surface->GetCellData();
    for (vtkIntArray* array : {solid.Get(), overlap.Get(), coplanar.Get(), partner.Get(), coplanar_hits.Get(),
                               interference_hits.Get()})
      cd->AddArray(array);
    if (results.pairs) {
      auto clearance = NewArray<vtkDoubleArray>("Clearance", n);
      for (vtkIdType c = 0; c < n; ++c)
        clearance->SetValue(c, results.pairs->triangle_clearance[base + std::size_t(PrimOfCell(solid_piece, c))]);
      cd->AddArray(clearance);
    }
    cd->SetActiveScalars("OverlapCount");
  }
}

void AddOverlapStatistics(const OverlapResults& results, vtkFieldData* field_data) {
  if (results.pairs) {
    // The pairs of solids by kind, as `pierce overlaps --clearance` lists them: one tuple per pair.
    auto kind = NewArray<vtkStringArray>("PairKind");
    auto solid_a = NewArray<vtkIntArray>("PairSolidA");
    auto solid_b = NewArray<vtkIntArray>("PairSolidB");
    auto gap = NewArray<vtkDoubleArray>("PairGap");
    auto depth = NewArray<vtkDoubleArray>("PairDepth");
    auto overlap_length = NewArray<vtkDoubleArray>("PairOverlapLength");
    auto volume = NewArray<vtkDoubleArray>("PairVolume");
    auto point = NewArray<vtkDoubleArray>("PairPoint", 0, 3);
    auto point_b = NewArray<vtkDoubleArray>("PairPointB", 0, 3);
    for (const pa::SolidPair& p : results.pairs->pairs) {
      kind->InsertNextValue(std::string(pierce::enum_name(p.kind)));
      solid_a->InsertNextValue(int(p.solid_a));
      solid_b->InsertNextValue(int(p.solid_b));
      gap->InsertNextValue(p.gap);
      depth->InsertNextValue(p.depth);
      overlap_length->InsertNextValue(p.overlap_length);
      volume->InsertNextValue(p.volume);
      point->InsertNextTuple3(p.point.x, p.point.y, p.point.z);
      point_b->InsertNextTuple3(p.point_b.x, p.point_b.y, p.point_b.z);
    }
    for (vtkAbstractArray* a :
         {static_cast<vtkAbstractArray*>(kind), static_cast<vtkAbstractArray*>(solid_a),
          static_cast<vtkAbstractArray*>(solid_b), static_cast<vtkAbstractArray*>(gap),
          static_cast<vtkAbstractArray*>(depth), static_cast<vtkAbstractArray*>(overlap_length),
          static_cast<vtkAbstractArray*>(volume), static_cast<vtkAbstractArray*>(point),
          static_cast<vtkAbstractArray*>(point_b)})
      field_data->AddArray(a);
  }
  if (!results.rays) return;
  const pa::CoplanarRayStats& s = results.rays->coplanar;
  field_data->AddArray(OneValue("CoplanarRayShareEqual", s.share_equal()));
  field_data->AddArray(OneValue("CoplanarRayShareWithinEps", s.share_within_eps()));
  field_data->AddArray(OneValue("CoplanarRayEpsilon", s.epsilon));
  field_data->AddArray(OneValue("RaysHitting", double(s.rays_hitting)));
}

void WriteOverlapTable(const OverlapResults& results, const Surfaces& surfaces, vtkTable* table) {
  auto kind = NewArray<vtkStringArray>("Kind");
  auto solid_a = NewArray<vtkIntArray>("SolidA");
  auto solid_b = NewArray<vtkIntArray>("SolidB");
  auto name_a = NewArray<vtkStringArray>("NameA");
  auto name_b = NewArray<vtkStringArray>("NameB");
  auto count = NewArray<vtkIdTypeArray>("Count");
  auto max_depth = NewArray<vtkDoubleArray>("MaxDepth");
  auto penetration = NewArray<vtkDoubleArray>("Penetration");
  auto area = NewArray<vtkDoubleArray>("Area");
  auto where = NewArray<vtkDoubleArray>("Where", 0, 3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto row = [&](const char* k, std::uint32_t a, std::uint32_t b, std::size_t n, double depth, double pen,
                 double ar, const pierce::Vec3d& at) {
    kind->InsertNextValue(k);
    solid_a->InsertNextValue(int(a));
    solid_b->InsertNextValue(int(b));
    name_a->InsertNextValue(surfaces.scene.geometry(a).name);
    name_b->InsertNextValue(surfaces.scene.geometry(b).name);
    count->InsertNextValue(vtkIdType(n));
    max_depth->InsertNextValue(depth);
    penetration->InsertNextValue(pen);
    area->InsertNextValue(ar);
    where->InsertNextTuple3(at.x, at.y, at.z);
  };
  if (results.rays) {
    for (const pa::InterferencePair& p : results.rays->interferences)
      row("interference", p.a, p.b, p.count, p.max_depth, p.penetration, nan, p.max_depth_entry);
    for (const pa::ContactPair& p : results.rays->contacts) row("contact", p.a, p.b, p.count, 0.0, 0.0, nan, p.where);
  }
  if (results.coplanar) {
    for (const pa::CoplanarSolidPair& p : results.coplanar->solid_pairs)
      row("coplanar", p.a, p.b, p.pairs, nan, nan, p.area, p.where);
  }
  for (vtkAbstractArray* a : {static_cast<vtkAbstractArray*>(kind), static_cast<vtkAbstractArray*>(solid_a),
                              static_cast<vtkAbstractArray*>(solid_b), static_cast<vtkAbstractArray*>(name_a),
                              static_cast<vtkAbstractArray*>(name_b), static_cast<vtkAbstractArray*>(count),
                              static_cast<vtkAbstractArray*>(max_depth), static_cast<vtkAbstractArray*>(penetration),
                              static_cast<vtkAbstractArray*>(area), static_cast<vtkAbstractArray*>(where)})
    table->AddColumn(a);
}

}  // namespace pierce_vtk
