#pragma once
// The steps every Pierce filter's RequestData takes around its analysis, written once: gather the
// solids' surfaces of input 0 on every rank, and run the analysis so that a failure on any rank
// stops all of them with one error.
#include <exception>
#include <string>
#include <utility>

#include <vtkAlgorithm.h>
#include <vtkSetGet.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKStageTimer.h"
#include "PierceVTKSurfaces.h"

class vtkDataObject;
class vtkInformation;

namespace pierce_vtk {

// What a filter's RequestData holds from start to end: the ranks, the stage times and the text
// for the run report (ReportDistributedRun), and the solids' surfaces of input 0.
struct SurfaceRun
{
  const Distribution distribution;
  StageTimer timer;
  Surfaces surfaces;
  std::string info;

  // Collective: Distribution::ExtractSurfaces of `input`, ending the stage "gather". Reports the
  // error on `filter` and returns false when the surfaces cannot be had; passes their warnings
  // on as the filter's warnings.
  bool Gather(vtkAlgorithm* filter, vtkDataObject* input, double maxReplicatedMB, bool orientOutward);
};

// FillInputPortInformation of every Pierce filter: input 0 (the solids) is a data set or a
// composite data set, any other input (the rays) a data set.
int FillSolidsInputInformation(int port, vtkInformation* info);

// Output 0 of the surface filters: the surfaces in the input's structure, with the solid names
// as field data.
void StoreSurfaceOutput(const Surfaces& surfaces, vtkDataObject* input, vtkDataObject* output);

// Collective: runs `analysis` (which may throw) and returns true when it succeeded on every rank;
// otherwise reports on `filter` this rank's error, or that another rank failed.
template <class Analysis>
bool RunOnEveryRank(vtkAlgorithm* filter, const Distribution& distribution, Analysis&& analysis)
{
  std::string error;
  bool ok = true;
  try
  {
    std::forward<Analysis>(analysis)();
  }
  catch (const std::exception& e)
  {
    error = e.what();
    ok = false;
  }
  if (!distribution.AllTrue(ok))
  {
    vtkErrorWithObjectMacro(filter, << (ok ? std::string("the analysis failed on another rank") : error));
    return false;
  }
  return true;
}

} // namespace pierce_vtk
