#include "vtkPierceOverlaps.h"

#include <string>

#include <vtkDataObject.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include "PierceVTKDistributed.h"
#include "PierceVTKFilterSteps.h"
#include "PierceVTKOverlaps.h"
#include "PierceVTKProgress.h"
#include "PierceVTKSurfaces.h"

vtkStandardNewMacro(vtkPierceOverlaps);

vtkPierceOverlaps::vtkPierceOverlaps()
  : FindCoplanar(true)
  , Tolerance(0.0)
  , RaysPerAxis(128)
  , EpsilonRel(1e-5)
  , Clearance(0.0)
{
}

vtkPierceOverlaps::~vtkPierceOverlaps() = default;

vtkTable* vtkPierceOverlaps::GetPairsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkPierceOverlaps::AnalyseSurfaces(
  pierce_vtk::SurfaceRun& run, vtkDataObject* input, vtkInformationVector* outputVector)
{
  pierce_vtk::OverlapSettings settings;
  settings.find_coplanar = this->FindCoplanar;
  settings.tolerance = this->Tolerance;
  settings.rays_per_axis = this->RaysPerAxis;
  settings.epsilon_rel = this->EpsilonRel;
  settings.clearance = this->Clearance;
  // Every rank analyses the whole scene (the coplanar pairs and the ray grid are global); each
  // keeps its own triangles' arrays, rank 0 the table.
  pierce_vtk::ProgressBridge progress(this);
  pierce_vtk::OverlapResults results;
  bool completed = true;
  if (!pierce_vtk::RunOnEveryRank(this, run.distribution, [&] {
        completed = pierce_vtk::RunOverlaps(run.surfaces.scene, settings, progress, results);
        run.timer.Stage("analysis");
      }))
  {
    return 0;
  }
  if (!run.distribution.AllTrue(completed))
  {
    return 1; // aborted: the executive hands out empty outputs
  }
  pierce_vtk::AttachOverlaps(results, run.surfaces);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  pierce_vtk::StoreSurfaceOutput(run.surfaces, input, output);
  pierce_vtk::AddOverlapStatistics(results, output->GetFieldData());
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  pierce_vtk::WriteOverlapTable(results, run.surfaces, table);
  run.distribution.KeepTableOnRoot(table);
  pierce_vtk::ReportDistributedRun("Pierce Overlaps", run.distribution, run.info, run.timer);
  return 1;
}

void vtkPierceOverlaps::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FindCoplanar: " << this->FindCoplanar << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "RaysPerAxis: " << this->RaysPerAxis << "\n";
  os << indent << "EpsilonRel: " << this->EpsilonRel << "\n";
  os << indent << "Clearance: " << this->Clearance << "\n";
}
