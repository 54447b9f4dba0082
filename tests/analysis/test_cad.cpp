// CAD loading through OpenCASCADE: a STEP assembly written here with OCCT (names, placements,
// a repeated part, touching and clashing solids), a hollow sphere as BREP, error cases; then
// the thickness and overlap reports on the loaded assembly.
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Trsf.hxx>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "analysis_scenes.h"
#include "pierce/analysis/mesh_report.h"
#include "pierce/analysis/overlaps.h"
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/io/cad_io.h"
#include "pierce/io/model_io.h"
#include "../common/process_temp_dir.h"
#include "step_assembly.h"

namespace pierce::test {
namespace {

namespace fs = std::filesystem;
using namespace pierce::analysis;

const fs::path& temp_dir() { return process_temp_dir("pierce_cad_test_"); }

// The tests' STEP assembly (tests/occt/step_assembly.h): a 10 x 10 x 2 plate at the origin; the part
// "block" (2 x 2 x 2) placed twice on top of it, touching; "clash" (2 x 2 x 2) sunk 0.5 into the plate.
std::string write_assembly_step() {
  const std::string path = (temp_dir() / "assembly.step").string();
  test_models::write_step_assembly(path);
  return path;
}

const std::string& assembly_step() {
  static const std::string path = write_assembly_step();
  return path;
}

std::map<std::string, std::uint32_t> ids_by_name(const Scene& s) {
  std::map<std::string, std::uint32_t> m;
  for (std::uint32_t g = 0; g < s.geometries().size(); ++g) m[s.geometry(g).name] = g;
  return m;
}

TEST(CadStep, AssemblyLoadsWithNamesAndPlacements) {
  TessellationOptions t;
  t.linear_deflection = 0.01;
  const CadModel m = load_cad_file(assembly_step(), t);
  EXPECT_EQ(m.units, "mm");
  EXPECT_EQ(m.linear_deflection, 0.01);
  ASSERT_EQ(m.solids.size(), 4u);
  std::map<std::string, BBoxd> boxes;
  for (const CadSolid& s : m.solids) {
    BBoxd b;
    for (const Vec3d& p : s.vertices) b.extend(p);
    boxes[s.name] = b;
  }
  ASSERT_TRUE(boxes.count("plate_assy/plate")) << m.solids[0].name;
  ASSERT_TRUE(boxes.count("plate_assy/block"));
  ASSERT_TRUE(boxes.count("plate_assy/block#2"));
  ASSERT_TRUE(boxes.count("plate_assy/clash"));
  auto near = [](Vec3d a, Vec3d b) { return length(a - b) < 1e-9; };
  EXPECT_TRUE(near(boxes["plate_assy/plate"].hi, {10, 10, 2}));
  EXPECT_TRUE(near(boxes["plate_assy/block"].lo, {1, 1, 2}));
  EXPECT_TRUE(near(boxes["plate_assy/block#2"].lo, {6, 1, 2}));
  EXPECT_TRUE(near(boxes["plate_assy/clash"].lo, {6, 6, 1.5}));
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();

  // Closed, outward, right volume.
  Scene scene;
  add_any_model(scene, {assembly_step()}, t);
  for (const SolidReport& r : mesh_report(scene)) {
    EXPECT_TRUE(r.consistently_oriented) << r.name;
    EXPECT_NEAR(r.volume, r.name == "plate_assy/plate" ? 200.0 : 8.0, 1e-9) << r.name;
  }
}

TEST(CadStep, ThicknessAndOverlapReportsOfTheAssembly) {
  auto w = std::make_unique<World>([] {
    Scene s;
    add_any_model(s, {assembly_step()});
    return s;
  }());
  const auto id = ids_by_name(w->scene);
  ThicknessOptions o;
  o.per = SampleAt::face;
  const ThicknessResult r = compute_thickness(w->accel, o);
  ASSERT_TRUE(r.completed);
  for (const SolidThickness& s : r.solids) {
    EXPECT_EQ(s.valid, s.elements) << s.name;
    if (s.name == "plate_assy/plate") {
      // Its own 2 mm, also under the touching blocks and the clash; 10 across.
      EXPECT_NEAR(s.summary.min, 2.0, 1e-6);
      EXPECT_NEAR(s.summary.max, 10.0, 1e-6);
    } else {
      EXPECT_NEAR(s.summary.min, 2.0, 1e-6) << s.name;
      EXPECT_NEAR(s.summary.max, 2.0, 1e-6) << s.name;
    }
  }

  const RayOverlapReport rays = analyse_ray_overlaps(w->accel, axis_grid_rays(w->scene.bounds(), 48));
  ASSERT_EQ(rays.interferences.size(), 1u);
  const InterferencePair& clash = rays.interferences[0];
  EXPECT_EQ(std::minmax(clash.a, clash.b), std::minmax(id.at("plate_assy/plate"), id.at("plate_assy/clash")));
  EXPECT_NEAR(clash.penetration, 0.5, 1e-5);
  EXPECT_NEAR(clash.axis_max_depth[2], 0.5, 1e-5);
  ASSERT_EQ(rays.contacts.size(), 2u);
  for (const ContactPair& c : rays.contacts) {
    EXPECT_EQ(c.a, id.at("plate_assy/plate"));
    EXPECT_TRUE(c.b == id.at("plate_assy/block") || c.b == id.at("plate_assy/block#2"));
    EXPECT_NEAR(c.where.z, 2.0, 1e-5);
  }

  const CoplanarReport cop = find_coplanar_overlaps(w->scene);
  ASSERT_EQ(cop.solid_pairs.size(), 2u);  // the blocks' bottoms on the plate's top
  for (const CoplanarSolidPair& p : cop.solid_pairs) {
    EXPECT_EQ(p.a, id.at("plate_assy/plate"));
    EXPECT_NEAR(p.area, 4.0, 1e-9);
    EXPECT_EQ(p.opposite_facing, p.pairs);
    EXPECT_EQ(p.exact_pairs, p.pairs);
  }
}

// One solid: outer sphere radius 1, inner shell radius 0.95 reversed (the cavity).
TopoDS_Shape hollow_sphere_shape() {
  BRep_Builder b;
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  const TopoDS_Shape outer = BRepPrimAPI_MakeSphere(1.0).Shell();
  const TopoDS_Shape inner = BRepPrimAPI_MakeSphere(0.95).Shell();
  b.Add(solid, outer);
  b.Add(solid, inner.Reversed());
  return solid;
}

TEST(CadBrep, HollowSphereIsWoundOutwardAndHasTheWallThickness) {
  const std::string path = (temp_dir() / "hollow.brep").string();
  ASSERT_TRUE(BRepTools::Write(hollow_sphere_shape(), path.c_str()));
  TessellationOptions t;
  t.linear_deflection = 0.001;
  t.angular_deflection_deg = 10;
  Scene scene;
  const auto files = add_any_model(scene, {path}, t);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].units, "model units");
  ASSERT_EQ(scene.geometries().size(), 1u);
  EXPECT_EQ(scene.geometry(0).name, "hollow");
  const SolidReport rep = mesh_report(scene)[0];
  EXPECT_TRUE(rep.closed);
  EXPECT_TRUE(rep.consistently_oriented);
  const double pi = std::acos(-1.0);
  EXPECT_NEAR(rep.volume, 4.0 / 3.0 * pi * (1 - 0.95 * 0.95 * 0.95), 0.01);
  auto w = std::make_unique<World>(std::move(scene));
  const ThicknessResult r = compute_thickness(w->accel, {});
  std::size_t ok = 0;
  for (double v : r.thickness) ok += std::abs(v - 0.05) <= 2 * t.linear_deflection;
  EXPECT_GE(double(ok) / double(r.size()), 0.99);
}

TEST(CadIges, BoxLoadsAsASurface) {
  const std::string path = (temp_dir() / "box.igs").string();
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 0);  // faces mode
  writer.AddShape(BRepPrimAPI_MakeBox(3, 2, 1).Shape());
  writer.ComputeModel();
  ASSERT_TRUE(writer.Write(path.c_str()));
  Scene scene;
  add_any_model(scene, {path});
  ASSERT_GE(scene.geometries().size(), 1u);
  BBoxd b = scene.bounds();
  EXPECT_NEAR(b.hi.x, 3, 1e-6);
  EXPECT_NEAR(b.hi.y, 2, 1e-6);
  EXPECT_NEAR(b.hi.z, 1, 1e-6);
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = (temp_dir() / name).string();
  std::ofstream(path) << text;
  return path;
}

void expect_input_error(const std::string& path, const std::string& needle) {
  try {
    load_cad_file(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  }
}

TEST(CadErrors, MissingEmptyMalformedUnsupported) {
  expect_input_error((temp_dir() / "nope.step").string(), "no such file");
  expect_input_error(write_file("empty.step", ""), "empty");
  expect_input_error(write_file("garbage.step", "this is not a STEP file\n"), "STEP");
  expect_input_error(write_file("garbage.brep", "neither a BREP file\n"), "BREP");
  expect_input_error(write_file("garbage.igs", "nor an IGES file\n"), "IGES");
  expect_input_error(write_file("model.xyz", "x"), "unknown CAD format");
  Scene s;
  try {
    add_any_model(s, {write_file("model.abc", "x")});
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(".step"), std::string::npos) << e.what();
  }
  TessellationOptions bad;
  bad.angular_deflection_deg = 0;
  EXPECT_THROW(load_cad_file(assembly_step(), bad), InputError);
}

std::string assembly_text() {
  std::ifstream in(assembly_step());
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Replaces the parameters of the n-th (from the end when n < 0) entity of type `type`.
std::string break_entity(std::string s, const std::string& type, int n) {
  std::vector<std::size_t> found;
  for (std::size_t at = s.find(type); at != std::string::npos; at = s.find(type, at + 1)) found.push_back(at);
  EXPECT_FALSE(found.empty());
  const std::size_t at = found[n >= 0 ? std::size_t(n) : found.size() - std::size_t(-n)];
  const std::size_t open = s.find('(', at), close = s.find(';', at);
  s.replace(open, close - open, "(garbage ## !!)");
  return s;
}

TEST(CadErrors, PartlyReadableStepReportsWhatWasSkipped) {
  // A broken point in the last part's geometry and an entity of unknown type: the rest loads,
  // with warnings naming the entities.
  std::string s = break_entity(assembly_text(), "CARTESIAN_POINT", -1);
  s.insert(s.find("ENDSEC;", s.find("DATA;")), "#99999 = NOT_A_STEP_ENTITY(1,2,3);\n");
  const CadModel m = load_cad_file(write_file("broken.step", s));
  for (const std::string& w : m.warnings) std::cerr << "  warning: " << w << "\n";
  EXPECT_FALSE(m.solids.empty());
  ASSERT_FALSE(m.warnings.empty());
  bool names_entity = false;
  for (const std::string& w : m.warnings) names_entity |= w.find("entity #") != std::string::npos;
  EXPECT_TRUE(names_entity) << m.warnings.front();
}

TEST(CadErrors, CrashInsideOpenCascadeBecomesAnError) {
  // A broken placement point of the assembly makes OpenCASCADE 7.6 dereference a null handle;
  // it must surface as an InputError naming the file, twice in a row (handlers restored).
  const std::string path = write_file("broken_root.step", break_entity(assembly_text(), "CARTESIAN_POINT", 0));
  for (int i = 0; i < 2; ++i) expect_input_error(path, "STEP");
  // And the process still loads good files afterwards.
  EXPECT_EQ(load_cad_file(assembly_step()).solids.size(), 4u);
}

TEST(AnyModel, MeshesAndCadTogetherInArgumentOrder) {
  const std::string stl = write_file("tri.stl",
                                     "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 5\nvertex 1 0 5\n"
                                     "vertex 0 1 5\nendloop\nendfacet\nendsolid t\n");
  Scene scene;
  const auto files = add_any_model(scene, {stl, assembly_step()});
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].first_geometry, 0u);
  EXPECT_EQ(files[0].geometry_count, 1u);
  EXPECT_EQ(files[1].first_geometry, 1u);
  EXPECT_EQ(files[1].geometry_count, 4u);
  EXPECT_EQ(files[1].units, "mm");
  EXPECT_GT(files[1].linear_deflection, 0);
  EXPECT_EQ(scene.geometry(1).source, assembly_step());
}

}  // namespace
}  // namespace pierce::test
