// Thickness maps: ray, cone and sphere methods on scenes with known wall thickness.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <stdexcept>

#include <tbb/global_control.h>

#include "analysis_scenes.h"
#include "pierce/analysis/thickness.h"

namespace pierce::test {
namespace {

using analysis::compute_thickness;
using analysis::SampleAt;
using analysis::ThicknessMethod;
using analysis::ThicknessOptions;
using analysis::ThicknessResult;
using analysis::ThicknessStatus;
using analysis::thickness_along;
using analysis::ThicknessAlong;

// gen::box triangle i lies on the face with outward normal along axis i / 4, side (i / 2) % 2.
int box_face_axis(std::uint32_t tri) { return int(tri / 4); }

double share_within(const ThicknessResult& r, double expected, double tol) {
  std::size_t ok = 0;
  for (double t : r.thickness) ok += std::abs(t - expected) <= tol;
  return double(ok) / double(r.size());
}

class HollowSphere : public ::testing::Test {
 protected:
  static constexpr int kSubdivisions = 4;
  void SetUp() override {
    mesh_ = hollow_sphere(kSubdivisions, 0.95);
    world_ = make_world({mesh_});
    // Facets of a tessellated sphere lie inside it by up to e^2 / (8 r) (e: edge length); a
    // thickness ray meets a facet of the other shell, so that is the error to allow (twice, for
    // the vertex normal's deviation from the radius).
    const double e = max_edge_length(mesh_);
    tol_ = e * e / (4 * 0.95);
  }
  gen::Mesh mesh_;
  std::unique_ptr<World> world_;
  double tol_ = 0;
};

TEST_F(HollowSphere, RayThicknessPerVertexIsTheWall) {
  ASSERT_LT(tol_, 0.005);  // the tolerance must be far below the wall it checks
  ThicknessOptions o;
  o.method = ThicknessMethod::ray;
  o.per = SampleAt::vertex;
  const ThicknessResult r = compute_thickness(world_->accel, o);
  ASSERT_TRUE(r.completed);
  ASSERT_EQ(r.size(), mesh_.vertices.size());
  EXPECT_GE(share_within(r, 0.05, tol_), 0.99);
  ASSERT_EQ(r.solids.size(), 1u);
  EXPECT_EQ(r.solids[0].no_exit, 0u);
  EXPECT_NEAR(r.solids[0].summary.min, 0.05, tol_);
  EXPECT_NEAR(r.solids[0].summary.max, 0.05, tol_);
}

TEST_F(HollowSphere, EveryExactKernelGivesTheSameMap) {
  ThicknessOptions o;
  o.kernel = KernelKind::queue;
  const ThicknessResult a = compute_thickness(world_->accel, o);
  for (KernelKind k : {KernelKind::restart, KernelKind::embree_restart, KernelKind::filter}) {
    o.kernel = k;
    const ThicknessResult b = compute_thickness(world_->accel, o);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
      ASSERT_EQ(a.thickness[i], b.thickness[i]) << kernel_name(k) << " vertex " << i;
  }
}

TEST_F(HollowSphere, SphereMethodMatchesTheWall) {
  ThicknessOptions o;
  o.method = ThicknessMethod::sphere;
  const ThicknessResult r = compute_thickness(world_->accel, o);
  ASSERT_TRUE(r.completed);
  EXPECT_GE(share_within(r, 0.05, tol_), 0.99);
}

TEST_F(HollowSphere, PerFaceRayThickness) {
  ThicknessOptions o;
  o.per = SampleAt::face;
  const ThicknessResult r = compute_thickness(world_->accel, o);
  ASSERT_EQ(r.size(), mesh_.triangles.size());
  EXPECT_GE(share_within(r, 0.05, tol_), 0.99);
}

TEST_F(HollowSphere, CancelStopsEarly) {
  std::size_t calls = 0;
  const ThicknessResult r =
      compute_thickness(world_->accel, {}, [&](std::size_t, std::size_t) { return ++calls < 2; });
  EXPECT_FALSE(r.completed);
}

// A sample mask (how the ParaView filters split one scene's samples between MPI ranks) measures
// the selected elements exactly as the full run does, and only those.
TEST_F(HollowSphere, SampleMaskMeasuresTheSelectedElementsAsTheFullRun) {
  for (SampleAt per : {SampleAt::vertex, SampleAt::face}) {
    ThicknessOptions o;
    o.per = per;
    const ThicknessResult full = compute_thickness(world_->accel, o);
    const std::size_t n = per == SampleAt::vertex ? mesh_.vertices.size() : mesh_.triangles.size();
    o.sample_mask.assign(1, std::vector<std::uint8_t>(n, 0));
    for (std::size_t e = 0; e < n; e += 3) o.sample_mask[0][e] = 1;
    const ThicknessResult part = compute_thickness(world_->accel, o);
    ASSERT_EQ(part.size(), (n + 2) / 3);
    for (std::size_t i = 0; i < part.size(); ++i) {
      const std::uint32_t e = part.element[i];
      ASSERT_EQ(e % 3, 0u);
      ASSERT_EQ(full.element[e], e);
      ASSERT_EQ(std::bit_cast<std::uint64_t>(part.thickness[i]), std::bit_cast<std::uint64_t>(full.thickness[e]));
      ASSERT_EQ(part.status[i], full.status[e]);
    }
    o.sample_mask[0].pop_back();
    EXPECT_THROW(compute_thickness(world_->accel, o), std::invalid_argument);
  }
}

// Coincident vertices are measured once, at the first of them: a mask selecting only a later copy
// still gets the value (the first one is measured for it).
TEST(SampleMask, ACopyOfAnUnselectedVertexGetsItsValue) {
  const gen::Mesh sphere = hollow_sphere(2, 0.9);
  const gen::Mesh soup = triangle_soup(sphere);  // every triangle with its own three vertices
  const auto w = make_world({soup});
  ThicknessOptions o;
  const ThicknessResult full = compute_thickness(w->accel, o);
  o.sample_mask.assign(1, std::vector<std::uint8_t>(soup.vertices.size(), 0));
  const std::size_t last = soup.vertices.size() - 1;
  o.sample_mask[0][last] = 1;
  const ThicknessResult part = compute_thickness(w->accel, o);
  ASSERT_FALSE(part.element.empty());
  ASSERT_EQ(part.element.back(), last);
  EXPECT_TRUE(std::isfinite(part.thickness.back()));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(part.thickness.back()), std::bit_cast<std::uint64_t>(full.thickness[last]));
}

// Per-face ray thickness of every triangle of every box equals that box's extent along the
// triangle's normal.
void expect_box_widths(const ThicknessResult& r, const std::vector<gen::Mesh>& boxes) {
  for (std::size_t i = 0; i < r.size(); ++i) {
    const gen::Mesh& b = boxes[r.solid[i]];
    const Vec3d ext = b.vertices[7] - b.vertices[0];
    const Vec3d n = r.normal[i];
    const std::size_t axis = std::abs(n.x) > 0.5 ? 0 : (std::abs(n.y) > 0.5 ? 1 : 2);
    const double expected = ext[axis];
    EXPECT_NEAR(r.thickness[i], expected, 1e-6) << "solid " << r.solid[i] << " face " << r.element[i];
    EXPECT_EQ(r.status[i], ThicknessStatus::ok);
  }
}

TEST(BoxThickness, TwoBoxesSharingAFaceEachGetTheirOwnWidth) {
  const std::vector<gen::Mesh> boxes = {gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {3, 1, 1}, "b")};
  auto w = make_world(boxes);
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.min_thickness = 1.5;
  const ThicknessResult r = compute_thickness(w->accel, o);
  ASSERT_EQ(r.size(), 24u);
  expect_box_widths(r, boxes);
  // Thin flags and statistics follow the numbers.
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_EQ(r.thin[i], r.thickness[i] < 1.5) << i;
  ASSERT_EQ(r.solids.size(), 2u);
  EXPECT_EQ(r.solids[0].name, "a");
  EXPECT_EQ(r.solids[0].thin, 12u);
  EXPECT_EQ(r.solids[1].thin, 8u);
  EXPECT_NEAR(r.solids[1].summary.max, 2.0, 1e-6);
  EXPECT_NEAR(r.solids[1].summary.min, 1.0, 1e-6);
}

// thickness_along: the per-face thickness map's own rays, given from outside, give its values; the
// direction's length does not matter; bad input is refused.
TEST(BoxThickness, ThicknessAlongGivenRaysMatchesTheMap) {
  const std::vector<gen::Mesh> boxes = {gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {3, 1, 1}, "b")};
  auto w = make_world(boxes);
  ThicknessOptions o;
  o.per = SampleAt::face;
  const ThicknessResult r = compute_thickness(w->accel, o);
  std::vector<std::uint32_t> geoms;
  std::vector<Ray> rays;
  for (std::size_t i = 0; i < r.size(); ++i) {
    geoms.push_back(r.solid[i]);
    rays.push_back(Ray{r.point[i], r.normal[i] * -3.0});
  }
  const ThicknessAlong along = thickness_along(w->accel, geoms, rays, std::numeric_limits<double>::infinity());
  ASSERT_TRUE(along.completed);
  ASSERT_EQ(along.thickness.size(), r.size());
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_EQ(along.thickness[i], r.thickness[i]) << i;
  EXPECT_THROW(thickness_along(w->accel, {0}, rays, 1.0), std::invalid_argument);
  EXPECT_THROW(thickness_along(w->accel, std::vector<std::uint32_t>(rays.size(), 7), rays, 1.0), std::invalid_argument);
  EXPECT_THROW(thickness_along(w->accel, geoms, rays, 1.0, 1e-6, KernelKind::epsilon), std::invalid_argument);
  const ThicknessAlong cancelled =
      thickness_along(w->accel, geoms, rays, 1.0, 1e-6, KernelKind::queue, [](std::size_t, std::size_t) { return false; });
  EXPECT_FALSE(cancelled.completed);
}

// Each row of the map is its own element's, however the rays are split between threads: 300
// boxes of distinct extents (3 600 faces, dozens of chunks of the parallel loop) give every face
// its own box's width along its normal, on one thread and on two, bit for bit alike. (Neighbouring
// boxes differ by at least 0.005 in every extent; the float hits out at x = 1 500 are within
// 1e-3.)
TEST(BoxThickness, EveryRowIsItsOwnElementsOnAnyThreadCount) {
  std::vector<gen::Mesh> boxes;
  for (int k = 0; k < 300; ++k) {
    const Vec3d lo{5.0 * k, 0, 0};
    std::string name = "b";
    name += std::to_string(k);
    boxes.push_back(gen::box(lo, lo + Vec3d{1 + 0.01 * k, 2 + 0.005 * k, 3 + 0.007 * k}, name));
  }
  auto w = make_world(boxes);
  ThicknessOptions o;
  o.per = SampleAt::face;
  auto map_on = [&](std::size_t threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return compute_thickness(w->accel, o);
  };
  const ThicknessResult one = map_on(1), two = map_on(2);
  ASSERT_EQ(one.size(), 3600u);
  ASSERT_EQ(two.size(), one.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    const gen::Mesh& b = boxes[one.solid[i]];
    const Vec3d n = one.normal[i];
    const std::size_t axis = std::abs(n.x) > 0.5 ? 0 : (std::abs(n.y) > 0.5 ? 1 : 2);
    ASSERT_NEAR(one.thickness[i], (b.vertices[7] - b.vertices[0])[axis], 1e-3)
        << "solid " << one.solid[i] << " face " << one.element[i];
    ASSERT_EQ(two.solid[i], one.solid[i]) << i;
    ASSERT_EQ(two.element[i], one.element[i]) << i;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(two.thickness[i]), std::bit_cast<std::uint64_t>(one.thickness[i])) << i;
  }
}

TEST(BoxThickness, AllExactKernelsAgreeOnTouchingBoxes) {
  // Stacked plates share whole faces; a thickness ray from one plate's face starts on the
  // neighbour's coincident face.
  const auto plates = gen::stacked_plates(4, 1.0, 0.25);
  auto w = make_world(plates);
  for (KernelKind k : kAllKernels) {
    if (!is_exact(k)) continue;
    ThicknessOptions o;
    o.per = SampleAt::face;
    o.kernel = k;
    const ThicknessResult r = compute_thickness(w->accel, o);
    expect_box_widths(r, plates);
  }
}

TEST(BoxThickness, DuplicatedFacesGiveTheTrueWidth) {
  const gen::Mesh b = gen::box({0, 0, 0}, {2, 1, 0.5});
  // A single duplicated face (as STL exports produce), every face duplicated with the same
  // winding, and every face duplicated with alternating winding.
  gen::Mesh one_dup = b;
  one_dup.triangles.push_back(b.triangles[10]);
  one_dup.triangles.push_back(b.triangles[11]);
  for (const gen::Mesh& m : {one_dup, gen::duplicated(b, 2, false), gen::duplicated(b, 2, true)}) {
    auto w = make_world({m});
    ThicknessOptions o;
    o.per = SampleAt::face;
    const ThicknessResult r = compute_thickness(w->accel, o);
    ASSERT_EQ(r.size(), m.triangles.size());
    expect_box_widths(r, {b});
    // Per vertex (corner rays run diagonally): finite and positive, never 0.
    o.per = SampleAt::vertex;
    const ThicknessResult v = compute_thickness(w->accel, o);
    for (std::size_t i = 0; i < v.size(); ++i) {
      EXPECT_EQ(v.status[i], ThicknessStatus::ok);
      EXPECT_GT(v.thickness[i], 0.4);
    }
  }
}

TEST(BoxThickness, OpenMeshGivesNoThicknessWhereRaysEscape) {
  gen::Mesh b = gen::box({0, 0, 0}, {1, 1, 1});
  b.triangles.erase(b.triangles.begin() + 10, b.triangles.end());  // drop the +z face
  auto w = make_world({b});
  ThicknessOptions o;
  o.per = SampleAt::face;
  const ThicknessResult r = compute_thickness(w->accel, o);
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (r.element[i] == 8 || r.element[i] == 9) {  // -z face: its ray leaves through the hole
      EXPECT_TRUE(std::isnan(r.thickness[i]));
      EXPECT_EQ(r.status[i], ThicknessStatus::no_exit);
      EXPECT_EQ(r.thin[i], 0);
    } else {
      EXPECT_NEAR(r.thickness[i], 1.0, 1e-6);
    }
  }
  EXPECT_EQ(r.solids[0].no_exit, 2u);
  EXPECT_EQ(r.solids[0].valid, 8u);
}

TEST(BoxThickness, MaxDistanceCutsOff) {
  auto w = make_world({gen::box({0, 0, 0}, {4, 1, 1})});
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.max_distance = 2;
  const ThicknessResult r = compute_thickness(w->accel, o);
  for (std::size_t i = 0; i < r.size(); ++i) {
    if (box_face_axis(r.element[i]) == 0) EXPECT_EQ(r.status[i], ThicknessStatus::no_exit);
    else EXPECT_NEAR(r.thickness[i], 1.0, 1e-6);
  }
}

TEST(BoxThickness, SphereMethodIsTheLargestInscribedBall) {
  const Vec3d lo{0, 0, 0}, hi{3, 1, 2};
  auto w = make_world({gen::box(lo, hi)});
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.method = ThicknessMethod::sphere;
  const ThicknessResult r = compute_thickness(w->accel, o);
  for (std::size_t i = 0; i < r.size(); ++i) {
    // Ball centre p + r n: it fits while r <= half the extent along n and r <= the distance
    // from p to each side face.
    const int k = box_face_axis(r.element[i]);
    double rad = 0.5 * (hi - lo)[std::size_t(k)];
    for (int j = 0; j < 3; ++j)
      if (j != k) rad = std::min({rad, r.point[i][std::size_t(j)] - lo[std::size_t(j)],
                                  hi[std::size_t(j)] - r.point[i][std::size_t(j)]});
    EXPECT_NEAR(r.thickness[i], 2 * rad, 1e-9) << "face " << r.element[i];
  }
}

TEST(BoxThickness, ConeWithNarrowOpeningApproachesTheRay) {
  auto w = make_world({gen::box({0, 0, 0}, {10, 10, 1})});
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.method = ThicknessMethod::cone;
  o.cone_angle_deg = 20;
  const ThicknessResult r = compute_thickness(w->accel, o);
  for (std::size_t i = 0; i < r.size(); ++i)
    if (box_face_axis(r.element[i]) == 2) {
      // Rays at angle a to the normal travel 1 / cos(a) <= 1 / cos(10 deg) through the plate.
      EXPECT_GE(r.thickness[i], 1.0 - 1e-9);
      EXPECT_LE(r.thickness[i], 1.0 / std::cos(10 * std::acos(-1.0) / 180));
    }
  // The median aggregate stays in the same range; wide cones on a ball give chords < diameter.
  o.cone_aggregate = analysis::ConeAggregate::median;
  const ThicknessResult m = compute_thickness(w->accel, o);
  for (std::size_t i = 0; i < m.size(); ++i)
    if (box_face_axis(m.element[i]) == 2) {
      EXPECT_NEAR(m.thickness[i], 1.0, 0.02);
    }
}

TEST(BoxThickness, WideConeStaysWithinItsBounds) {
  auto w = make_world({gen::box({-5, -5, 0}, {5, 5, 1})});
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.method = ThicknessMethod::cone;
  const ThicknessResult r = compute_thickness(w->accel, o);
  for (std::size_t i = 0; i < r.size(); ++i)
    if (box_face_axis(r.element[i]) == 2) {
      EXPECT_GT(r.thickness[i], 1.0);
      EXPECT_LT(r.thickness[i], 2.0);  // 1 / cos(60 deg): the longest ray in a 120 degree cone
    }
}

TEST(ConeAggregate, DropsOutliersAndWeighsByAngle) {
  // Nine rays near 1, one running into a far wall: the outlier must not move the result.
  std::vector<std::pair<double, double>> la;
  for (int i = 0; i < 9; ++i) la.emplace_back(1.0 + 0.01 * (i % 3), 0.1 * (i + 1));
  la.emplace_back(25.0, 0.5);
  const double shapira = analysis::cone_aggregate(la, analysis::ConeAggregate::shapira, 0.1);
  EXPECT_GE(shapira, 1.0);
  EXPECT_LE(shapira, 1.02);
  EXPECT_NEAR(analysis::cone_aggregate(la, analysis::ConeAggregate::median, 0.1), 1.01, 1e-12);
  // Weights 1/angle: a short ray on the axis outweighs a longer one at a wide angle.
  // Here 3.0 is beyond one standard deviation (0.76) of the median (1.1) and is dropped.
  const std::vector<std::pair<double, double>> five = {{1.0, 0.0}, {1.2, 1.0}, {1.1, 0.5}, {1.1, 0.3}, {3.0, 0.6}};
  const double w = analysis::cone_aggregate(five, analysis::ConeAggregate::shapira, 0.1);
  const double w0 = 1 / 0.05, w1 = 1 / 1.0, w2 = 1 / 0.5, w3 = 1 / 0.3;
  EXPECT_NEAR(w, (w0 * 1.0 + w1 * 1.2 + w2 * 1.1 + w3 * 1.1) / (w0 + w1 + w2 + w3), 1e-12);
}

TEST(BoxThickness, SolidsSubsetAndBadOptions) {
  const std::vector<gen::Mesh> boxes = {gen::box({0, 0, 0}, {1, 1, 1}), gen::box({1, 0, 0}, {3, 1, 1})};
  auto w = make_world(boxes);
  ThicknessOptions o;
  o.per = SampleAt::face;
  o.solids = {1};
  const ThicknessResult r = compute_thickness(w->accel, o);
  ASSERT_EQ(r.size(), 12u);
  for (auto s : r.solid) EXPECT_EQ(s, 1u);
  o.solids = {5};
  EXPECT_THROW(compute_thickness(w->accel, o), std::invalid_argument);
  o.solids = {};
  o.kernel = KernelKind::epsilon;
  EXPECT_THROW(compute_thickness(w->accel, o), std::invalid_argument);
  o.kernel = KernelKind::queue;
  o.max_distance = -1;
  EXPECT_THROW(compute_thickness(w->accel, o), std::invalid_argument);
}

TEST(BoxThickness, UnweldedMeshUsesWeldedVertexNormals) {
  // Three vertices per triangle, as STL stores them: vertex normals must still average the
  // faces around each corner, so corner rays run diagonally into the box (not along one face
  // normal, which would give exactly 1 for every vertex).
  const gen::Mesh b = gen::box({0, 0, 0}, {1, 1, 1});
  const gen::Mesh soup = triangle_soup(b);
  auto w = make_world({soup});
  const ThicknessResult r = compute_thickness(w->accel, {});
  for (std::size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(r.thickness[i], std::sqrt(3.0), 1e-6);
}

}  // namespace
}  // namespace pierce::test

namespace pierce::test {
namespace {

// CAD mode without a B-rep (ThicknessOptions::tessellation_flags, as vtkPierceThickness gets them
// from a CAD reader): in a closed solid every ray must leave, so a ray that does not (here through
// a triangle turned upside down, which the ray enters instead of leaving) is a tessellation
// artefact, excluded from the statistics and counted; as a mesh the same sample is no_exit.
TEST(TessellationStatus, NoExitInAClosedCadSolidIsATessellationArtefact) {
  gen::Mesh box = gen::box({0, 0, 0}, {2, 1, 1}, "box");
  std::swap(box.triangles[0][1], box.triangles[0][2]);  // closed, but one triangle upside down
  auto w = make_world({box});
  ThicknessOptions o;
  o.per = SampleAt::face;
  const ThicknessResult mesh = compute_thickness(w->accel, o);
  o.tessellation_flags = {std::vector<std::uint8_t>(box.triangles.size(), 0)};
  const ThicknessResult cad = compute_thickness(w->accel, o);
  ASSERT_EQ(mesh.size(), cad.size());
  std::size_t no_exit = 0;
  for (std::size_t i = 0; i < mesh.size(); ++i) {
    if (mesh.status[i] == ThicknessStatus::no_exit) {
      ++no_exit;
      EXPECT_EQ(cad.status[i], ThicknessStatus::tessellation) << i;
    } else {
      EXPECT_EQ(cad.status[i], mesh.status[i]) << i;
      EXPECT_EQ(cad.thickness[i], mesh.thickness[i]) << i;
    }
  }
  EXPECT_GE(no_exit, 2u);  // the turned triangle's own sample and one whose ray meets it
  EXPECT_EQ(mesh.solids[0].no_exit, no_exit);
  EXPECT_EQ(mesh.solids[0].tessellation, 0u);
  EXPECT_EQ(cad.solids[0].no_exit, 0u);
  EXPECT_EQ(cad.solids[0].tessellation, no_exit);
  EXPECT_EQ(cad.solids[0].valid, mesh.solids[0].valid);
  EXPECT_TRUE(cad.brep_faces.empty());
  // A flag on a triangle: samples starting on it, or whose ray leaves through it, are excluded.
  o.tessellation_flags[0][4] = 1;  // on the face y = 0
  const ThicknessResult flagged = compute_thickness(w->accel, o);
  EXPECT_EQ(flagged.status[4], ThicknessStatus::tessellation);
  EXPECT_GT(flagged.solids[0].tessellation, cad.solids[0].tessellation);
  // Flags must match the scene.
  o.tessellation_flags = {std::vector<std::uint8_t>(3, 0)};
  EXPECT_THROW(compute_thickness(w->accel, o), std::invalid_argument);
  o.tessellation_flags = {{}, {}};
  EXPECT_THROW(compute_thickness(w->accel, o), std::invalid_argument);
}

}  // namespace
}  // namespace pierce::test
