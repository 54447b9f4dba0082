#include "vtkPierceRayClassify.h"

#include <string>

#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataSet.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTable.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKFilterSteps.h"
#include "PierceVTKPartitions.h"
#include "PierceVTKProgress.h"
#include "PierceVTKRays.h"
#include "PierceVTKSurfaces.h"

vtkStandardNewMacro(vtkPierceRayClassify);

vtkPierceRayClassify::vtkPierceRayClassify()
  : RayDirection{ 0.0, 0.0, 1.0 }
  , UseDirectionArray(false)
  , DirectionArrayName(nullptr)
  , MaxLength(0.0)
  , IncludeGaps(false)
  , InconsistentRays(0)
  , MaxReplicatedMB(4096.0)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

vtkPierceRayClassify::~vtkPierceRayClassify()
{
  this->SetDirectionArrayName(nullptr);
}

void vtkPierceRayClassify::SetRaysConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

void vtkPierceRayClassify::SetRaysData(vtkDataObject* rays)
{
  this->SetInputData(1, rays);
}

vtkTable* vtkPierceRayClassify::GetTableOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkPierceRayClassify::FillInputPortInformation(int port, vtkInformation* info)
{
  return pierce_vtk::FillSolidsInputInformation(port, info);
}

int vtkPierceRayClassify::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

int vtkPierceRayClassify::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  this->InconsistentRays = 0;
  pierce_vtk::SurfaceRun run;
  if (!run.Gather(this, vtkDataObject::GetData(inputVector[0], 0), this->MaxReplicatedMB, true))
  {
    return 0;
  }
  const pierce_vtk::Distribution& distribution = run.distribution;
  const pierce_vtk::Surfaces& surfaces = run.surfaces;
  // The rays stay where they are: each rank shoots its own (not its ghosts).
  vtkDataSet* rayInput = vtkDataSet::GetData(inputVector[1], 0);
  vtkDataArray* directions = nullptr;
  std::string error;
  bool ok = true;
  if (this->UseDirectionArray && rayInput && rayInput->GetNumberOfPoints() > 0)
  {
    const std::string name = this->DirectionArrayName ? this->DirectionArrayName : "";
    directions = rayInput->GetPointData()->GetArray(name.c_str());
    if (!directions)
    {
      error = "the ray input has no point array '" + name + "' for the ray directions";
      ok = false;
    }
  }
  vtkIdType rayElements = 0;
  if (rayInput)
  {
    vtkPolyData* rayLines = vtkPolyData::SafeDownCast(rayInput);
    rayElements = rayLines && rayLines->GetNumberOfLines() > 0 ? rayLines->GetNumberOfCells()
                                                               : rayInput->GetNumberOfPoints();
  }
  const vtkIdType rayIdOffset = distribution.ExclusiveSum(rayElements);
  pierce_vtk::RayInput rays;
  ok = ok &&
    pierce_vtk::ExtractRays(rayInput, this->RayDirection, directions, this->MaxLength, rays, error, rayIdOffset,
      surfaces.distributed);
  if (surfaces.distributed && !distribution.AllTrue(ok))
  {
    vtkErrorMacro(<< (ok ? std::string("another rank could not read its rays") : error));
    return 0;
  }
  if (!ok)
  {
    vtkErrorMacro(<< error);
    return 0;
  }
  if (rays.skipped > 0)
  {
    vtkWarningMacro(<< rays.skipped << " rays without a usable origin or direction were skipped");
  }

  pierce_vtk::ProgressBridge progress(this);
  pierce_vtk::ClassifiedRays classified;
  const bool completed = pierce_vtk::ClassifyRays(surfaces.scene, rays.rays, progress, classified);
  run.timer.Stage("BVH build and trace");
  if (!distribution.AllTrue(completed))
  {
    return 1; // aborted: the executive hands out empty outputs
  }
  this->InconsistentRays = static_cast<vtkIdType>(classified.inconsistent_rays);
  if (this->InconsistentRays > 0)
  {
    vtkWarningMacro(<< this->InconsistentRays
                    << " rays crossed an open or non-manifold solid (an entry without exit or an exit "
                       "without entry); those crossings claim nothing");
  }
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  pierce_vtk::WritePartitions(
    classified, rays, surfaces, this->IncludeGaps, vtkPolyData::GetData(outputVector, 0), table);
  distribution.GatherTableRows(table);
  pierce_vtk::ReportDistributedRun("Pierce Ray Classify", distribution, run.info, run.timer);
  return 1;
}

void vtkPierceRayClassify::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RayDirection: (" << this->RayDirection[0] << ", " << this->RayDirection[1] << ", "
     << this->RayDirection[2] << ")\n";
  os << indent << "UseDirectionArray: " << this->UseDirectionArray << "\n";
  os << indent << "DirectionArrayName: " << (this->DirectionArrayName ? this->DirectionArrayName : "(none)")
     << "\n";
  os << indent << "MaxLength: " << this->MaxLength << "\n";
  os << indent << "IncludeGaps: " << this->IncludeGaps << "\n";
  os << indent << "InconsistentRays: " << this->InconsistentRays << "\n";
  os << indent << "MaxReplicatedMB: " << this->MaxReplicatedMB << "\n";
}
