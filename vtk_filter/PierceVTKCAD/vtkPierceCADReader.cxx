#include "vtkPierceCADReader.h"

#include <cstdint>
#include <exception>
#include <string>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkObjectFactory.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkTypeInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include "pierce/io/cad_io.h"
#include "pierce/io/cad_registry.h"

vtkStandardNewMacro(vtkPierceCADReader);

namespace
{

// The link of each triangle to its B-rep face, for vtkPierceThickness (PierceVTKBRep.h): the
// registered model, the solid and triangle in it, the face and the (u, v) of the triangle's
// corners there.
void AddBRepLink(const pierce::CadSolid& solid, std::int64_t modelKey, int solidId, vtkCellData* cells)
{
  const auto n = static_cast<vtkIdType>(solid.triangles.size());
  auto model = vtkSmartPointer<vtkTypeInt64Array>::New();
  model->SetName("BRepModel");
  model->SetNumberOfValues(n);
  model->FillValue(modelKey);
  auto solidIds = vtkSmartPointer<vtkIntArray>::New();
  solidIds->SetName("BRepSolid");
  solidIds->SetNumberOfValues(n);
  solidIds->Fill(solidId);
  auto triangles = vtkSmartPointer<vtkIntArray>::New();
  triangles->SetName("BRepTriangle");
  triangles->SetNumberOfValues(n);
  auto faces = vtkSmartPointer<vtkIntArray>::New();
  faces->SetName("BRepFace");
  faces->SetNumberOfValues(n);
  auto uv = vtkSmartPointer<vtkDoubleArray>::New();
  uv->SetName("BRepUV");
  uv->SetNumberOfComponents(6);
  uv->SetNumberOfTuples(n);
  for (vtkIdType t = 0; t < n; ++t)
  {
    triangles->SetValue(t, static_cast<int>(t));
    faces->SetValue(t, static_cast<int>(solid.link.face[static_cast<std::size_t>(t)]));
    uv->SetTypedTuple(t, solid.link.uv[static_cast<std::size_t>(t)].data());
  }
  cells->AddArray(model);
  cells->AddArray(solidIds);
  cells->AddArray(triangles);
  cells->AddArray(faces);
  cells->AddArray(uv);
}

vtkSmartPointer<vtkPolyData> ToPolyData(const pierce::CadSolid& solid, int solidId, std::int64_t modelKey)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(solid.vertices.size()));
  for (std::size_t i = 0; i < solid.vertices.size(); ++i)
  {
    const pierce::Vec3d& p = solid.vertices[i];
    points->SetPoint(static_cast<vtkIdType>(i), p.x, p.y, p.z);
  }
  auto triangles = vtkSmartPointer<vtkCellArray>::New();
  triangles->AllocateExact(static_cast<vtkIdType>(solid.triangles.size()),
    3 * static_cast<vtkIdType>(solid.triangles.size()));
  for (const pierce::Tri& t : solid.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    triangles->InsertNextCell(3, ids);
  }
  auto ids = vtkSmartPointer<vtkIntArray>::New();
  ids->SetName("SolidId");
  ids->SetNumberOfValues(static_cast<vtkIdType>(solid.triangles.size()));
  ids->Fill(solidId);
  // 1 where the tessellation folds against the B-rep (cad_io.h): vtkPierceThickness gives the
  // samples there status tessellation.
  auto folded = vtkSmartPointer<vtkUnsignedCharArray>::New();
  folded->SetName("TessellationFolded");
  folded->SetNumberOfValues(static_cast<vtkIdType>(solid.triangles.size()));
  for (std::size_t t = 0; t < solid.triangles.size(); ++t)
  {
    const bool f = t < solid.link.flags.size() && (solid.link.flags[t] & pierce::kTriangleFolded) != 0;
    folded->SetValue(static_cast<vtkIdType>(t), f ? 1 : 0);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(triangles);
  poly->GetCellData()->AddArray(ids);
  poly->GetCellData()->AddArray(folded);
  if (!solid.link.empty())
  {
    AddBRepLink(solid, modelKey, solidId, poly->GetCellData());
  }
  return poly;
}

}

vtkPierceCADReader::vtkPierceCADReader()
  : FileName(nullptr)
  , LinearDeflection(pierce::TessellationOptions{}.linear_deflection)
  , AngularDeflection(pierce::TessellationOptions{}.angular_deflection_deg)
{
  this->SetNumberOfInputPorts(0);
}

vtkPierceCADReader::~vtkPierceCADReader()
{
  this->SetFileName(nullptr);
}

int vtkPierceCADReader::CanReadFile(const char* fileName)
{
  return fileName && pierce::is_cad_file(fileName) ? 1 : 0;
}

int vtkPierceCADReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no file name");
    return 0;
  }
  pierce::TessellationOptions options;
  options.linear_deflection = this->LinearDeflection;
  options.angular_deflection_deg = this->AngularDeflection;
  pierce::CadModel model;
  try
  {
    model = pierce::load_cad_file(this->FileName, options);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  // Every rank loads the file, so every rank can look the faces up under the same key.
  const std::int64_t modelKey = pierce::register_cad_model(this->FileName, options, model);

  // Under MPI every rank asks for its piece: piece 0 gets the whole model, the others the same
  // blocks empty (a filter such as D3 then spreads it), so no triangle is there twice.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int piece = outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  // One warning per problem: from the piece that holds the model (not once per rank), and not
  // again when the same file is read again with the same options (the pipeline re-executing).
  std::string reported = this->FileName;
  reported += '\n' + std::to_string(options.linear_deflection) + ' ' + std::to_string(options.angular_deflection_deg);
  for (const std::string& warning : model.warnings)
  {
    reported += '\n' + warning;
  }
  if (piece == 0 && reported != this->ReportedWarnings)
  {
    for (const std::string& warning : model.warnings)
    {
      vtkWarningMacro(<< this->FileName << ": " << warning);
    }
    this->ReportedWarnings = reported;
  }
  vtkMultiBlockDataSet* output = vtkMultiBlockDataSet::GetData(outputVector, 0);
  output->SetNumberOfBlocks(static_cast<unsigned int>(model.solids.size()));
  for (std::size_t i = 0; i < model.solids.size(); ++i)
  {
    const auto block = static_cast<unsigned int>(i);
    output->SetBlock(block,
      piece == 0 ? ToPolyData(model.solids[i], static_cast<int>(i), modelKey) : vtkSmartPointer<vtkPolyData>::New());
    output->GetMetaData(block)->Set(vtkCompositeDataSet::NAME(), model.solids[i].name.c_str());
  }
  auto units = vtkSmartPointer<vtkStringArray>::New();
  units->SetName("Units");
  units->InsertNextValue(model.units);
  auto deflection = vtkSmartPointer<vtkDoubleArray>::New();
  deflection->SetName("LinearDeflection");
  deflection->InsertNextValue(model.linear_deflection);
  output->GetFieldData()->AddArray(units);
  output->GetFieldData()->AddArray(deflection);
  return 1;
}

void vtkPierceCADReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "LinearDeflection: " << this->LinearDeflection << "\n";
  os << indent << "AngularDeflection: " << this->AngularDeflection << "\n";
}
