// Ray-grid volumes and centroids of CAD solids against their exact values (OCCT BRepGProp).
//
// `pierce gqa` measures the tessellated mesh, so the gap to the exact CAD values has two parts:
//  - tessellation: every triangle lies within the linear deflection d of its face (BRepMesh's
//    criterion) and the mesh and the surface coincide on planar faces, so the mesh and the exact
//    solid differ only in a shell of thickness <= d over the curved faces:
//      |V_mesh - V_exact| <= d * A_curved,
//    and the centroid, (integral of x - c_exact over that shell) / V_mesh, moves by at most
//      |c_mesh - c_exact| <= R * d * A_curved / V_mesh   (R: largest |x - c_exact| on the solid);
//  - the ray grid: run_gqa refines until the volume changes by at most tol (relative) between passes
//    and the centroid by at most tol x scene diagonal, and must then be that close to the mesh's own
//    exact (divergence theorem) values, to float rounding of the hit distances (kFloat).
// The test checks each part and their sum, with the tessellation and tolerance `pierce gqa` uses.
#include <gtest/gtest.h>
#include <unistd.h>

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "pierce/analysis/gqa.h"
#include "pierce/io/model_io.h"

namespace pierce::analysis {
namespace {

namespace fs = std::filesystem;

// Hit distances come from float arithmetic: "exact" ray-grid results agree to about 1e-7 relative.
constexpr double kFloat = 1e-6;

struct ExactSolid {
  double volume = 0;
  Vec3d centroid;
  double curved_area = 0;  // area of the non-planar faces
  double radius = 0;       // largest distance from the centroid to the solid's bounding box corners
};

Vec3d to_vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

ExactSolid exact_properties(const TopoDS_Shape& solid) {
  ExactSolid e;
  GProp_GProps props;
  BRepGProp::VolumeProperties(solid, props);
  e.volume = props.Mass();
  e.centroid = to_vec(props.CentreOfMass());
  for (TopExp_Explorer f(solid, TopAbs_FACE); f.More(); f.Next()) {
    if (BRepAdaptor_Surface(TopoDS::Face(f.Current())).GetType() == GeomAbs_Plane) continue;
    GProp_GProps area;
    BRepGProp::SurfaceProperties(f.Current(), area);
    e.curved_area += area.Mass();
  }
  Bnd_Box box;
  BRepBndLib::Add(solid, box);
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  for (double x : {x0, x1})
    for (double y : {y0, y1})
      for (double z : {z0, z1}) e.radius = std::max(e.radius, length(Vec3d{x, y, z} - e.centroid));
  return e;
}

// The solids of a STEP or BREP file, exact, in OCCT's order (matched to Pierce's by centroid).
std::vector<ExactSolid> exact_solids(const std::string& path) {
  TopoDS_Shape shape;
  if (path.ends_with(".brep")) {
    BRep_Builder b;
    EXPECT_TRUE(BRepTools::Read(shape, path.c_str(), b)) << path;
  } else {
    STEPControl_Reader reader;
    EXPECT_EQ(reader.ReadFile(path.c_str()), IFSelect_RetDone) << path;
    reader.TransferRoots();
    shape = reader.OneShape();
  }
  std::vector<ExactSolid> out;
  for (TopExp_Explorer s(shape, TopAbs_SOLID); s.More(); s.Next()) out.push_back(exact_properties(s.Current()));
  return out;
}

struct MeshSolid {
  double volume = 0;
  Vec3d centroid;
};

// The mesh's own exact volume and centroid: signed tetrahedra from the origin.
MeshSolid mesh_properties(const Geometry& g) {
  MeshSolid m;
  Vec3d moment{};
  for (const Tri& t : g.triangles) {
    const Vec3d a = g.vertices[t[0]], b = g.vertices[t[1]], c = g.vertices[t[2]];
    const double w = dot(a, cross(b, c)) / 6.0;
    m.volume += w;
    moment = moment + (a + b + c) * (w / 4.0);
  }
  m.centroid = moment * (1.0 / m.volume);
  return m;
}

// Loads `path` as `pierce gqa` does (default tessellation and tolerance), runs gqa (from grid size
// `start_n`, 0 = the CLI's default) and checks every solid against the exact values. Returns the
// number of solids checked.
std::size_t check_against_exact(const std::string& path, int start_n = 0) {
  Scene scene;
  const std::vector<LoadedFile> loaded = add_any_model(scene, {path}, TessellationOptions{});
  const double deflection = loaded.at(0).linear_deflection;
  EXPECT_GT(deflection, 0);
  GqaOptions opts;  // the CLI's --tol default is GqaOptions' one
  opts.start_n = start_n;
  const double tol = opts.tolerance;
  const Accel accel(scene);
  const GqaResult r = run_gqa(accel, opts);
  std::string passes;
  for (const GqaPass& p : r.passes)
    passes += " n=" + std::to_string(p.n) + ": " + std::to_string(p.worst_change) + " (" + p.worst + ")";
  EXPECT_TRUE(r.converged) << path << passes;

  const std::vector<ExactSolid> exact = exact_solids(path);
  EXPECT_EQ(exact.size(), scene.geometries().size()) << path;
  std::vector<bool> used(exact.size(), false);
  for (std::uint32_t g = 0; g < scene.geometries().size() && g < r.solids.size(); ++g) {
    const MeshSolid mesh = mesh_properties(scene.geometry(g));
    // The exact solid this mesh tessellates: the nearest centroid (matched one to one).
    std::size_t best = exact.size();
    for (std::size_t k = 0; k < exact.size(); ++k)
      if (!used[k] && (best == exact.size() || length(exact[k].centroid - mesh.centroid) <
                                                    length(exact[best].centroid - mesh.centroid)))
        best = k;
    if (best == exact.size()) {
      ADD_FAILURE() << path << ": no exact solid left for " << scene.geometry(g).name;
      continue;
    }
    used[best] = true;
    const ExactSolid& e = exact[best];
    const GqaQuantities& q = r.solids[g];
    const std::string what = path + ": " + scene.geometry(g).name;

    // Tessellation error bounds.
    const double dv_mesh = deflection * e.curved_area + kFloat * e.volume;
    const double dc_mesh = e.radius * deflection * e.curved_area / mesh.volume + kFloat * scene.scale();
    EXPECT_LE(std::abs(mesh.volume - e.volume), dv_mesh) << what << ": mesh volume vs exact";
    EXPECT_LE(length(mesh.centroid - e.centroid), dc_mesh) << what << ": mesh centroid vs exact";

    // The ray grid approaches the mesh within its tolerance.
    const double dv_grid = (tol + kFloat) * mesh.volume;
    const double dc_grid = (tol + kFloat) * scene.scale();
    EXPECT_LE(std::abs(q.volume - mesh.volume), dv_grid)
        << what << ": gqa volume " << q.volume << " vs mesh " << mesh.volume;
    EXPECT_LE(length(q.centroid - mesh.centroid), dc_grid) << what << ": gqa centroid vs mesh";

    std::printf("%-40s V exact %.6f mesh %.6f gqa %.6f | mesh err %.2e <= %.2e, gqa-mesh %.2e <= %.2e\n",
                scene.geometry(g).name.substr(0, 40).c_str(), e.volume, mesh.volume, q.volume,
                std::abs(mesh.volume - e.volume), dv_mesh, std::abs(q.volume - mesh.volume), dv_grid);

    // Hence the exact CAD values within the sum of both.
    EXPECT_LE(std::abs(q.volume - e.volume), dv_grid + dv_mesh)
        << what << ": gqa volume " << q.volume << " vs exact " << e.volume;
    EXPECT_LE(length(q.centroid - e.centroid), dc_grid + dc_mesh)
        << what << ": gqa centroid (" << q.centroid.x << ", " << q.centroid.y << ", " << q.centroid.z
        << ") vs exact (" << e.centroid.x << ", " << e.centroid.y << ", " << e.centroid.z << ")";
  }
  return scene.geometries().size();
}

class GqaCad : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pierce_gqa_cad_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// A box, a cylinder and a sphere with a cap cut away, turned about the axis (1, 2, 3) so that no
// face is parallel to a grid's rays. (A face parallel to the rays that falls inside grid cells costs
// first-order error that the pass-to-pass change criterion does not see, docs/CSG.md, Accuracy; the
// plate assembly below has its faces on cell boundaries.)
TopoDS_Compound primitives() {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0.5, 0.5, 0.5), 1.5, 2.5, 1.0).Shape();
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(5, 1.5, 0), gp_Dir(0, 0, 1)), 1.0, 6.0).Shape();
  const TopoDS_Shape sphere = BRepPrimAPI_MakeSphere(gp_Pnt(1.5, 4.5, 4.5), 1.5).Shape();
  // The cutting plane z = 5 is 0.5 above the centre: a cap of height 1 goes.
  const TopoDS_Shape cap = BRepPrimAPI_MakeBox(gp_Pnt(-1, 2, 5), 5, 5, 2).Shape();
  BRepAlgoAPI_Cut cut(sphere, cap);
  EXPECT_TRUE(cut.IsDone());
  BRep_Builder b;
  TopoDS_Compound c;
  b.MakeCompound(c);
  b.Add(c, box);
  b.Add(c, cylinder);
  for (TopExp_Explorer s(cut.Shape(), TopAbs_SOLID); s.More(); s.Next()) b.Add(c, s.Current());
  gp_Trsf turn;
  turn.SetRotation(gp_Ax1(gp_Pnt(3, 3, 3), gp_Dir(1, 2, 3)), 0.7);
  return TopoDS::Compound(BRepBuilderAPI_Transform(c, turn, true).Shape());
}

TEST_F(GqaCad, PrimitivesInStepMatchBRepGProp) {
  const std::string path = (dir_ / "primitives.step").string();
  STEPControl_Writer writer;
  ASSERT_EQ(writer.Transfer(primitives(), STEPControl_AsIs), IFSelect_RetDone);
  ASSERT_EQ(writer.Write(path.c_str()), IFSelect_RetDone);
  // The exact values are what the geometry says (so the OCCT side of the test is right too).
  const std::vector<ExactSolid> exact = exact_solids(path);
  ASSERT_EQ(exact.size(), 3u);
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(exact[0].volume, 1.5 * 2.5 * 1.0, 1e-9);
  EXPECT_NEAR(exact[1].volume, pi * 6.0, 1e-6);
  EXPECT_NEAR(exact[2].volume, 4.0 / 3.0 * pi * 1.5 * 1.5 * 1.5 - pi * 1.0 * 1.0 * (3 * 1.5 - 1.0) / 3.0, 1e-6);
  EXPECT_GT(exact[2].curved_area, 0);
  EXPECT_EQ(exact[0].curved_area, 0);
  EXPECT_EQ(check_against_exact(path), 3u);
}

TEST_F(GqaCad, PrimitivesInBrepMatchBRepGProp) {
  const std::string path = (dir_ / "primitives.brep").string();
  ASSERT_TRUE(BRepTools::Write(primitives(), path.c_str()));
  EXPECT_EQ(check_against_exact(path), 3u);
}

TEST_F(GqaCad, PlateAssemblySampleMatchesBRepGProp) {
  EXPECT_EQ(check_against_exact(PIERCE_SAMPLES_DIR "/plate_assembly.step"), 4u);
}

}  // namespace
}  // namespace pierce::analysis
