#include "PierceVTKFilterSteps.h"

#include <vtkAlgorithm.h>
#include <vtkDataObject.h>
#include <vtkInformation.h>


namespace pierce_vtk
{

bool SurfaceRun::Gather(vtkAlgorithm* filter, vtkDataObject* input, double maxReplicatedMB, bool orientOutward)
{
  std::string error;
  if (!this->distribution.ExtractSurfaces(input, maxReplicatedMB, orientOutward, this->surfaces, error, this->info))
  {
    vtkErrorWithObjectMacro(filter, << error);
    return false;
  }
  for (const std::string& warning : this->surfaces.warnings)
  {
    vtkWarningWithObjectMacro(filter, << warning);
  }
  this->timer.Stage("gather");
  return true;
}

int FillSolidsInputInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  if (port == 0)
  {
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  }
  return 1;
}

void StoreSurfaceOutput(const Surfaces& surfaces, vtkDataObject* input, vtkDataObject* output)
{
  StoreSurfaces(surfaces, input, output);
  AddSolidNames(surfaces, output->GetFieldData());
}

} // namespace pierce_vtk
