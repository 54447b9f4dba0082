#include "vtkPierceThickness.h"

#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <vtkDataObject.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkTable.h>

#include "PierceVTKBRep.h"
#include "PierceVTKDistributed.h"
#include "PierceVTKEnums.h"
#include "PierceVTKFilterSteps.h"
#include "PierceVTKProgress.h"
#include "PierceVTKSurfaces.h"
#include "PierceVTKThickness.h"
#include "pierce/io/cad_surfaces.h"
#include "pierce/kernel.h"

vtkStandardNewMacro(vtkPierceThickness);

namespace
{
namespace pa = pierce::analysis;
using pierce_vtk::IsCodeOf;

// The filter's enum codes are positions in core's name tables (PierceVTKEnums.h).
static_assert(IsCodeOf(vtkPierceThickness::RAY, pa::ThicknessMethod::ray) &&
  IsCodeOf(vtkPierceThickness::CONE, pa::ThicknessMethod::cone) &&
  IsCodeOf(vtkPierceThickness::SPHERE, pa::ThicknessMethod::sphere));
static_assert(IsCodeOf(vtkPierceThickness::POINTS, pa::SampleAt::vertex) &&
  IsCodeOf(vtkPierceThickness::CELLS, pa::SampleAt::face));
static_assert(IsCodeOf(vtkPierceThickness::SHAPIRA, pa::ConeAggregate::shapira) &&
  IsCodeOf(vtkPierceThickness::MEDIAN, pa::ConeAggregate::median));

pa::ThicknessOptions ThicknessOptionsOf(vtkPierceThickness& filter)
{
  pa::ThicknessOptions o;
  o.method = pierce_vtk::EnumAt<pa::ThicknessMethod>(filter.GetMethod());
  o.per = pierce_vtk::EnumAt<pa::SampleAt>(filter.GetSampleAt());
  o.max_distance =
    filter.GetMaxDistance() > 0.0 ? filter.GetMaxDistance() : std::numeric_limits<double>::infinity();
  o.min_thickness = filter.GetMinThickness();
  o.max_thickness =
    filter.GetMaxThickness() > 0.0 ? filter.GetMaxThickness() : std::numeric_limits<double>::infinity();
  o.cone_rays = filter.GetConeRays();
  o.cone_angle_deg = filter.GetConeAngle();
  o.cone_aggregate = pierce_vtk::EnumAt<pa::ConeAggregate>(filter.GetConeAggregate());
  return o;
}

// Sets `code` to the code of core's name `name`; reports an unknown name on `filter`.
template <class E>
bool SetCodeByName(vtkPierceThickness* filter, const char* name, int& code)
{
  try
  {
    const int parsed = pierce_vtk::EnumCodeOf<E>(name ? name : "");
    if (parsed == code)
    {
      return false;
    }
    code = parsed;
    return true;
  }
  catch (const std::invalid_argument& e)
  {
    vtkErrorWithObjectMacro(filter, << e.what());
    return false;
  }
}
} // namespace

void vtkPierceThickness::SetMethod(const char* name)
{
  if (SetCodeByName<pa::ThicknessMethod>(this, name, this->Method))
  {
    this->Modified();
  }
}

void vtkPierceThickness::SetSampleAt(const char* name)
{
  if (SetCodeByName<pa::SampleAt>(this, name, this->SampleAt))
  {
    this->Modified();
  }
}

void vtkPierceThickness::SetConeAggregate(const char* name)
{
  if (SetCodeByName<pa::ConeAggregate>(this, name, this->ConeAggregate))
  {
    this->Modified();
  }
}

const char* vtkPierceThickness::GetMethodAsString()
{
  return pierce_vtk::EnumNameAt<pa::ThicknessMethod>(this->Method);
}

const char* vtkPierceThickness::GetSampleAtAsString()
{
  return pierce_vtk::EnumNameAt<pa::SampleAt>(this->SampleAt);
}

const char* vtkPierceThickness::GetConeAggregateAsString()
{
  return pierce_vtk::EnumNameAt<pa::ConeAggregate>(this->ConeAggregate);
}

vtkPierceThickness::vtkPierceThickness()
  : Method(RAY)
  , SampleAt(POINTS)
  , MaxDistance(0.0)
  , MinThickness(0.0)
  , MaxThickness(0.0)
  , ConeRays(30)
  , ConeAngle(120.0)
  , ConeAggregate(SHAPIRA)
{
}

vtkPierceThickness::~vtkPierceThickness() = default;

vtkTable* vtkPierceThickness::GetStatisticsOutput()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkPierceThickness::AnalyseSurfaces(
  pierce_vtk::SurfaceRun& run, vtkDataObject* input, vtkInformationVector* outputVector)
{
  const pierce_vtk::Surfaces& surfaces = run.surfaces;
  pierce::analysis::ThicknessOptions options = ThicknessOptionsOf(*this);
  const bool perCell = this->SampleAt == CELLS;
  // CAD reader output: measured on the exact B-rep where the link to it holds.
  const pierce_vtk::CadInput cad = pierce_vtk::FindCadInput(surfaces, run.distribution);
  options.tessellation_flags = cad.folded;
  options.exact = cad.exact.get();
  if (run.distribution.IsRoot())
  {
    for (const std::string& warning : cad.warnings)
    {
      vtkWarningMacro(<< warning);
    }
  }
  pierce_vtk::VertexOwners owners;
  pierce::analysis::ThicknessOptions measureOptions = options;
  if (surfaces.distributed)
  {
    if (!perCell)
    {
      owners = pierce_vtk::FindVertexOwners(surfaces);
    }
    // Each rank measures its own samples; thin flags and regions come from the whole map,
    // assembled below, so that they are those of a serial run.
    measureOptions.sample_mask = pierce_vtk::OwnSampleMask(surfaces, perCell, owners);
    measureOptions.min_thickness = 0.0;
    measureOptions.max_thickness = std::numeric_limits<double>::infinity();
  }

  pierce_vtk::ProgressBridge progress(this, 0.05, 1.0);
  pierce::analysis::ThicknessResult result;
  std::unique_ptr<pierce::Accel> accel;
  if (!pierce_vtk::RunOnEveryRank(this, run.distribution, [&] {
        accel = std::make_unique<pierce::Accel>(surfaces.scene);
        run.timer.Stage("BVH build");
        this->UpdateProgress(0.05);
        result = pierce::analysis::compute_thickness(*accel, measureOptions, progress.Callback());
        run.timer.Stage("trace");
      }))
  {
    return 0;
  }
  if (!run.distribution.AllTrue(result.completed && !progress.CheckAbort()))
  {
    return 1; // aborted: the executive hands out empty outputs
  }
  if (surfaces.distributed)
  {
    run.info += "; " + pierce_vtk::DescribeSampleSplit(result, perCell, owners, run.distribution);
    options.sample_mask = pierce_vtk::AllSampleMask(surfaces, perCell, owners);
    const pierce::analysis::ThicknessResult mine = std::move(result);
    if (!pierce_vtk::RunOnEveryRank(this, run.distribution, [&] {
          result = pierce_vtk::AssembleThickness(*accel, options, mine, run.distribution);
          run.timer.Stage("assemble");
        }))
    {
      return 0;
    }
  }
  if (options.exact)
  {
    // Every rank the same arrays, whether or not its own samples lie on a B-rep.
    result.brep_faces.resize(result.size(), 0);
  }
  pierce_vtk::AttachThickness(result, run.surfaces, surfaces.distributed && !perCell ? &owners : nullptr);
  pierce_vtk::StoreSurfaceOutput(surfaces, input, vtkDataObject::GetData(outputVector, 0));
  pierce_vtk::WriteRegionTable(result, options, vtkDataObject::GetData(outputVector, 0)->GetFieldData());
  const std::vector<pierce::analysis::SolidThickness> statistics = surfaces.distributed
    ? pierce_vtk::GatherThicknessStatistics(surfaces, perCell, options, run.distribution)
    : result.solids;
  pierce_vtk::WriteThicknessTable(statistics, options.percentiles, vtkTable::GetData(outputVector, 1));
  pierce_vtk::ReportDistributedRun("Pierce Thickness", run.distribution, run.info, run.timer);
  return 1;
}

void vtkPierceThickness::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->GetMethodAsString() << "\n";
  os << indent << "SampleAt: " << this->GetSampleAtAsString() << "\n";
  os << indent << "MaxDistance: " << this->MaxDistance << "\n";
  os << indent << "MinThickness: " << this->MinThickness << "\n";
  os << indent << "MaxThickness: " << this->MaxThickness << "\n";
  os << indent << "ConeRays: " << this->ConeRays << "\n";
  os << indent << "ConeAngle: " << this->ConeAngle << "\n";
  os << indent << "ConeAggregate: " << this->GetConeAggregateAsString() << "\n";
}
