#include "step_assembly.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepOffsetAPI_ThruSections.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GC_MakeCircle.hxx>
#include <GC_MakeSegment.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Solid.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include <cmath>
#include <stdexcept>

namespace pierce::test_models {
namespace {

// Writes an XCAF document (names kept) as STEP and closes it; throws when OpenCASCADE cannot.
void write_and_close(const Handle(TDocStd_Document)& doc, const std::string& path) {
  STEPCAFControl_Writer writer;
  writer.SetNameMode(true);
  const bool transferred = writer.Transfer(doc, STEPControl_AsIs);
  const bool written = transferred && writer.Write(path.c_str()) == IFSelect_RetDone;
  XCAFApp_Application::GetApplication()->Close(doc);
  if (!written) throw std::runtime_error("OpenCASCADE could not write " + path);
}

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
  write_and_close(doc, path);
}

TopoDS_Shape bent_sheet() {
  auto p = [](double x, double z) { return gp_Pnt(x, 0, z); };
  const double c = 1.5, ri = 1.0, ro = 1.5, r2 = std::sqrt(0.5);
  BRepBuilderAPI_MakeWire w;
  auto seg = [&](gp_Pnt a, gp_Pnt b) { w.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(a, b).Value()).Edge()); };
  auto arc = [&](gp_Pnt a, gp_Pnt m, gp_Pnt b) {
    w.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(a, m, b).Value()).Edge());
  };
  seg(p(c, 0), p(12, 0));
  seg(p(12, 0), p(12, 0.5));
  seg(p(12, 0.5), p(c, 0.5));
  arc(p(c, 0.5), p(c - ri * r2, c - ri * r2), p(0.5, c));
  seg(p(0.5, c), p(0.5, 12));
  seg(p(0.5, 12), p(0, 12));
  seg(p(0, 12), p(0, c));
  arc(p(0, c), p(c - ro * r2, c - ro * r2), p(c, 0));
  if (!w.IsDone()) throw std::runtime_error("bent_sheet: profile is not a wire");
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(w.Wire(), true).Face();
  return BRepPrimAPI_MakePrism(face, gp_Vec(0, 8, 0)).Shape();
}

namespace {

// `shape` with every edge blended by a fillet of `radius`; `model` names the model in the error.
TopoDS_Shape with_all_edges_filleted(const TopoDS_Shape& shape, double radius, const char* model) {
  BRepFilletAPI_MakeFillet f(shape);
  for (TopExp_Explorer ex(shape, TopAbs_EDGE); ex.More(); ex.Next()) f.Add(radius, TopoDS::Edge(ex.Current()));
  f.Build();
  if (!f.IsDone()) throw std::runtime_error(std::string(model) + ": fillet failed");
  return f.Shape();
}

}  // namespace

TopoDS_Shape filleted_box() {
  return with_all_edges_filleted(BRepPrimAPI_MakeBox(10, 8, 6).Shape(), 1.0, "filleted_box");
}

TopoDS_Shape hollow_torus() {
  BRep_Builder b;
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  b.Add(solid, BRepPrimAPI_MakeTorus(5.0, 1.0).Shell());
  b.Add(solid, BRepPrimAPI_MakeTorus(5.0, 0.8).Shell().Reversed());
  return solid;
}

TopoDS_Shape thin_blended_plate() {
  const TopoDS_Shape plate =
      with_all_edges_filleted(BRepPrimAPI_MakeBox(30, 30, 0.3).Shape(), 0.01, "thin_blended_plate");
  const TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(15, 15, -0.3), gp_Dir(0, 0, 1)), 3.75, 0.9).Shape();
  BRepAlgoAPI_Cut cut(plate, hole);
  if (!cut.IsDone()) throw std::runtime_error("thin_blended_plate: hole failed");
  return cut.Shape();
}

TopoDS_Shape embossed_box() {
  const TopoDS_Shape body = BRepPrimAPI_MakeBox(10, 8, 6).Shape();
  const TopoDS_Shape dot =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(3, 4, 6), gp_Dir(0, 0, 1)), 1.0, kEmbossHeight).Shape();
  const TopoDS_Shape bar = BRepPrimAPI_MakeBox(gp_Pnt(6, 3.5, 6), 2, 1, kEmbossHeight).Shape();
  BRepAlgoAPI_Fuse with_dot(body, dot);
  if (!with_dot.IsDone()) throw std::runtime_error("embossed_box: fuse failed");
  BRepAlgoAPI_Fuse with_bar(with_dot.Shape(), bar);
  if (!with_bar.IsDone()) throw std::runtime_error("embossed_box: fuse failed");
  return with_bar.Shape();
}

TopoDS_Shape lofted_solid() {
  BRepOffsetAPI_ThruSections loft(true, false);
  const double r[3] = {5, 3, 4}, x[3] = {0, 1, 0}, y[3] = {0, 0, 1};
  for (int i = 0; i < 3; ++i) {
    const gp_Ax2 ax(gp_Pnt(x[i], y[i], 10.0 * i), gp_Dir(0, 0, 1));
    loft.AddWire(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(GC_MakeCircle(ax, r[i]).Value()).Edge()).Wire());
  }
  loft.Build();
  if (!loft.IsDone()) throw std::runtime_error("lofted_solid: loft failed");
  return loft.Shape();
}

namespace {

// A slot tool: the box [lo, lo + size] with its four edges along `axis` (0, 1, 2: x, y, z)
// rounded with `radius`, so its cut leaves a slot with rounded corners.
TopoDS_Shape rounded_slot(gp_Pnt lo, double dx, double dy, double dz, int axis, double radius) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(lo, dx, dy, dz).Shape();
  BRepFilletAPI_MakeFillet f(box);
  for (TopExp_Explorer ex(box, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    const gp_Pnt a = BRep_Tool::Pnt(TopExp::FirstVertex(e)), b = BRep_Tool::Pnt(TopExp::LastVertex(e));
    const double d[3] = {std::abs(a.X() - b.X()), std::abs(a.Y() - b.Y()), std::abs(a.Z() - b.Z())};
    if (d[axis] > 0 && d[(axis + 1) % 3] == 0 && d[(axis + 2) % 3] == 0) f.Add(radius, e);
  }
  f.Build();
  if (!f.IsDone()) throw std::runtime_error("rounded_slot: fillet failed");
  return f.Shape();
}

// `shape` minus every tool, in one boolean operation.
TopoDS_Shape cut_all(const TopoDS_Shape& shape, const TopTools_ListOfShape& tools, const char* model) {
  BRepAlgoAPI_Cut cut;
  TopTools_ListOfShape args;
  args.Append(shape);
  cut.SetArguments(args);
  cut.SetTools(tools);
  cut.Build();
  if (!cut.IsDone()) throw std::runtime_error(std::string(model) + ": cut failed");
  return cut.Shape();
}

}  // namespace

TopoDS_Shape sheet_heatsink() {
  // The U profile in the xz plane (sheet 1 thick, bends about (2, 2) and (28, 2), inner radius 1,
  // outer 2), extruded 40 along y.
  auto p = [](double x, double z) { return gp_Pnt(x, 0, z); };
  const double r2 = std::sqrt(0.5);
  BRepBuilderAPI_MakeWire w;
  auto seg = [&](gp_Pnt a, gp_Pnt b) { w.Add(BRepBuilderAPI_MakeEdge(GC_MakeSegment(a, b).Value()).Edge()); };
  auto arc = [&](gp_Pnt a, gp_Pnt m, gp_Pnt b) { w.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(a, m, b).Value()).Edge()); };
  seg(p(2, 0), p(28, 0));
  arc(p(28, 0), p(28 + 2 * r2, 2 - 2 * r2), p(30, 2));
  seg(p(30, 2), p(30, 20));
  seg(p(30, 20), p(29, 20));
  seg(p(29, 20), p(29, 2));
  arc(p(29, 2), p(28 + r2, 2 - r2), p(28, 1));
  seg(p(28, 1), p(2, 1));
  arc(p(2, 1), p(2 - r2, 2 - r2), p(1, 2));
  seg(p(1, 2), p(1, 20));
  seg(p(1, 20), p(0, 20));
  seg(p(0, 20), p(0, 2));
  arc(p(0, 2), p(2 - 2 * r2, 2 - 2 * r2), p(2, 0));
  if (!w.IsDone()) throw std::runtime_error("sheet_heatsink: profile is not a wire");
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(w.Wire(), true).Face();
  const TopoDS_Shape sheet = BRepPrimAPI_MakePrism(face, gp_Vec(0, 40, 0)).Shape();
  // Slots 1.2 wide, 3 apart along y: 12 across the base (20 long in x), 12 in each leg (10 high).
  TopTools_ListOfShape slots;
  const int per_wall = kHeatsinkSlots / 3;
  for (int i = 0; i < per_wall; ++i) {
    const double y = 1.9 + 3.0 * i;
    slots.Append(rounded_slot(gp_Pnt(5, y, -1), 20, 1.2, 3, 2, 0.5));
    slots.Append(rounded_slot(gp_Pnt(-1, y, 6), 3, 1.2, 10, 0, 0.5));
    slots.Append(rounded_slot(gp_Pnt(28, y, 6), 3, 1.2, 10, 0, 0.5));
  }
  return cut_all(sheet, slots, "sheet_heatsink");
}

void write_connector_assembly(const std::string& path) {
  // Two rows of pins, 2.54 apart in x and 3 apart in y, in cavities 1 x 1 through the housing.
  const int per_row = kConnectorPins / 2;
  TopoDS_Shape housing = with_all_edges_filleted(BRepPrimAPI_MakeBox(2.54 * per_row + 1.5, 8, 10).Shape(), 0.5, "connector");
  TopTools_ListOfShape cavities;
  auto pin_x = [](int i) { return 2.0 + 2.54 * i; };
  for (int i = 0; i < per_row; ++i)
    for (double y : {2.5, 5.5}) cavities.Append(BRepPrimAPI_MakeBox(gp_Pnt(pin_x(i) - 0.5, y - 0.5, -1), 1, 1, 12).Shape());
  housing = cut_all(housing, cavities, "connector");
  const TopoDS_Shape pin = with_all_edges_filleted(BRepPrimAPI_MakeBox(0.64, 0.64, 14).Shape(), 0.1, "connector pin");

  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  const TDF_Label assy = tool->NewShape();
  TDataStd_Name::Set(assy, "connector");
  const TDF_Label h = tool->AddShape(housing, false);
  TDataStd_Name::Set(h, "housing");
  const TDF_Label p = tool->AddShape(pin, false);
  TDataStd_Name::Set(p, "pin");
  tool->AddComponent(assy, h, TopLoc_Location());
  for (int i = 0; i < per_row; ++i)
    for (double y : {2.5, 5.5}) tool->AddComponent(assy, p, at(pin_x(i) - 0.32, y - 0.32, -3));
  tool->UpdateAssemblies();
  write_and_close(doc, path);
}

void write_step(const TopoDS_Shape& shape, const std::string& path) {
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone || writer.Write(path.c_str()) != IFSelect_RetDone)
    throw std::runtime_error("OpenCASCADE could not write " + path);
}

TopoDS_Shape with_folded_triangle(const TopoDS_Shape& shape, double deflection) {
  BRepMesh_IncrementalMesh mesh(shape, deflection, false, 0.5, false);
  Handle(Poly_Triangulation) best;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) t = BRep_Tool::Triangulation(TopoDS::Face(ex.Current()), loc);
    if (!t.IsNull() && (best.IsNull() || t->NbTriangles() > best->NbTriangles())) best = t;
  }
  if (best.IsNull()) throw std::runtime_error("with_folded_triangle: nothing meshed");
  const Standard_Integer k = best->NbTriangles() / 2 + 1;
  Standard_Integer a, b, c;
  best->Triangle(k).Get(a, b, c);
  best->SetTriangle(k, Poly_Triangle(a, c, b));
  return shape;
}

TopoDS_Shape pocket_part() {
  TopoDS_Shape part = BRepPrimAPI_MakeBox(60, 40, 12).Shape();
  const double top = 12;
  part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeBox(gp_Pnt(5, 5, 0.6), gp_Pnt(20, 15, top + 1)).Shape()).Shape();
  part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(12, 28, 0.8), gp::DZ()), 5, top).Shape()).Shape();
  part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeBox(gp_Pnt(25, 5, 1.5), gp_Pnt(55, 35, top + 1)).Shape()).Shape();
  return part;
}

void write_step_part(const TopoDS_Shape& shape, const std::string& name, const std::string& path) {
  Handle(TDocStd_Document) doc;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", doc);
  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
  TDataStd_Name::Set(tool->AddShape(shape, false), name.c_str());
  write_and_close(doc, path);
}

void write_brep(const TopoDS_Shape& shape, const std::string& path) {
  if (!BRepTools::Write(shape, path.c_str())) throw std::runtime_error("OpenCASCADE could not write " + path);
}

}  // namespace pierce::test_models
