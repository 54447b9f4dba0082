// Writes the CAD models the CLI tests use: `make_models DIR` creates DIR/assembly.step (the tests'
// STEP assembly, tests/occt/step_assembly.h: plate, two touching blocks, a clash sunk 0.5 into it) and
// DIR/hollow.brep (hollow sphere, outer radius 1, inner 0.95), DIR/sheet.brep (the bent sheet 0.5
// thick), DIR/folded.brep (the filleted box 10 x 8 x 6 with one triangle of its mesh folded) and
// DIR/torus.brep (the hollow torus, wall 0.2), DIR/pocket_part.step (a part with pocket floors 0.6,
// 0.8 and 1.5 thick); see tests/occt/step_assembly.h.
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <TopoDS_Solid.hxx>

#include <cstdio>
#include <filesystem>
#include <exception>
#include <string>

#include "step_assembly.h"

namespace {

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
  // An option (--help) is not a directory to write into.
  if (argc != 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  Message::DefaultMessenger()->ChangePrinters().Clear();  // no transfer statistics on stdout
  const std::string dir = argv[1];
  try {
    std::filesystem::create_directories(dir);
    namespace tm = pierce::test_models;
    tm::write_step_assembly(dir + "/assembly.step");
    tm::write_brep(tm::bent_sheet(), dir + "/sheet.brep");
    tm::write_brep(tm::with_folded_triangle(tm::filleted_box(), 0.01), dir + "/folded.brep");
    tm::write_brep(tm::hollow_torus(), dir + "/torus.brep");
    tm::write_brep(tm::thin_blended_plate(), dir + "/thin_plate.brep");
    tm::write_step_part(tm::pocket_part(), "pocket_part", dir + "/pocket_part.step");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_models: %s\n", e.what());
    return 1;
  }
  if (!write_hollow_sphere(dir + "/hollow.brep")) {
    std::fprintf(stderr, "make_models: writing %s/hollow.brep failed\n", dir.c_str());
    return 1;
  }
  return 0;
}
