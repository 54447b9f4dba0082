#pragma once
// Helpers for the VTK filter tests: surfaces built from Pierce's generators (known geometry),
// multiblock assembly, and an observer that collects VTK error and warning messages.
#include <string>
#include <vector>

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkCompositeDataSet.h>
#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "pierce/generators.h"
#include "vtkPierceThickness.h"

namespace pierce::vtk_test {

inline vtkSmartPointer<vtkPolyData> to_polydata(const gen::Mesh& m) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  for (const Vec3d& p : m.vertices) points->InsertNextPoint(p.x, p.y, p.z);
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  for (const Tri& t : m.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    polys->InsertNextCell(3, ids);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  return pd;
}

inline vtkSmartPointer<vtkMultiBlockDataSet> to_multiblock(const std::vector<gen::Mesh>& meshes) {
  auto mb = vtkSmartPointer<vtkMultiBlockDataSet>::New();
  mb->SetNumberOfBlocks(static_cast<unsigned int>(meshes.size()));
  for (unsigned int i = 0; i < meshes.size(); ++i) {
    mb->SetBlock(i, to_polydata(meshes[i]));
    mb->GetMetaData(i)->Set(vtkCompositeDataSet::NAME(), meshes[i].name.c_str());
  }
  return mb;
}

// Collects the messages of ErrorEvent and WarningEvent on the object it observes (which then
// does not print them).
class MessageCollector : public vtkCommand {
 public:
  static MessageCollector* New() { return new MessageCollector; }
  void Execute(vtkObject*, unsigned long event, void* data) override {
    const std::string text = data ? static_cast<const char*>(data) : "";
    (event == vtkCommand::ErrorEvent ? errors : warnings).push_back(text);
  }
  void Watch(vtkObject* o) {
    o->AddObserver(vtkCommand::ErrorEvent, this);
    o->AddObserver(vtkCommand::WarningEvent, this);
  }
  bool ErrorContains(const std::string& what) const {
    for (const std::string& e : errors)
      if (e.find(what) != std::string::npos) return true;
    return false;
  }
  std::vector<std::string> errors, warnings;
};

// vtkPierceThickness on `input`, per cell (the tests compare face values), already updated.
inline vtkSmartPointer<vtkPierceThickness> thickness_per_cell(vtkDataObject* input) {
  auto f = vtkSmartPointer<vtkPierceThickness>::New();
  f->SetInputData(input);
  f->SetSampleAt(vtkPierceThickness::CELLS);
  f->Update();
  return f;
}

}  // namespace pierce::vtk_test
