/**
 * @class vtkPierceSurfaceAlgorithm
 * @brief Base of the Pierce filters that map solids' surfaces to the same surfaces with arrays
 * (vtkPierceThickness, vtkPierceOverlaps).
 *
 * Holds what those filters share: input 0 is a vtkPolyData (one solid) or a composite data set
 * (one solid per non-empty block); output 0 has the input's structure (the triangulated
 * surfaces), output 1 is a vtkTable; and the MaxReplicatedMB limit for MPI runs. Subclasses
 * implement RequestData (see PierceVTKFilterSteps.h for the steps around the analysis).
 */
#ifndef vtkPierceSurfaceAlgorithm_h
#define vtkPierceSurfaceAlgorithm_h

#include "PierceVTKModule.h"
#include "vtkDataObjectAlgorithm.h"

class PIERCEVTK_EXPORT vtkPierceSurfaceAlgorithm : public vtkDataObjectAlgorithm
{
public:
  vtkTypeMacro(vtkPierceSurfaceAlgorithm, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Under MPI (pvserver, pvbatch), every rank holds the whole surface: refuse, with an error
   * naming the size, when it would take more than this many MB per rank. <= 0: no limit.
   * Default 4096.
   */
  vtkSetMacro(MaxReplicatedMB, double);
  vtkGetMacro(MaxReplicatedMB, double);
  ///@}

protected:
  vtkPierceSurfaceAlgorithm();
  ~vtkPierceSurfaceAlgorithm() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  double MaxReplicatedMB;

private:
  vtkPierceSurfaceAlgorithm(const vtkPierceSurfaceAlgorithm&) = delete;
  void operator=(const vtkPierceSurfaceAlgorithm&) = delete;
};

#endif
