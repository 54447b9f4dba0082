// Ray-grid quantities: volumes and centroids converge to the exact mesh values within the requested
// tolerance (boxes, tessellated spheres, CSG combinations); touching solids give no gaps or
// overlaps; interpenetrating ones give the right pair, depth and overlap volume.
#include <gtest/gtest.h>

#include <cmath>

#include "csg_test_scenes.h"
#include "pierce/analysis/gqa.h"

namespace pierce::analysis {
namespace {

using csgtest::make_world;
using csgtest::mesh_centroid;
using csgtest::mesh_volume;

constexpr double kTol = 1e-3;
// Hit distances come from float arithmetic: "exact" results agree to about 1e-7 relative.
constexpr double kFloat = 1e-6;

GqaResult gqa(const csgtest::World& w, std::vector<std::string> regions = {}, double tol = kTol, int max_n = 1024) {
  GqaOptions o;
  o.tolerance = tol;
  o.max_n = max_n;
  for (const auto& r : regions) o.regions.push_back(parse_csg(r, w.scene));
  return run_gqa(w.accel, o);
}

void expect_within_tolerance(double estimate, double exact, double tol, const std::string& what) {
  EXPECT_LE(std::abs(estimate - exact), tol * std::abs(exact)) << what << ": " << estimate << " vs exact " << exact;
}

TEST(Gqa, SingleBoxIsExactAtTheFirstPasses) {
  const gen::Mesh b = gen::box({1, 2, 3}, {2, 4, 7}, "b");
  auto w = make_world({b});
  const GqaResult r = gqa(*w);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.passes.size(), 2u);
  ASSERT_EQ(r.solids.size(), 1u);
  EXPECT_EQ(r.solids[0].name, "b");
  EXPECT_NEAR(r.solids[0].volume, 8.0, 8 * kFloat);
  EXPECT_NEAR(r.solids[0].centroid.x, 1.5, kFloat);
  EXPECT_NEAR(r.solids[0].centroid.y, 3.0, kFloat);
  EXPECT_NEAR(r.solids[0].centroid.z, 5.0, kFloat);
  // Every ray of the last pass crosses the box twice.
  EXPECT_EQ(r.solids[0].crossings, 2u * 3u * std::uint64_t(r.n) * std::uint64_t(r.n));
  EXPECT_TRUE(r.overlaps.empty());
  EXPECT_TRUE(r.gaps.empty());
}

TEST(Gqa, SphereVolumeAndCentroidConvergeToTheMeshValues) {
  const gen::Mesh s = csgtest::sphere(1.3, {0.2, -0.4, 0.9}, "ball", 3);
  auto w = make_world({s});
  const GqaResult r = gqa(*w);
  ASSERT_TRUE(r.converged);
  EXPECT_GE(r.passes.size(), 2u);
  expect_within_tolerance(r.solids[0].volume, mesh_volume(s), kTol, "sphere volume");
  const Vec3d c = mesh_centroid(s);
  EXPECT_LE(length(r.solids[0].centroid - c), kTol * w->scene.scale());
  // A tighter tolerance takes more passes and still holds.
  const GqaResult tight = gqa(*w, {}, 2e-4);
  ASSERT_TRUE(tight.converged);
  EXPECT_GE(tight.n, r.n);
  expect_within_tolerance(tight.solids[0].volume, mesh_volume(s), 2e-4, "sphere volume (tight)");
}

TEST(Gqa, NotConvergedWhenTheGridCapIsTooCoarse) {
  auto w = make_world({csgtest::sphere(1.0, {0, 0, 0}, "ball", 3)});
  const GqaResult r = gqa(*w, {}, 1e-6, 64);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.n, 64);
  EXPECT_GT(r.passes.back().worst_change, 1e-6);
  EXPECT_EQ(r.passes.back().worst, "ball");
}

TEST(Gqa, TouchingBoxesAndPlateStackHaveNoGapsOrOverlaps) {
  auto w = make_world(gen::stacked_plates(20, 1.0, 0.1));
  const GqaResult r = gqa(*w);
  EXPECT_TRUE(r.converged);
  for (const GqaQuantities& q : r.solids) {
    EXPECT_NEAR(q.volume, 0.1, 0.1 * kFloat) << q.name;
    EXPECT_NEAR(q.centroid.x, 0.5, kFloat);
  }
  EXPECT_TRUE(r.overlaps.empty());
  EXPECT_TRUE(r.gaps.empty());

  // Touching cubes whose shared faces use different diagonals: the crossings of a shared face differ
  // by float rounding, which must not read as overlap or gap. Start at 12 so the cells align with the
  // unit cubes and the volumes are exact.
  auto g = make_world(gen::cube_grid(3));
  GqaOptions o;
  o.start_n = 12;
  const GqaResult rg = run_gqa(g->accel, o);
  EXPECT_TRUE(rg.converged);
  EXPECT_TRUE(rg.overlaps.empty());
  EXPECT_TRUE(rg.gaps.empty());
  for (const GqaQuantities& q : rg.solids) EXPECT_NEAR(q.volume, 1.0, kFloat) << q.name;
  EXPECT_EQ(rg.unmatched_leaves, 0u);
}

TEST(Gqa, RotatedTouchingCubesMeshedDifferentlyHaveNoGapsOrOverlaps) {
  // Shared faces triangulated with different diagonals and not axis-aligned: their crossings differ
  // by float rounding; snapping keeps that from reading as overlap or gap.
  std::vector<gen::Mesh> cubes = gen::cube_grid(2);
  for (gen::Mesh& m : cubes)
    for (Vec3d& v : m.vertices) v = csgtest::rotated(v);
  auto w = make_world(cubes);
  GqaOptions o;
  o.start_n = 32;
  o.max_n = 64;
  const GqaResult r = run_gqa(w->accel, o);
  EXPECT_TRUE(r.overlaps.empty()) << r.overlaps.size() << " overlapping pairs, e.g. depth " << r.overlaps[0].max_depth;
  EXPECT_TRUE(r.gaps.empty());
  o.tie_tolerance_rel = 0;  // unsnapped, the slivers do appear: the test above can fail
  const GqaResult raw = run_gqa(w->accel, o);
  EXPECT_FALSE(raw.overlaps.empty() && raw.gaps.empty());
  for (const GqaQuantities& q : r.solids) EXPECT_NEAR(q.volume, 1.0, 0.05) << q.name;
}

TEST(Gqa, NestedBoxesOverlapByTheInnerBox) {
  auto w = make_world({gen::box({0, 0, 0}, {3, 3, 3}, "outer"), gen::box({1, 1, 1}, {2, 2, 2}, "inner")});
  GqaOptions o;
  o.start_n = 12;  // cells aligned with the inner box: no aliasing, exact volumes
  const GqaResult r = run_gqa(w->accel, o);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.solids[0].volume, 27.0, 27 * kTol);
  EXPECT_NEAR(r.solids[1].volume, 1.0, kTol);
  ASSERT_EQ(r.overlaps.size(), 1u);
  EXPECT_EQ(r.overlaps[0].a, 0u);
  EXPECT_EQ(r.overlaps[0].b, 1u);
  EXPECT_NEAR(r.overlaps[0].max_depth, 1.0, kFloat);
  EXPECT_NEAR(r.overlaps[0].volume, 1.0, kTol);
  EXPECT_NEAR(r.overlaps[0].at.x, 1.0, kFloat);  // first deepest interval: an x ray entering at x=1
  EXPECT_TRUE(r.gaps.empty());
}

TEST(Gqa, InterpenetratingBoxesReportPairDepthAndVolume) {
  // a = [0,1]^3, b = [0.75,1.75] x [0,1] x [0,1]: they share 0.25 x 1 x 1.
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.75, 0, 0}, {1.75, 1, 1}, "b"),
                       gen::box({5, 0, 0}, {6, 1, 1}, "far")});
  const GqaResult r = gqa(*w);
  ASSERT_EQ(r.overlaps.size(), 1u);
  const GqaPair& p = r.overlaps[0];
  EXPECT_EQ(p.a, 0u);
  EXPECT_EQ(p.b, 1u);
  EXPECT_NEAR(p.max_depth, 1.0, kFloat);  // rays along y and z run 1 unit inside both
  EXPECT_NEAR(p.axis_max_depth[0], 0.25, kFloat);
  EXPECT_NEAR(p.penetration, 0.25, kFloat);
  EXPECT_NEAR(p.volume, 0.25, 0.25 * kTol);
  EXPECT_GE(p.at.x, 0.75 - kFloat);
  EXPECT_LE(p.at.x, 1.0 + kFloat);
  // The gap between b and far: 3.25 along x.
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].a, 1u);
  EXPECT_EQ(r.gaps[0].b, 2u);
  EXPECT_NEAR(r.gaps[0].max_depth, 3.25, kFloat);
  EXPECT_NEAR(r.gaps[0].at.x, 1.75, kFloat);
}

TEST(Gqa, GapLimitsFilterGaps) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1.01, 0, 0}, {2, 1, 1}, "b"),
                       gen::box({3, 0, 0}, {4, 1, 1}, "c")});
  GqaOptions o;
  o.gap_max = 0.1;
  o.max_n = 64;  // not about convergence
  const GqaResult r = run_gqa(w->accel, o);
  ASSERT_EQ(r.gaps.size(), 1u);
  EXPECT_EQ(r.gaps[0].a, 0u);
  EXPECT_EQ(r.gaps[0].b, 1u);
  EXPECT_NEAR(r.gaps[0].max_depth, 0.01, kFloat);
}

TEST(Gqa, CsgRegionsOfSpheresAndBoxesConvergeToExactVolumes) {
  // ball: tessellated sphere symmetric about z = 0; lid: the box above z = 0 containing the upper
  // half of the ball; crate: a box containing the whole ball (it sets the bounds [-2, 2]^3); two
  // overlapping boxes p and q. Every box face lies on a cell boundary of the 16, 32, ... grids, so
  // the boxes add no aliasing error and what is left is the spheres' tessellated surface.
  const gen::Mesh ball = csgtest::sphere(1.0, {0, 0, 0}, "ball", 3);
  const gen::Mesh lid = gen::box({-2, -2, 0}, {2, 2, 2}, "lid");
  const gen::Mesh crate = gen::box({-2, -2, -2}, {2, 2, 2}, "crate");
  const gen::Mesh p = gen::box({-1.5, -1.5, -1.5}, {-0.5, -0.5, -0.5}, "p");
  const gen::Mesh q = gen::box({-1, -1, -1.25}, {0, 0, -0.5}, "q");
  auto w = make_world({ball, lid, crate, p, q});
  const double vb = mesh_volume(ball), vl = mesh_volume(lid), vc = mesh_volume(crate);
  GqaOptions o;
  o.tolerance = kTol;
  o.start_n = 16;
  for (const char* e : {"intersection(ball, lid)", "difference(ball, lid)", "union(ball, lid)",
                        "difference(crate, ball)", "union(p, q)", "intersection(p, q)",
                        "difference(union(p, q), intersection(p, q))"})
    o.regions.push_back(parse_csg(e, w->scene));
  const GqaResult r = run_gqa(w->accel, o);
  ASSERT_TRUE(r.converged);
  ASSERT_EQ(r.regions.size(), 7u);
  expect_within_tolerance(r.regions[0].volume, vb / 2, kTol, r.regions[0].name);
  expect_within_tolerance(r.regions[1].volume, vb / 2, kTol, r.regions[1].name);
  expect_within_tolerance(r.regions[2].volume, vl + vb / 2, kTol, r.regions[2].name);
  expect_within_tolerance(r.regions[3].volume, vc - vb, kTol, r.regions[3].name);
  const double vpq = 0.5 * 0.5 * 0.75;
  expect_within_tolerance(r.regions[4].volume, 1.0 + 0.75 - vpq, kTol, r.regions[4].name);
  expect_within_tolerance(r.regions[5].volume, vpq, kTol, r.regions[5].name);
  expect_within_tolerance(r.regions[6].volume, 1.0 + 0.75 - 2 * vpq, kTol, r.regions[6].name);
  // The lower half's centroid lies below the centre on the z axis (3/8 of the radius for a ball).
  EXPECT_NEAR(r.regions[1].centroid.z, -0.375, 0.01);
  EXPECT_NEAR(r.regions[1].centroid.x, 0.0, kTol * w->scene.scale());
  EXPECT_EQ(r.regions[0].geoms, (std::vector<std::uint32_t>{0, 1}));
}

TEST(Gqa, ResultDoesNotDependOnTheKernel) {
  auto w = make_world({csgtest::sphere(1.0, {0, 0, 0}, "ball", 2), gen::box({0, 0, 0}, {1, 1, 1}, "box")});
  GqaOptions o;
  o.start_n = 16;
  o.max_n = 32;
  const GqaResult a = run_gqa(w->accel, o);
  o.kernel = KernelKind::embree_filter;
  const GqaResult b = run_gqa(w->accel, o);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(a.solids[i].volume, b.solids[i].volume);
  ASSERT_EQ(a.overlaps.size(), 1u);
  ASSERT_EQ(b.overlaps.size(), 1u);
  EXPECT_EQ(a.overlaps[0].max_depth, b.overlaps[0].max_depth);
}

TEST(Gqa, CancelStopsEarly) {
  auto w = make_world({csgtest::sphere(1.0, {0, 0, 0}, "ball", 2)});
  GqaOptions o;
  o.tolerance = 1e-9;
  int calls = 0;
  const GqaResult r = run_gqa(w->accel, o, [&](int, std::size_t, std::size_t) { return ++calls < 3; });
  EXPECT_FALSE(r.completed);
  EXPECT_FALSE(r.converged);
}

TEST(Gqa, RejectsBadOptions) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a")});
  GqaOptions o;
  o.tolerance = 0;
  EXPECT_THROW(run_gqa(w->accel, o), std::invalid_argument);
  o.tolerance = 1e-3;
  o.kernel = KernelKind::epsilon;
  EXPECT_THROW(run_gqa(w->accel, o), std::invalid_argument);
}

}  // namespace
}  // namespace pierce::analysis
