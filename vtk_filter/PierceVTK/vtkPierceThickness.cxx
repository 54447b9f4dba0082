#include "vtkPierceThickness.h"

#include <stdexcept>
#include <string>

#include <vtkCompositeDataSet.h>
#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKProgress.h"
#include "PierceVTKSurfaces.h"
#include "PierceVTKThickness.h"
#include "pierce/kernel.h"

vtkStandardNewMacro(vtkPierceThickness);

vtkPierceThickness::vtkPierceThickness()
  : Method(RAY)
  , SampleAt(POINTS)
  , MaxDistance(0.0)
  , MinThickness(0.0)
  , ConeRays(30)
  , ConeAngle(120.0)
  , ConeAggregate(SHAPIRA)
  , MaxReplicatedMB(4096.0)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkPierceThickness::~vtkPierceThickness() = default;

vtkTable* vtkPierceThickness::GetStatisticsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkPierceThickness::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

int vtkPierceThickness::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkDataObject" : "vtkTable");
  return 1;
}

int vtkPierceThickness::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return pierce_vtk::RequestSurfaceDataObject(inputVector, outputVector);
}

int vtkPierceThickness::RequestData(
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
  timer.Stage("gather");

  pierce_vtk::ThicknessSettings settings;
  settings.method = this->Method;
  settings.sample_at = this->SampleAt;
  settings.max_distance = this->MaxDistance;
  settings.min_thickness = this->MinThickness;
  settings.cone_rays = this->ConeRays;
  settings.cone_angle = this->ConeAngle;
  settings.cone_aggregate = this->ConeAggregate;
  pierce::analysis::ThicknessOptions options = pierce_vtk::ToThicknessOptions(settings);
  const bool perCell = this->SampleAt == CELLS;
  options.tessellation_flags = pierce_vtk::TessellationFlags(surfaces);
  pierce_vtk::VertexOwners owners;
  if (surfaces.distributed)
  {
    if (!perCell)
    {
      owners = pierce_vtk::FindVertexOwners(surfaces);
    }
    options.sample_mask = pierce_vtk::OwnSampleMask(surfaces, perCell, owners);
  }

  pierce_vtk::ProgressBridge progress(this, 0.05, 1.0);
  pierce::analysis::ThicknessResult result;
  bool ok = true;
  try
  {
    const pierce::Accel accel(surfaces.scene);
    timer.Stage("BVH build");
    this->UpdateProgress(0.05);
    result = pierce::analysis::compute_thickness(accel, options, progress.Callback());
    timer.Stage("trace");
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
  if (!distribution.AllTrue(result.completed && !progress.CheckAbort()))
  {
    return 1; // aborted: the executive hands out empty outputs
  }
  if (surfaces.distributed)
  {
    info += "; " + pierce_vtk::DescribeSampleSplit(result, perCell, owners, distribution);
    if (!perCell)
    {
      pierce_vtk::ShareVertexResults(surfaces, owners, distribution, result);
    }
  }
  pierce_vtk::AttachThickness(result, surfaces);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  pierce_vtk::StoreSurfaces(surfaces, input, output);
  pierce_vtk::AddSolidNames(surfaces, output->GetFieldData());
  const std::vector<pierce::analysis::SolidThickness> statistics = surfaces.distributed
    ? pierce_vtk::GatherThicknessStatistics(surfaces, perCell, options, distribution)
    : result.solids;
  pierce_vtk::WriteThicknessTable(statistics, options.percentiles, vtkTable::GetData(outputVector, 1));
  pierce_vtk::ReportDistributedRun("Pierce Thickness", distribution, info, timer);
  return 1;
}

void vtkPierceThickness::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->Method << "\n";
  os << indent << "SampleAt: " << this->SampleAt << "\n";
  os << indent << "MaxDistance: " << this->MaxDistance << "\n";
  os << indent << "MinThickness: " << this->MinThickness << "\n";
  os << indent << "ConeRays: " << this->ConeRays << "\n";
  os << indent << "ConeAngle: " << this->ConeAngle << "\n";
  os << indent << "ConeAggregate: " << this->ConeAggregate << "\n";
  os << indent << "MaxReplicatedMB: " << this->MaxReplicatedMB << "\n";
}
