#include "PierceVTKThickness.h"

#include <cmath>
#include <limits>
#include <sstream>

#include <vtkCellData.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnsignedCharArray.h>

#include "PierceVTKSurfaces.h"

namespace pierce_vtk {

namespace pa = pierce::analysis;

pa::ThicknessOptions ToThicknessOptions(const ThicknessSettings& s) {
  pa::ThicknessOptions o;
  o.method = s.method == 1 ? pa::ThicknessMethod::cone
                           : (s.method == 2 ? pa::ThicknessMethod::sphere : pa::ThicknessMethod::ray);
  o.per = s.sample_at == 1 ? pa::SampleAt::face : pa::SampleAt::vertex;
  o.max_distance = s.max_distance > 0.0 ? s.max_distance : std::numeric_limits<double>::infinity();
  o.min_thickness = s.min_thickness;
  o.cone_rays = s.cone_rays;
  o.cone_angle_deg = s.cone_angle;
  o.cone_aggregate = s.cone_aggregate == 1 ? pa::ConeAggregate::median : pa::ConeAggregate::shapira;
  return o;
}

void AttachThickness(const pa::ThicknessResult& result, Surfaces& surfaces) {
  const bool per_cell = result.per == pa::SampleAt::face;
  struct Arrays {
    vtkSmartPointer<vtkDoubleArray> thickness = vtkSmartPointer<vtkDoubleArray>::New();
    vtkSmartPointer<vtkUnsignedCharArray> thin = vtkSmartPointer<vtkUnsignedCharArray>::New();
    vtkSmartPointer<vtkUnsignedCharArray> status = vtkSmartPointer<vtkUnsignedCharArray>::New();
    vtkSmartPointer<vtkIntArray> solid = vtkSmartPointer<vtkIntArray>::New();
  };
  std::vector<Arrays> arrays(surfaces.solids.size());
  for (std::size_t g = 0; g < surfaces.solids.size(); ++g) {
    vtkPolyData* surface = surfaces.solids[g].surface;
    const vtkIdType n = per_cell ? surface->GetNumberOfCells() : surface->GetNumberOfPoints();
    Arrays& a = arrays[g];
    a.thickness->SetName("Thickness");
    a.thin->SetName("Thin");
    a.status->SetName("ThicknessStatus");
    a.solid->SetName("SolidId");
    a.thickness->SetNumberOfValues(n);
    a.thin->SetNumberOfValues(n);
    a.status->SetNumberOfValues(n);
    a.solid->SetNumberOfValues(n);
    a.thickness->Fill(std::numeric_limits<double>::quiet_NaN());
    a.thin->Fill(0);
    a.status->Fill(static_cast<unsigned char>(pa::ThicknessStatus::no_normal));
    a.solid->Fill(static_cast<int>(g));
  }
  for (std::size_t i = 0; i < result.size(); ++i) {
    Arrays& a = arrays[result.solid[i]];
    const vtkIdType e = static_cast<vtkIdType>(result.element[i]);
    a.thickness->SetValue(e, result.thickness[i]);
    a.thin->SetValue(e, result.thin[i]);
    a.status->SetValue(e, static_cast<unsigned char>(result.status[i]));
  }
  for (std::size_t g = 0; g < surfaces.solids.size(); ++g) {
    vtkPolyData* surface = surfaces.solids[g].surface;
    vtkDataSetAttributes* data = per_cell ? static_cast<vtkDataSetAttributes*>(surface->GetCellData())
                                          : static_cast<vtkDataSetAttributes*>(surface->GetPointData());
    data->AddArray(arrays[g].thickness);
    data->AddArray(arrays[g].thin);
    data->AddArray(arrays[g].status);
    data->AddArray(arrays[g].solid);
    data->SetActiveScalars("Thickness");
  }
}

void WriteThicknessTable(const pa::ThicknessResult& result, vtkTable* table) {
  auto column = [&](auto array, const std::string& name) {
    array->SetName(name.c_str());
    table->AddColumn(array);
    return array;
  };
  auto id = column(vtkSmartPointer<vtkIntArray>::New(), "SolidId");
  auto name = column(vtkSmartPointer<vtkStringArray>::New(), "Name");
  auto elements = column(vtkSmartPointer<vtkIdTypeArray>::New(), "Elements");
  auto valid = column(vtkSmartPointer<vtkIdTypeArray>::New(), "Valid");
  auto no_exit = column(vtkSmartPointer<vtkIdTypeArray>::New(), "NoExit");
  auto no_normal = column(vtkSmartPointer<vtkIdTypeArray>::New(), "NoNormal");
  auto thin = column(vtkSmartPointer<vtkIdTypeArray>::New(), "Thin");
  auto min = column(vtkSmartPointer<vtkDoubleArray>::New(), "Min");
  auto max = column(vtkSmartPointer<vtkDoubleArray>::New(), "Max");
  auto mean = column(vtkSmartPointer<vtkDoubleArray>::New(), "Mean");
  std::vector<vtkSmartPointer<vtkDoubleArray>> percentiles;
  if (!result.solids.empty()) {
    for (const auto& [q, value] : result.solids.front().summary.percentiles) {
      std::ostringstream n;
      n << 'P' << q;
      percentiles.push_back(column(vtkSmartPointer<vtkDoubleArray>::New(), n.str()));
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const pa::SolidThickness& s : result.solids) {
    id->InsertNextValue(static_cast<int>(s.geom));
    name->InsertNextValue(s.name);
    elements->InsertNextValue(static_cast<vtkIdType>(s.elements));
    valid->InsertNextValue(static_cast<vtkIdType>(s.valid));
    no_exit->InsertNextValue(static_cast<vtkIdType>(s.no_exit));
    no_normal->InsertNextValue(static_cast<vtkIdType>(s.no_normal));
    thin->InsertNextValue(static_cast<vtkIdType>(s.thin));
    const bool any = s.summary.count > 0;
    min->InsertNextValue(any ? s.summary.min : nan);
    max->InsertNextValue(any ? s.summary.max : nan);
    mean->InsertNextValue(any ? s.summary.mean : nan);
    for (std::size_t k = 0; k < percentiles.size(); ++k)
      percentiles[k]->InsertNextValue(any && k < s.summary.percentiles.size() ? s.summary.percentiles[k].second : nan);
  }
}

}  // namespace pierce_vtk
