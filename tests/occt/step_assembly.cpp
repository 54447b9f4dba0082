#include "step_assembly.h"

#include <BRepPrimAPI_MakeBox.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <gp_Trsf.hxx>

#include <stdexcept>

namespace pierce::test_models {
namespace {

TopLoc_Location at(double x, double y, double z) {
  gp_Trsf t;
  t.SetTranslation(gp_Vec(x, y, z));
  return TopLoc_Location(t);
}

}  // namespace

void write_step_assembly(const std::string& path) {
  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  const TDF_Label assy = tool->NewShape();
  TDataStd_Name::Set(assy, "plate_assy");
  const TDF_Label plate = tool->AddShape(BRepPrimAPI_MakeBox(10, 10, 2).Shape(), false);
  TDataStd_Name::Set(plate, "plate");
  const TDF_Label block = tool->AddShape(BRepPrimAPI_MakeBox(2, 2, 2).Shape(), false);
  TDataStd_Name::Set(block, "block");
  const TDF_Label clash = tool->AddShape(BRepPrimAPI_MakeBox(2, 2, 2).Shape(), false);
  TDataStd_Name::Set(clash, "clash");
  tool->AddComponent(assy, plate, TopLoc_Location());
  tool->AddComponent(assy, block, at(1, 1, 2));
  tool->AddComponent(assy, block, at(6, 1, 2));
  tool->AddComponent(assy, clash, at(6, 6, 1.5));
  tool->UpdateAssemblies();
  STEPCAFControl_Writer writer;
  writer.SetNameMode(true);
  const bool transferred = writer.Transfer(doc, STEPControl_AsIs);
  const bool written = transferred && writer.Write(path.c_str()) == IFSelect_RetDone;
  XCAFApp_Application::GetApplication()->Close(doc);
  if (!written) throw std::runtime_error("OpenCASCADE could not write " + path);
}

}  // namespace pierce::test_models
