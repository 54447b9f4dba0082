#include "PierceVTKPartitions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include "PierceVTKProgress.h"
#include "PierceVTKRays.h"
#include "PierceVTKSurfaces.h"
#include "pierce/analysis/obliquity.h"
#include "pierce/kernel.h"

namespace pierce_vtk {
namespace {

// Rays per trace_batch call: bounds the memory of the hit lists, which can be long.
constexpr std::size_t kChunk = 8192;

template <typename Array>
vtkSmartPointer<Array> NewArray(const char* name) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  return a;
}

// One output row/cell, a partition or a gap.
struct Segment {
  vtkIdType ray_id;
  const pierce::Ray* ray;
  double t_in, t_out;
  const std::uint32_t* solids;
  std::uint32_t count;
  const pierce::Hit* in_hit;
  const pierce::Hit* out_hit;
};

class Writer {
 public:
  explicit Writer(const Surfaces& surfaces) : surfaces_(surfaces) {
    points_ = vtkSmartPointer<vtkPoints>::New();
    points_->SetDataTypeToDouble();
    lines_ = vtkSmartPointer<vtkCellArray>::New();
  }

  void Add(const Segment& s) {
    const pierce::Vec3d a = s.ray->org + s.ray->dir * s.t_in;
    const pierce::Vec3d b = s.ray->org + s.ray->dir * s.t_out;
    const vtkIdType ids[2] = {points_->InsertNextPoint(a.x, a.y, a.z), points_->InsertNextPoint(b.x, b.y, b.z)};
    lines_->InsertNextCell(2, ids);
    const int solid = s.count == 1 ? int(s.solids[0]) : -1;
    std::string list, names;
    for (std::uint32_t k = 0; k < s.count; ++k) {
      if (k > 0) list += ' ', names += '+';
      list += std::to_string(s.solids[k]);
      names += surfaces_.scene.geometry(s.solids[k]).name;
    }
    const double obl_in = pierce::analysis::obliquity_deg(s.ray->dir, *s.in_hit),
                 obl_out = pierce::analysis::obliquity_deg(s.ray->dir, *s.out_hit);
    ray_id_->InsertNextValue(s.ray_id);
    solid_id_->InsertNextValue(solid);
    solid_count_->InsertNextValue(int(s.count));
    depth_->InsertNextValue(s.t_out - s.t_in);
    t_in_->InsertNextValue(s.t_in);
    t_out_->InsertNextValue(s.t_out);
    obl_in_->InsertNextValue(obl_in);
    obl_out_->InsertNextValue(obl_out);
    kind_->InsertNextValue(s.count == 0 ? "gap" : (s.count == 1 ? "solid" : "overlap"));
    solids_->InsertNextValue(list);
    names_->InsertNextValue(names);
    entry_->InsertNextTuple3(a.x, a.y, a.z);
    exit_->InsertNextTuple3(b.x, b.y, b.z);
  }

  void Finish(vtkPolyData* segments, vtkTable* table) {
    segments->SetPoints(points_);
    segments->SetLines(lines_);
    for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{
             ray_id_, solid_id_, solid_count_, depth_, t_in_, t_out_, obl_in_, obl_out_})
      segments->GetCellData()->AddArray(a);
    segments->GetCellData()->SetActiveScalars("SolidId");
    AddSolidNames(surfaces_, segments->GetFieldData());
    for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{
             ray_id_, kind_, solid_id_, solid_count_, solids_, names_, t_in_, t_out_, depth_, entry_, exit_,
             obl_in_, obl_out_})
      table->AddColumn(a);
  }

 private:
  const Surfaces& surfaces_;
  vtkSmartPointer<vtkPoints> points_;
  vtkSmartPointer<vtkCellArray> lines_;
  vtkSmartPointer<vtkIdTypeArray> ray_id_ = NewArray<vtkIdTypeArray>("RayId");
  vtkSmartPointer<vtkIntArray> solid_id_ = NewArray<vtkIntArray>("SolidId");
  vtkSmartPointer<vtkIntArray> solid_count_ = NewArray<vtkIntArray>("SolidCount");
  vtkSmartPointer<vtkDoubleArray> depth_ = NewArray<vtkDoubleArray>("Depth");
  vtkSmartPointer<vtkDoubleArray> t_in_ = NewArray<vtkDoubleArray>("TIn");
  vtkSmartPointer<vtkDoubleArray> t_out_ = NewArray<vtkDoubleArray>("TOut");
  vtkSmartPointer<vtkDoubleArray> obl_in_ = NewArray<vtkDoubleArray>("EntryObliquity");
  vtkSmartPointer<vtkDoubleArray> obl_out_ = NewArray<vtkDoubleArray>("ExitObliquity");
  vtkSmartPointer<vtkStringArray> kind_ = NewArray<vtkStringArray>("Kind");
  vtkSmartPointer<vtkStringArray> solids_ = NewArray<vtkStringArray>("Solids");
  vtkSmartPointer<vtkStringArray> names_ = NewArray<vtkStringArray>("Names");
  vtkSmartPointer<vtkDoubleArray> entry_ = MakePointArray("Entry");
  vtkSmartPointer<vtkDoubleArray> exit_ = MakePointArray("Exit");

  static vtkSmartPointer<vtkDoubleArray> MakePointArray(const char* name) {
    auto a = NewArray<vtkDoubleArray>(name);
    a->SetNumberOfComponents(3);
    return a;
  }
};

}  // namespace

bool ClassifyRays(const pierce::Scene& scene, const std::vector<pierce::Ray>& rays, ProgressBridge& progress,
                  ClassifiedRays& out) {
  out = ClassifiedRays{};
  out.ray_begin.reserve(rays.size() + 1);
  out.ray_begin.push_back(0);
  const pierce::Accel accel(scene);
  const pierce::KernelOptions options{pierce::HitOrder{pierce::TieOrder::leave_before_enter}};
  pierce::PartitionBuilder builder(scene.geometries().size());
  pierce::RayPartitions parts;
  std::vector<pierce::Ray> lines;
  pierce::HitBatch hits;
  for (std::size_t begin = 0; begin < rays.size(); begin += kChunk) {
    const std::size_t end = std::min(rays.size(), begin + kChunk);
    lines.clear();
    for (std::size_t i = begin; i < end; ++i) lines.push_back(pierce::full_line_ray(rays[i], scene.bounds()));
    const bool completed = pierce::trace_batch(accel, pierce::kDefaultKernel, lines, 0, hits, options,
                                               [&](std::size_t done, std::size_t) { return progress.Report(begin + done, rays.size()); });
    if (!completed || progress.CheckAbort()) return false;
    for (std::size_t i = begin; i < end; ++i) {
      builder.build(hits.of(i - begin), parts);
      clip_partitions(parts, rays[i].tmin, rays[i].tmax);
      if (parts.unmatched_leaves > 0 || parts.unclosed > 0) ++out.inconsistent_rays;
      const auto offset = static_cast<std::uint32_t>(out.solids.size());
      out.solids.insert(out.solids.end(), parts.solids.begin(), parts.solids.end());
      for (pierce::Partition p : parts.partitions) {
        p.first += offset;
        out.partitions.push_back(p);
      }
      out.ray_begin.push_back(out.partitions.size());
    }
  }
  return true;
}

void WritePartitions(const ClassifiedRays& classified, const RayInput& rays, const Surfaces& surfaces,
                     bool include_gaps, vtkPolyData* segments, vtkTable* table) {
  Writer writer(surfaces);
  for (std::size_t r = 0; r + 1 < classified.ray_begin.size(); ++r) {
    const pierce::Partition* previous = nullptr;
    for (std::size_t k = classified.ray_begin[r]; k < classified.ray_begin[r + 1]; ++k) {
      const pierce::Partition& p = classified.partitions[k];
      if (include_gaps && previous && previous->t_out < p.t_in)
        writer.Add({rays.source_ids[r], &rays.rays[r], previous->t_out, p.t_in, nullptr, 0, &previous->out_hit,
                    &p.in_hit});
      writer.Add({rays.source_ids[r], &rays.rays[r], p.t_in, p.t_out, classified.solids.data() + p.first, p.count,
                  &p.in_hit, &p.out_hit});
      previous = &p;
    }
  }
  writer.Finish(segments, table);
}

}  // namespace pierce_vtk
