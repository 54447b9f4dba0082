// Writes the CAD models the CLI tests use: `make_models DIR` creates DIR/assembly.step (the
// assembly of test_cad.cpp: plate, two touching blocks, a clash sunk 0.5 into the plate) and
// DIR/hollow.brep (hollow sphere, outer radius 1, inner 0.95).
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopoDS_Solid.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <gp_Trsf.hxx>

#include <cstdio>
#include <string>

namespace {

TopLoc_Location at(double x, double y, double z) {
  gp_Trsf t;
  t.SetTranslation(gp_Vec(x, y, z));
  return TopLoc_Location(t);
}

bool write_assembly(const std::string& path) {
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
  const bool ok = writer.Transfer(doc, STEPControl_AsIs) && writer.Write(path.c_str()) == IFSelect_RetDone;
  XCAFApp_Application::GetApplication()->Close(doc);
  return ok;
}

bool write_hollow_sphere(const std::string& path) {
  BRep_Builder b;
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  b.Add(solid, BRepPrimAPI_MakeSphere(1.0).Shell());
  b.Add(solid, BRepPrimAPI_MakeSphere(0.95).Shell().Reversed());
  return BRepTools::Write(solid, path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  Message::DefaultMessenger()->ChangePrinters().Clear();  // no transfer statistics on stdout
  const std::string dir = argv[1];
  if (!write_assembly(dir + "/assembly.step") || !write_hollow_sphere(dir + "/hollow.brep")) {
    std::fprintf(stderr, "make_models: writing failed\n");
    return 1;
  }
  return 0;
}
