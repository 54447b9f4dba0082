/**
 * @class vtkPierceSurfaceAlgorithm
 * @brief Base of the Pierce filters that map solids' surfaces to the same surfaces with arrays
 * (vtkPierceThickness, vtkPierceOverlaps).
 *
 * Holds what those filters share: input 0 is a vtkPolyData (one solid) or a composite data set
 * (one solid per non-empty block); output 0 has the input's structure (the triangulated
 * surfaces), output 1 is a vtkTable; the MaxReplicatedMB limit for MPI runs; and the first step
 * of RequestData, gathering the surfaces. Subclasses implement AnalyseSurfaces, the rest (see
 * PierceVTKFilterSteps.h for the steps around the analysis).
 */
#ifndef vtkPierceSurfaceAlgorithm_h
#define vtkPierceSurfaceAlgorithm_h

#include "PierceVTKModule.h"
#include "vtkDataObjectAlgorithm.h"

namespace pierce_vtk
{
struct SurfaceRun;
}

class PIERCEVTK_EXPORT vtkPierceSurfaceAlgorithm : public vtkDataObjectAlgorithm
{
public:
  vtkAbstractTypeMacro(vtkPierceSurfaceAlgorithm, vtkDataObjectAlgorithm);
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
  // Gathers input 0's surfaces (collective), then hands them to AnalyseSurfaces.
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * The filter's own part of RequestData: analyses the gathered surfaces of `input` and fills the
   * outputs. Returns RequestData's result.
   */
  virtual int AnalyseSurfaces(
    pierce_vtk::SurfaceRun& run, vtkDataObject* input, vtkInformationVector* outputVector) = 0;

  double MaxReplicatedMB;

private:
  vtkPierceSurfaceAlgorithm(const vtkPierceSurfaceAlgorithm&) = delete;
  void operator=(const vtkPierceSurfaceAlgorithm&) = delete;
};

#endif
