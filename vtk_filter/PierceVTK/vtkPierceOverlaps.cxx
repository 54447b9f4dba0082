#include "vtkPierceOverlaps.h"

#include <stdexcept>
#include <string>

#include <vtkCompositeDataSet.h>
#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKOverlaps.h"
#include "PierceVTKProgress.h"
#include "PierceVTKSurfaces.h"

vtkStandardNewMacro(vtkPierceOverlaps);

vtkPierceOverlaps::vtkPierceOverlaps()
  : FindCoplanar(true)
  , Tolerance(0.0)
  , RaysPerAxis(128)
  , EpsilonRel(1e-5)
  , MaxReplicatedMB(4096.0)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkPierceOverlaps::~vtkPierceOverlaps() = default;

vtkTable* vtkPierceOverlaps::GetPairsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkPierceOverlaps::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

int vtkPierceOverlaps::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkDataObject" : "vtkTable");
  return 1;
}

int vtkPierceOverlaps::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return pierce_vtk::RequestSurfaceDataObject(inputVector, outputVector);
}

int vtkPierceOverlaps::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  const pierce_vtk::Distribution distribution;
  pierce_vtk::StageTimer timer;
  pierce_vtk::Surfaces surfaces;
  std::string error, info;
  if (!distribution.ExtractSurfaces(input, this->MaxReplicatedMB, false, surfaces, error, info))
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  for (const std::string& warning : surfaces.warnings)
  {
    vtkWarningMacro(<< warning);
  }

  pierce_vtk::OverlapSettings settings;
  settings.find_coplanar = this->FindCoplanar;
  settings.tolerance = this->Tolerance;
  settings.rays_per_axis = this->RaysPerAxis;
  settings.epsilon_rel = this->EpsilonRel;

  timer.Stage("gather");
  // Every rank analyses the whole scene (the coplanar pairs and the ray grid are global); each
  // keeps its own triangles' arrays, rank 0 the table.
  pierce_vtk::ProgressBridge progress(this);
  pierce_vtk::OverlapResults results;
  bool ok = true;
  bool completed = true;
  try
  {
    completed = pierce_vtk::RunOverlaps(surfaces.scene, settings, progress, results);
    timer.Stage("analysis");
  }
  catch (const std::exception& e)
  {
    error = e.what();
    ok = false;
  }
  if (!distribution.AllTrue(ok))
  {
    vtkErrorMacro(<< (ok ? std::string("the analysis failed on another rank") : error));
    return 0;
  }
  if (!distribution.AllTrue(completed))
  {
    return 1; // aborted: the executive hands out empty outputs
  }
  pierce_vtk::AttachOverlaps(results, surfaces);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  pierce_vtk::StoreSurfaces(surfaces, input, output);
  pierce_vtk::AddSolidNames(surfaces, output->GetFieldData());
  pierce_vtk::AddOverlapStatistics(results, output->GetFieldData());
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  pierce_vtk::WriteOverlapTable(results, surfaces, table);
  distribution.KeepTableOnRoot(table);
  pierce_vtk::ReportDistributedRun("Pierce Overlaps", distribution, info, timer);
  return 1;
}

void vtkPierceOverlaps::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FindCoplanar: " << this->FindCoplanar << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "RaysPerAxis: " << this->RaysPerAxis << "\n";
  os << indent << "EpsilonRel: " << this->EpsilonRel << "\n";
  os << indent << "MaxReplicatedMB: " << this->MaxReplicatedMB << "\n";
}
