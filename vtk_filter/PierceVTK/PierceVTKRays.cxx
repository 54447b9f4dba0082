#include "PierceVTKRays.h"

#include <cmath>
#include <limits>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataSetAttributes.h>
#include <vtkPointData.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkIdList.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace pierce_vtk {
namespace {

bool MakeRay(const double org[3], const double dir[3], double length, pierce::Ray& ray) {
  const pierce::Vec3d o{org[0], org[1], org[2]}, d{dir[0], dir[1], dir[2]};
  const double len = pierce::length(d);
  if (!pierce::all_finite(o) || !pierce::all_finite(d) || !(len > 0.0) || !std::isfinite(len)) return false;
  ray.org = o;
  ray.dir = d * (1.0 / len);
  ray.tmin = 0.0;
  ray.tmax = length;
  return true;
}

}  // namespace

bool ExtractRays(vtkDataSet* data, const double default_direction[3], vtkDataArray* direction_array,
                 double max_length, RayInput& out, std::string& error, vtkIdType id_offset, bool skip_ghosts) {
  out = RayInput{};
  if (skip_ghosts && (!data || data->GetNumberOfPoints() == 0)) return true;
  if (!data || data->GetNumberOfPoints() == 0) {
    error = "the ray input has no points";
    return false;
  }
  auto ghost = [&](vtkDataSetAttributes* attributes, vtkIdType i, int flags) {
    if (!skip_ghosts) return false;
    vtkDataArray* g = attributes->GetArray(vtkDataSetAttributes::GhostArrayName());
    return g && (int(g->GetTuple1(i)) & flags) != 0;
  };
  auto* poly = vtkPolyData::SafeDownCast(data);
  if (poly && poly->GetNumberOfLines() > 0) {
    out.from_cells = true;
    vtkCellArray* lines = poly->GetLines();
    const vtkIdType first_line = poly->GetNumberOfVerts();
    auto ids = vtkSmartPointer<vtkIdList>::New();
    for (vtkIdType c = 0; c < lines->GetNumberOfCells(); ++c) {
      lines->GetCellAtId(c, ids);
      if (ghost(poly->GetCellData(), first_line + c,
                vtkDataSetAttributes::DUPLICATECELL | vtkDataSetAttributes::HIDDENCELL))
        continue;
      pierce::Ray ray;
      double a[3] = {0, 0, 0}, b[3] = {0, 0, 0}, d[3];
      if (ids->GetNumberOfIds() >= 2) {
        poly->GetPoint(ids->GetId(0), a);
        poly->GetPoint(ids->GetId(ids->GetNumberOfIds() - 1), b);
      }
      for (int k = 0; k < 3; ++k) d[k] = b[k] - a[k];
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (!MakeRay(a, d, length, ray)) {
        ++out.skipped;
        continue;
      }
      out.rays.push_back(ray);
      out.source_ids.push_back(id_offset + first_line + c);
    }
    return true;
  }
  if (direction_array && direction_array->GetNumberOfComponents() != 3) {
    error = std::string("direction array '") + (direction_array->GetName() ? direction_array->GetName() : "") +
            "' has " + std::to_string(direction_array->GetNumberOfComponents()) + " components, not 3";
    return false;
  }
  const double length = max_length > 0.0 ? max_length : std::numeric_limits<double>::infinity();
  out.rays.reserve(std::size_t(data->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i) {
    double p[3], d[3] = {default_direction[0], default_direction[1], default_direction[2]};
    if (ghost(data->GetPointData(), i, vtkDataSetAttributes::DUPLICATEPOINT | vtkDataSetAttributes::HIDDENPOINT))
      continue;
    data->GetPoint(i, p);
    if (direction_array) direction_array->GetTuple(i, d);
    pierce::Ray ray;
    if (!MakeRay(p, d, length, ray)) {
      ++out.skipped;
      continue;
    }
    out.rays.push_back(ray);
    out.source_ids.push_back(id_offset + i);
  }
  return true;
}

}  // namespace pierce_vtk
