// Thickness maps true to the CAD model: solids built here with OpenCASCADE (fillets on a thin
// bent sheet, blends meeting at corners, a hollow toroid), loaded through the CAD loader, and
// every sample checked against OpenCASCADE's exact ray intersection with the B-rep
// (IntCurvesFace_ShapeIntersector) from the sample's point along its inward normal. Plus the
// loader's fold detection on an injected fold: repaired by remeshing, or flagged with the
// `tessellation` status and left out of the statistics.
#include <gtest/gtest.h>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <Bnd_Box.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Lin.hxx>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <filesystem>
#include <limits>
#include <random>
#include <unistd.h>

#include "pierce/analysis/mesh_report.h"
#include "pierce/analysis/thickness.h"
#include "pierce/error.h"
#include "pierce/io/cad_surfaces.h"
#include "pierce/io/model_io.h"
#include "../common/process_temp_dir.h"
#include "step_assembly.h"

namespace pierce::test {
namespace {

namespace fs = std::filesystem;
using namespace pierce::analysis;

const fs::path& temp_dir() { return process_temp_dir("pierce_cad_exact_test_"); }

struct Loaded {
  Scene scene;
  std::vector<LoadedFile> files;
  std::shared_ptr<const CadSurfaces> exact;
};

std::unique_ptr<Loaded> load(const TopoDS_Shape& shape, const std::string& name, TessellationOptions t = {}) {
  const std::string path = (temp_dir() / (name + ".brep")).string();
  test_models::write_brep(shape, path);
  auto l = std::make_unique<Loaded>();
  l->files = add_any_model(l->scene, {path}, t);
  l->exact = cad_surfaces(l->files, l->scene.geometries().size());
  return l;
}

double diagonal(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  return std::sqrt(box.SquareExtent());
}

// The exact thickness: distance from p along dir to the first crossing of the B-rep beyond the
// start face (parameters below `skip` are the start face itself); NaN when there is none.
class ExactReference {
 public:
  ExactReference(const TopoDS_Shape& shape, double size) : size_(size) { x_.Load(shape, 1e-9 * size); }
  double exit(Vec3d p, Vec3d inward) {
    x_.Perform(gp_Lin(gp_Pnt(p.x, p.y, p.z), gp_Dir(inward.x, inward.y, inward.z)), 1e-7 * size_, 1e9 * size_);
    double best = std::numeric_limits<double>::quiet_NaN();
    if (!x_.IsDone()) return best;
    for (Standard_Integer i = 1; i <= x_.NbPnt(); ++i)
      if (!(x_.WParameter(i) >= best)) best = x_.WParameter(i);
    return best;
  }

 private:
  IntCurvesFace_ShapeIntersector x_;
  double size_;
};

struct Comparison {
  std::size_t compared = 0, ok = 0, tessellation = 0;
  double max_error = 0;
};

// Every valid sample of `r` against the exact reference along its normal; the wall of every
// sample (exact value) must not be contradicted: no valid value under half the exact one.
Comparison compare(const ThicknessResult& r, ExactReference& ref, double tol) {
  Comparison c;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r.status[i] == ThicknessStatus::tessellation) ++c.tessellation;
    if (r.status[i] != ThicknessStatus::ok) continue;
    ++c.ok;
    const double exact = ref.exit(r.point[i], r.normal[i] * -1.0);
    EXPECT_TRUE(std::isfinite(exact)) << "sample " << i << " has no exact exit";
    if (!std::isfinite(exact)) continue;
    ++c.compared;
    const double err = std::abs(r.thickness[i] - exact);
    c.max_error = std::max(c.max_error, err);
    EXPECT_LE(err, tol) << "sample " << i << " element " << r.element[i] << " at (" << r.point[i].x << ", "
                        << r.point[i].y << ", " << r.point[i].z << "): pierce " << r.thickness[i] << ", exact "
                        << exact;
  }
  return c;
}

void expect_b_rep_true(const TopoDS_Shape& shape, const std::string& name, SampleAt per, double wall_min,
                       const TessellationOptions& t = {}) {
  const auto l = load(shape, name, t);
  ASSERT_TRUE(l->exact);
  const double size = diagonal(shape);
  ThicknessOptions o;
  o.per = per;
  o.exact = l->exact.get();
  const Accel accel(l->scene);
  const ThicknessResult r = compute_thickness(accel, o);
  ASSERT_TRUE(r.completed);
  ExactReference ref(shape, size);
  const Comparison c = compare(r, ref, 1e-6 * size);
  std::cout << name << " per " << enum_name(per) << ": " << r.size() << " samples, " << c.compared
            << " compared, max error " << c.max_error << " (" << c.max_error / size << " of the size), "
            << c.tessellation << " tessellation\n";
  EXPECT_GT(c.compared, r.size() * 9 / 10);
  ASSERT_EQ(r.solids.size(), 1u);
  const SolidThickness& s = r.solids[0];
  EXPECT_TRUE(s.exact);
  EXPECT_EQ(s.tessellation, c.tessellation);
  EXPECT_EQ(s.valid, c.ok);
  // No false thin spot: the summary minimum is the wall.
  EXPECT_GE(s.summary.min, wall_min * (1 - 1e-6));
  EXPECT_EQ(r.brep_faces.size(), r.size());
  std::size_t edges = 0;
  for (auto f : r.brep_faces) {
    if (per == SampleAt::face) {
      EXPECT_EQ(f, 1);
    }
    edges += f >= 2;
  }
  EXPECT_EQ(s.edge_samples, edges);
  // Models with edges between faces (all but the torus, one face per tube): vertices on them are
  // sampled per face.
  if (per == SampleAt::vertex && l->files[0].cad[0].check.faces > 2) {
    EXPECT_GT(edges, 0u);
  }
  const TessellationCheck& chk = l->files[0].cad[0].check;
  std::cout << "  tessellation check: " << chk.faces << " faces, " << chk.folded_found << " folded found, "
            << chk.folded << " left, " << chk.slivers << " slivers, " << chk.remesh_rounds << " remesh rounds\n";
}

// One model sampled one way, with the model's thinnest wall.
struct BrepTrueCase {
  const char* name;  // also names the test and the model's file
  TopoDS_Shape (*model)();
  SampleAt per;
  double wall_min;
};

// Without it, GoogleTest prints the case's bytes (pointers included) into the test's name.
void PrintTo(const BrepTrueCase& c, std::ostream* os) { *os << c.name; }

class CadExactBrepTrue : public ::testing::TestWithParam<BrepTrueCase> {};

TEST_P(CadExactBrepTrue, SamplesAreBrepTrue) {
  const BrepTrueCase& c = GetParam();
  expect_b_rep_true(c.model(), c.name, c.per, c.wall_min);
}

INSTANTIATE_TEST_SUITE_P(Models, CadExactBrepTrue,
                         ::testing::Values(BrepTrueCase{"sheet_face", test_models::bent_sheet, SampleAt::face, 0.5},
                                           BrepTrueCase{"sheet_vertex", test_models::bent_sheet, SampleAt::vertex, 0.5},
                                           BrepTrueCase{"box_face", test_models::filleted_box, SampleAt::face, 1.0},
                                           BrepTrueCase{"box_vertex", test_models::filleted_box, SampleAt::vertex, 1.0},
                                           BrepTrueCase{"torus_face", test_models::hollow_torus, SampleAt::face, 0.2},
                                           BrepTrueCase{"torus_vertex", test_models::hollow_torus, SampleAt::vertex,
                                                        0.2}),
                         [](const ::testing::TestParamInfo<BrepTrueCase>& info) { return std::string(info.param.name); });

// Edges longer than max_edge_length split (more samples on big flat faces): every edge within
// the limit, the mesh still closed and consistently oriented, and every sample still B-rep true,
// on flat and curved faces (new vertices on curved faces lie on the chords and are projected).
// The plate per vertex is the hard one: split vertices along its sides at x = 11.25 shoot along
// lines that pass 0.0025 inside the hole's circle, within the sagitta of its facets, so the mesh
// shows no crossing there (CadSurfaces::hidden_crossing finds them).
TEST(CadExact, SplitEdgesKeepTheMeshClosedAndTheSamplesBRepTrue) {
  TessellationOptions split;
  split.max_edge_length = 4.0;
  const auto plain = load(test_models::thin_blended_plate(), "plate_plain");
  const auto l = load(test_models::thin_blended_plate(), "plate_split", split);
  const Geometry& g = l->scene.geometry(0);
  EXPECT_GT(g.triangles.size(), 2 * plain->scene.geometry(0).triangles.size());
  double longest = 0;
  for (const Tri& t : g.triangles)
    for (int k = 0; k < 3; ++k) longest = std::max(longest, length(g.vertices[t[std::size_t(k)]] - g.vertices[t[std::size_t((k + 1) % 3)]]));
  EXPECT_LE(longest, split.max_edge_length);
  const SolidReport report = mesh_report(l->scene).at(0);
  EXPECT_TRUE(report.closed);
  EXPECT_TRUE(report.consistently_oriented);
  EXPECT_EQ(l->files.at(0).cad.at(0).face.size(), g.triangles.size());
  expect_b_rep_true(test_models::thin_blended_plate(), "plate_split_face", SampleAt::face, 0.3, split);
  expect_b_rep_true(test_models::thin_blended_plate(), "plate_split_vertex", SampleAt::vertex, 0.3, split);
  split.max_edge_length = 2.0;
  expect_b_rep_true(test_models::filleted_box(), "box_split_face", SampleAt::face, 1.0, split);
  expect_b_rep_true(test_models::filleted_box(), "box_split_vertex", SampleAt::vertex, 1.0, split);
  split.max_edge_length = -1;
  EXPECT_THROW(load(test_models::filleted_box(), "box_bad_split", split), InputError);
}

// The thin plate with tiny blends: its mesh alone reads walls far under the sheet's 0.3 (where
// rays start on the blends' chords); on the B-rep every valid sample is B-rep true and the
// minimum is the sheet.
TEST(CadExact, ThinBlendedPlateHasNoFalseThinSpot) {
  expect_b_rep_true(test_models::thin_blended_plate(), "plate_face", SampleAt::face, 0.3);
  const auto l = load(test_models::thin_blended_plate(), "plate_min");
  ThicknessOptions o;
  o.per = SampleAt::face;
  const Accel accel(l->scene);
  const ThicknessResult mesh = compute_thickness(accel, o);
  o.exact = l->exact.get();
  const ThicknessResult exact = compute_thickness(accel, o);
  std::cout << "thin plate: mesh min " << mesh.solids[0].summary.min << ", B-rep min " << exact.solids[0].summary.min
            << "\n";
  EXPECT_LT(mesh.solids[0].summary.min, 0.5 * 0.3);  // the false thin spots this is about
  EXPECT_NEAR(exact.solids[0].summary.min, 0.3, 1e-6 * 43);
}

// A B-spline side meeting planar caps at acute rims: face samples there graze the side (where
// Newton or the mesh give no answer, the B-rep is intersected directly); vertex samples on the
// acute rims are taken along the mean of the faces' normals (each face's own would leave at once).
TEST(CadExact, LoftFaceSamplesAreBrepTrue) {
  expect_b_rep_true(test_models::lofted_solid(), "loft_face", SampleAt::face, 0.0);
}

TEST(CadExact, LoftVertexSamplesAreBrepTrue) {
  expect_b_rep_true(test_models::lofted_solid(), "loft_vertex", SampleAt::vertex, 0.0);
}

// The B-rep fallback: with the fold's flag withheld, rays that meet the upside-down triangle
// find no exit on the mesh; the exact intersection gives their B-rep value instead.
TEST(CadExact, NoExitOnTheMeshFallsBackToTheBrep) {
  const TopoDS_Shape folded = test_models::with_folded_triangle(test_models::filleted_box(), 0.01);
  const auto l = load(folded, "fold_unflagged", TessellationOptions{0.05, 15, 0});
  std::vector<CadLink> links = l->files[0].cad;
  ASSERT_EQ(links[0].check.folded, 1u);
  for (auto& f : links[0].flags) f = 0;
  const CadSurfaces unflagged(links);
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.exact = &unflagged;
  const Accel accel(l->scene);
  const ThicknessResult r = compute_thickness(accel, o);
  ExactReference ref(folded, diagonal(folded));
  const Comparison c = compare(r, ref, 1e-6 * diagonal(folded));
  EXPECT_EQ(c.tessellation, 0u);
  EXPECT_EQ(c.compared, r.size());
  // The mesh alone has samples without exit here: the fallback answered them.
  ThicknessOptions mesh_only;
  mesh_only.per = SampleAt::face;
  EXPECT_GT(compute_thickness(accel, mesh_only).solids[0].no_exit, 0u);
  // exact_exit itself: from inside the box along +x it leaves through x = 10; from outside, it
  // passes in through x = 0 and leaves through x = 10; away from the box it never leaves.
  const auto inside = unflagged.exact_exit(0, {5, 4, 3}, {1, 0, 0}, 0.0);
  ASSERT_TRUE(inside.has_value());
  EXPECT_NEAR(*inside, 5.0, 1e-9);
  const auto through = unflagged.exact_exit(0, {-2, 4, 3}, {1, 0, 0}, 0.0);
  ASSERT_TRUE(through.has_value());
  EXPECT_NEAR(*through, 12.0, 1e-9);
  EXPECT_FALSE(unflagged.exact_exit(0, {-2, 4, 3}, {-1, 0, 0}, 0.0).has_value());
}

// KiCad packages carry their lettering embossed a few microns high. A vertex on a letter's rim
// is sampled per face; the top face's ray runs down the letter's wall (on the boundary, then
// inside the body) and leaves at the bottom: the mesh meets the wall's chords at once, and
// OpenCASCADE reports a crossing at every edge the ray passes. Neither may read as a wall of
// microns (they did, on 0603, 0805 and 1206 packages).
TEST(CadExact, EmbossedMarkingRimsReadTheWallBelow) {
  const TopoDS_Shape shape = test_models::embossed_box();
  const auto l = load(shape, "embossed");
  ASSERT_TRUE(l->exact);
  const double top = 6 + test_models::kEmbossHeight;
  // Down the dot's wall from its rim, and down the bar's wall from its edge and its corner.
  for (const Vec3d rim : {Vec3d{4, 4, top}, Vec3d{3, 5, top}, Vec3d{7, 3.5, top}, Vec3d{6, 3.5, top}}) {
    const auto t = l->exact->exact_exit(0, rim, {0, 0, -1}, 1e-6);
    ASSERT_TRUE(t.has_value()) << "from (" << rim.x << ", " << rim.y << ")";
    EXPECT_NEAR(*t, top, 1e-9) << "from (" << rim.x << ", " << rim.y << ")";
  }
  const double size = diagonal(shape);
  for (const SampleAt per : {SampleAt::vertex, SampleAt::face}) {
    ThicknessOptions o;
    o.per = per;
    o.exact = l->exact.get();
    const ThicknessResult r = compute_thickness(Accel(l->scene), o);
    ASSERT_TRUE(r.completed);
    // Every valid sample's wall, known in closed form: straight down, the height of its point;
    // sideways, through the body or through the marking (at least the bar's width, 1).
    std::size_t down = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      ASSERT_EQ(r.status[i], ThicknessStatus::ok) << "sample " << i;
      if (r.normal[i].z > 1 - 1e-9) {
        ++down;
        EXPECT_NEAR(r.thickness[i], r.point[i].z, 1e-6 * size)
            << "per " << enum_name(per) << " sample " << i << " at (" << r.point[i].x << ", " << r.point[i].y
            << ", " << r.point[i].z << ")";
      } else {
        EXPECT_GE(r.thickness[i], 1.0 - 1e-6 * size) << "per " << enum_name(per) << " sample " << i;
      }
    }
    EXPECT_GT(down, 0u);
    EXPECT_GE(r.solids[0].summary.min, 1.0 - 1e-6 * size) << "per " << enum_name(per);
  }
}

// On the B-rep, the sheet's wall is exactly 0.5 across its flat legs and the bend: face samples
// on the big faces (not the end caps, whose normals run along the sheet) read 0.5.
TEST(CadExact, BentSheetWallIsHalfAMillimetreEverywhere) {
  const auto l = load(test_models::bent_sheet(), "sheet_wall");
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.exact = l->exact.get();
  const ThicknessResult r = compute_thickness(Accel(l->scene), o);
  std::size_t on_wall = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r.status[i] != ThicknessStatus::ok) continue;
    const Vec3d n = r.normal[i];
    if (std::abs(n.y) > 0.5) continue;                               // y end caps
    if (std::abs(n.x) > 0.99 && r.point[i].x > 11.99) continue;      // leg end x = 12
    if (std::abs(n.z) > 0.99 && r.point[i].z > 11.99) continue;      // leg end z = 12
    ++on_wall;
    EXPECT_NEAR(r.thickness[i], 0.5, 1e-6 * 17) << "sample " << i;
  }
  EXPECT_GT(on_wall, 40u);
}

// Thin regions on CAD input: a 40 x 30 x 10 block with two 8 x 6 pockets leaving floors of 0.5
// and 1.0 (thin under 1.5). Each floor is one region with its exact minimum and the area of both
// sides, covering two B-rep faces: its pocket's floor and the block's bottom, shared by both.
TEST(CadExact, PocketFloorsAreRegionsWithTheirFaces) {
  TopoDS_Shape block = BRepPrimAPI_MakeBox(40, 30, 10).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeBox(gp_Pnt(4, 4, 0.5), gp_Pnt(12, 10, 11)).Shape()).Shape();
  block = BRepAlgoAPI_Cut(block, BRepPrimAPI_MakeBox(gp_Pnt(16, 4, 1.0), gp_Pnt(24, 10, 11)).Shape()).Shape();
  const auto l = load(block, "pocket_block");
  for (SampleAt per : {SampleAt::face, SampleAt::vertex}) {
    ThicknessOptions o;
    o.per = per;
    o.min_thickness = 1.5;
    o.exact = l->exact.get();
    const ThicknessResult r = compute_thickness(Accel(l->scene), o);
    ASSERT_EQ(r.thin_regions.size(), 2u) << "per " << enum_name(per);
    const double floors[2] = {0.5, 1.0}, x0[2] = {4, 16};
    for (int k = 0; k < 2; ++k) {
      const ThicknessRegion& g = r.thin_regions[std::size_t(k)];
      EXPECT_NEAR(g.thickness, floors[k], 1e-9 * floors[k]) << "per " << enum_name(per);
      EXPECT_GE(g.point.x, x0[k] - 1e-9);
      EXPECT_LE(g.point.x, x0[k] + 8 + 1e-9);
      EXPECT_NEAR(g.area, 96, 9.6) << "per " << enum_name(per);
      EXPECT_EQ(g.faces.size(), 2u) << "per " << enum_name(per);
    }
    // The bottom face is in both; the floors differ.
    std::vector<std::uint32_t> shared;
    std::set_intersection(r.thin_regions[0].faces.begin(), r.thin_regions[0].faces.end(),
                          r.thin_regions[1].faces.begin(), r.thin_regions[1].faces.end(), std::back_inserter(shared));
    EXPECT_EQ(shared.size(), 1u) << "per " << enum_name(per);
  }
}

// Without the B-rep (a mesh of the same solid), the mesh's chords make the wall differ from 0.5
// by up to the deflection: refinement is what makes it exact.
TEST(CadExact, RefinementIsWhatMakesItExact) {
  const auto l = load(test_models::hollow_torus(), "torus_mesh", TessellationOptions{0.05, 15, 3});
  ThicknessOptions o;
  o.per = SampleAt::face;
  const ThicknessResult mesh = compute_thickness(Accel(l->scene), o);
  o.exact = l->exact.get();
  const ThicknessResult exact = compute_thickness(Accel(l->scene), o);
  double mesh_err = 0, exact_err = 0;
  for (std::size_t i = 0; i < mesh.size(); ++i) {
    // Samples on the outer tube (distance 1 from the core circle) cross the 0.2 wall.
    const Vec3d p = exact.point[i];
    const double rho = std::hypot(p.x, p.y) - 5.0;
    if (std::hypot(rho, p.z) < 0.9 || exact.status[i] != ThicknessStatus::ok) continue;
    if (mesh.status[i] == ThicknessStatus::ok) mesh_err = std::max(mesh_err, std::abs(mesh.thickness[i] - 0.2));
    exact_err = std::max(exact_err, std::abs(exact.thickness[i] - 0.2));
  }
  EXPECT_LT(exact_err, 1e-6 * 12);
  EXPECT_GT(mesh_err, 100 * exact_err);
  EXPECT_TRUE(mesh.brep_faces.empty());
}

// Cone and sphere on CAD input: the cone's rays are refined on the B-rep (none shorter than the
// 0.2 wall), the sphere's ball lives on the mesh (within the deflection of the wall).
TEST(CadExact, ConeAndSphereOnTheTorusWall) {
  const auto l = load(test_models::hollow_torus(), "torus_methods");
  const Accel accel(l->scene);
  const double deflection = l->files[0].linear_deflection;
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.exact = l->exact.get();
  o.method = ThicknessMethod::cone;
  const ThicknessResult cone = compute_thickness(accel, o);
  EXPECT_EQ(cone.solids[0].valid, cone.size());
  EXPECT_GE(cone.solids[0].summary.min, 0.2 - 1e-9);
  o.method = ThicknessMethod::sphere;
  const ThicknessResult sphere = compute_thickness(accel, o);
  EXPECT_EQ(sphere.solids[0].valid, sphere.size());
  EXPECT_NEAR(sphere.solids[0].summary.min, 0.2, 2 * deflection);
  EXPECT_NEAR(sphere.solids[0].summary.max, 0.2, 2 * deflection);
}

TEST(CadTessellation, FoldIsFoundAndRemeshed) {
  const TopoDS_Shape folded = test_models::with_folded_triangle(test_models::filleted_box(), 0.01);
  const auto l = load(folded, "fold_remeshed", TessellationOptions{0.05, 15, 3});
  ASSERT_EQ(l->files.size(), 1u);
  ASSERT_EQ(l->files[0].cad.size(), 1u);
  const TessellationCheck& c = l->files[0].cad[0].check;
  EXPECT_EQ(c.folded_found, 1u);
  EXPECT_EQ(c.faces_folded, 1u);
  EXPECT_GE(c.remesh_rounds, 1);
  EXPECT_EQ(c.folded, 0u);
  EXPECT_EQ(c.faces, 26u);  // 6 sides, 12 edge blends, 8 corner blends
  // Only the faces around the fold are meshed again, and the mesh stays closed and oriented.
  EXPECT_GE(c.faces_remeshed, 1u);
  EXPECT_LT(c.faces_remeshed, std::size_t(c.remesh_rounds) * c.faces);
  const analysis::SolidReport mesh = analysis::mesh_report(l->scene).at(0);
  EXPECT_TRUE(mesh.closed && mesh.consistently_oriented);
  EXPECT_EQ(mesh.duplicates, 0u);
  bool warned = false;
  for (const std::string& w : l->files[0].warnings) warned = warned || w.find("folded") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(CadTessellation, FoldLeftInPlaceIsFlaggedAndExcluded) {
  const TopoDS_Shape folded = test_models::with_folded_triangle(test_models::filleted_box(), 0.01);
  const auto l = load(folded, "fold_flagged", TessellationOptions{0.05, 15, 0});
  const CadLink& link = l->files[0].cad[0];
  EXPECT_EQ(link.check.folded, 1u);
  EXPECT_EQ(link.check.remesh_rounds, 0);
  std::uint32_t fold = kInvalidId;
  for (std::uint32_t t = 0; t < link.flags.size(); ++t)
    if (link.flags[t] & kTriangleFolded) fold = t;
  ASSERT_NE(fold, kInvalidId);
  for (const bool with_brep : {true, false}) {
    ThicknessOptions o;
    o.per = SampleAt::face;
    if (with_brep) {
      o.exact = l->exact.get();
    } else {
      o.tessellation_flags.resize(1);
      for (auto f : link.flags) o.tessellation_flags[0].push_back((f & kTriangleFolded) != 0);
    }
    const ThicknessResult r = compute_thickness(Accel(l->scene), o);
    EXPECT_EQ(r.status[fold], ThicknessStatus::tessellation);
    EXPECT_TRUE(std::isnan(r.thickness[fold]));
    std::size_t tess = 0, finite = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      tess += r.status[i] == ThicknessStatus::tessellation;
      finite += std::isfinite(r.thickness[i]);
    }
    EXPECT_EQ(r.solids[0].tessellation, tess);
    EXPECT_EQ(r.solids[0].valid, finite);
    EXPECT_EQ(r.solids[0].summary.count, finite);
    EXPECT_EQ(r.solids[0].elements, r.size());
    EXPECT_GE(r.solids[0].summary.min, with_brep ? 1.0 - 1e-6 : 0.9);
  }
}

// thickness_at: points near the surface are projected onto it and measured like a caliper.
TEST(CadExact, ThicknessAtChosenPoints) {
  const TopoDS_Shape sheet = test_models::bent_sheet();
  const auto l = load(sheet, "sheet_at");
  ThicknessOptions o;
  o.exact = l->exact.get();
  const Accel accel(l->scene);
  // On the outer face of the horizontal leg (z = 0), slightly off; on the bend's outer
  // cylinder; on the inner face of the vertical leg with a given normal; far inside the leg.
  const double r2 = std::sqrt(0.5);
  const std::vector<Vec3d> pts = {{6, 4, -0.01}, {1.5 - 1.5 * r2, 2, 1.5 - 1.5 * r2}, {0.5, 3, 6}, {6, 4, 0.2}};
  const std::vector<Vec3d> normals = {{0, 0, -1}, {-1, 0, -1}, {1, 0, 0}, {0, 0, -1}};
  const ThicknessResult r = thickness_at(accel, {0, 0, 0, 0}, pts, normals, o);
  ASSERT_EQ(r.size(), 4u);
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(r.status[i], ThicknessStatus::ok) << i;
    EXPECT_NEAR(r.thickness[i], 0.5, 1e-6 * 17) << i;
  }
  EXPECT_NEAR(r.point[0].z, 0.0, 1e-12);
  EXPECT_NEAR(r.point[3].z, 0.0, 1e-12);  // nearest boundary of (6, 4, 0.2): the face z = 0
  EXPECT_NEAR(r.point[2].x, 0.5, 1e-12);
  EXPECT_NEAR(std::hypot(r.point[1].x - 1.5, r.point[1].z - 1.5), 1.5, 1e-9);
  EXPECT_EQ(r.solids.size(), 1u);
  EXPECT_EQ(r.solids[0].valid, 4u);
  EXPECT_THROW(thickness_at(accel, {0, 1}, {pts[0], pts[1]}, {}, o), std::invalid_argument);
  EXPECT_THROW(thickness_at(accel, {0}, {pts[0], pts[1]}, {}, o), std::invalid_argument);
}

// Points exactly on the B-rep (about `count`, spread over the faces: uniform in each face's
// parameter box, kept where the face's trim holds them) with the face's outward normal.
struct OnBrep {
  std::vector<Vec3d> points, normals;
};
OnBrep points_on_brep(const TopoDS_Shape& shape, std::size_t count) {
  std::size_t faces = 0;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) ++faces;
  const std::size_t per_face = (count + faces - 1) / faces;
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  OnBrep out;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& face = TopoDS::Face(ex.Current());
    double u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    const BRepTopAdaptor_FClass2d trim(face, 1e-9);
    const BRepGProp_Face props(face);
    std::size_t kept = 0;
    for (int tries = 0; kept < per_face && tries < 100 * int(per_face); ++tries) {
      const double u = u0 + (u1 - u0) * unit(rng), v = v0 + (v1 - v0) * unit(rng);
      if (trim.Perform(gp_Pnt2d(u, v)) != TopAbs_IN) continue;
      gp_Pnt p;
      gp_Vec n;
      props.Normal(u, v, p, n);
      if (!(n.Magnitude() > 1e-9)) continue;  // a pole
      n.Normalize();
      out.points.push_back({p.X(), p.Y(), p.Z()});
      out.normals.push_back({n.X(), n.Y(), n.Z()});
      ++kept;
    }
  }
  return out;
}

// thickness_at at points exactly on curved B-rep faces (cylinders, blends meeting in spheres,
// tori, a B-spline loft, a thin blended plate with a hole): every point keeps its coordinates,
// and its thickness is OpenCASCADE's exact ray thickness along the face's inward normal to 1e-6
// of the part's size at 99.9 % of the points or more.
TEST(CadExact, ThicknessAtPointsOnTheBrepStaysOnThem) {
  struct Model {
    const char* name;
    TopoDS_Shape shape;
  };
  const Model models[] = {{"at_bent_sheet", test_models::bent_sheet()},
                          {"at_filleted_box", test_models::filleted_box()},
                          {"at_hollow_torus", test_models::hollow_torus()},
                          {"at_lofted_solid", test_models::lofted_solid()},
                          {"at_thin_blended_plate", test_models::thin_blended_plate()}};
  for (const Model& m : models) {
    const auto l = load(m.shape, m.name);
    ASSERT_TRUE(l->exact);
    const double size = diagonal(m.shape);
    const OnBrep on = points_on_brep(m.shape, 600);
    ASSERT_GE(on.points.size(), 500u) << m.name;
    ThicknessOptions o;
    o.exact = l->exact.get();
    const Accel accel(l->scene);
    const ThicknessResult r =
        thickness_at(accel, std::vector<std::uint32_t>(on.points.size(), 0), on.points, {}, o);
    ASSERT_EQ(r.size(), on.points.size());
    ExactReference ref(m.shape, size);
    std::size_t within = 0, moved = 0;
    double worst = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      moved += !(r.point[i] == on.points[i]);
      const double exact = ref.exit(on.points[i], on.normals[i] * -1.0);
      const double err = r.status[i] == ThicknessStatus::ok ? std::abs(r.thickness[i] - exact)
                                                            : std::numeric_limits<double>::infinity();
      if (err <= 1e-6 * size) ++within;
      else worst = std::max(worst, err);
    }
    std::cout << m.name << ": " << r.size() << " points on the B-rep, " << within << " within 1e-6 of the size, "
              << moved << " moved; worst miss " << worst / size << " of the size\n";
    EXPECT_EQ(moved, 0u) << m.name;
    EXPECT_GE(double(within), 0.999 * double(r.size())) << m.name;
  }
}

}  // namespace
}  // namespace pierce::test
