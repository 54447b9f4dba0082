#include "vtkPierceSurfaceAlgorithm.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>

#include "PierceVTKFilterSteps.h"
#include "PierceVTKSurfaces.h"

vtkPierceSurfaceAlgorithm::vtkPierceSurfaceAlgorithm()
  : MaxReplicatedMB(4096.0)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkPierceSurfaceAlgorithm::~vtkPierceSurfaceAlgorithm() = default;

int vtkPierceSurfaceAlgorithm::FillInputPortInformation(int port, vtkInformation* info)
{
  return pierce_vtk::FillSolidsInputInformation(port, info);
}

int vtkPierceSurfaceAlgorithm::FillOutputPortInformation(int port, vtkInformation* info)
{
  // Output 0's concrete type follows the input's (RequestDataObject).
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkDataObject" : "vtkTable");
  return 1;
}

int vtkPierceSurfaceAlgorithm::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return pierce_vtk::RequestSurfaceDataObject(inputVector, outputVector);
}

int vtkPierceSurfaceAlgorithm::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  pierce_vtk::SurfaceRun run;
  if (!run.Gather(this, input, this->MaxReplicatedMB, false))
  {
    return 0;
  }
  return this->AnalyseSurfaces(run, input, outputVector);
}

void vtkPierceSurfaceAlgorithm::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MaxReplicatedMB: " << this->MaxReplicatedMB << "\n";
}
