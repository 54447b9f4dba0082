// Coplanar-overlap search, Gribble's statistic, interference along rays, per-triangle arrays.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis_scenes.h"
#include "pierce/analysis/overlaps.h"

namespace pierce::test {
namespace {

using namespace pierce::analysis;

RayOverlapReport ray_report(const World& w, int n = 32) {
  return analyse_ray_overlaps(w.accel, axis_grid_rays(w.scene.bounds(), n));
}

TEST(Interference, BoxesInterpenetratingByAKnownDepth) {
  // b reaches 0.2 into a along x and lies inside a's y, z range.
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.8, 0.1, 0.1}, {1.8, 0.9, 0.9}, "b")});
  const RayOverlapReport r = ray_report(*w);
  ASSERT_TRUE(r.completed);
  ASSERT_EQ(r.interferences.size(), 1u);
  const InterferencePair& p = r.interferences[0];
  EXPECT_EQ(p.a, 0u);
  EXPECT_EQ(p.b, 1u);
  EXPECT_NEAR(p.axis_max_depth[0], 0.2, 1e-6);
  EXPECT_NEAR(p.axis_max_depth[1], 0.8, 1e-6);
  EXPECT_NEAR(p.axis_max_depth[2], 0.8, 1e-6);
  EXPECT_NEAR(p.penetration, 0.2, 1e-6);
  EXPECT_NEAR(p.max_depth, 0.8, 1e-6);
  EXPECT_TRUE(r.contacts.empty());
  // Every interval lies in the overlap box, from entry to exit.
  ASSERT_FALSE(r.intervals.empty());
  for (const Interference& iv : r.intervals) {
    EXPECT_GE(iv.entry.x, 0.8 - 1e-6);
    EXPECT_LE(iv.exit.x, 1.0 + 1e-6);
    EXPECT_NEAR(iv.depth, length(iv.exit - iv.entry), 1e-9);
  }
  EXPECT_EQ(p.count, r.intervals.size());
  EXPECT_EQ(r.rays_ending_inside, 0u);
  // No coplanar faces: the coplanar search finds nothing either.
  EXPECT_TRUE(find_coplanar_overlaps(w->scene).pairs.empty());
}

TEST(Interference, TessellatedSpheresOverlapByTheirLens) {
  // Unit spheres 1.5 apart overlap by 0.5 along the line of centres (x).
  auto w = make_world({icosphere(4, 1.0, {0, 0, 0}), icosphere(4, 1.0, {1.5, 0, 0})});
  const RayOverlapReport r = ray_report(*w, 64);
  ASSERT_EQ(r.interferences.size(), 1u);
  const InterferencePair& p = r.interferences[0];
  // Tessellation (facets up to e^2/8 inside the sphere) and the grid's offset from the axis.
  EXPECT_NEAR(p.axis_max_depth[0], 0.5, 0.02);
  EXPECT_NEAR(p.penetration, 0.5, 0.02);
  EXPECT_GT(p.axis_max_depth[1], 1.2);  // the lens is 2 sqrt(1 - 0.75^2) = 1.32 across
}

TEST(Interference, TouchingBoxesAreContactsNotOverlaps) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "b")});
  for (KernelKind k : {KernelKind::queue, KernelKind::embree_restart, KernelKind::restart}) {
    RayOverlapOptions o;
    o.kernel = k;
    const RayOverlapReport r = analyse_ray_overlaps(w->accel, axis_grid_rays(w->scene.bounds(), 32), o);
    EXPECT_TRUE(r.interferences.empty()) << kernel_name(k);
    ASSERT_EQ(r.contacts.size(), 1u);
    EXPECT_EQ(r.contacts[0].a, 0u);
    EXPECT_EQ(r.contacts[0].b, 1u);
    // Every x ray through the shared face's interior crosses from a into b there once.
    const auto rays = axis_grid_rays(w->scene.bounds(), 32);
    std::size_t through = 0;
    for (const Ray& ray : rays)
      through += ray.dir.x != 0 && ray.org.y > 0 && ray.org.y < 1 && ray.org.z > 0 && ray.org.z < 1;
    EXPECT_GT(through, 0u);
    EXPECT_EQ(r.contacts[0].count, through);
    EXPECT_NEAR(r.contacts[0].where.x, 1.0, 1e-6);
  }
  const CoplanarReport c = find_coplanar_overlaps(w->scene);
  ASSERT_EQ(c.solid_pairs.size(), 1u);
  const CoplanarSolidPair& sp = c.solid_pairs[0];
  EXPECT_EQ(sp.a, 0u);
  EXPECT_EQ(sp.b, 1u);
  EXPECT_EQ(sp.opposite_facing, sp.pairs);
  EXPECT_EQ(sp.exact_pairs, sp.pairs);
  EXPECT_NEAR(sp.area, 1.0, 1e-12);
  EXPECT_NEAR(sp.where.x, 1.0, 1e-12);
}

TEST(Interference, StackedPlatesTouchAlongTheStack) {
  auto w = make_world(gen::stacked_plates(4, 1.0, 0.25));
  const RayOverlapReport r = ray_report(*w, 16);
  EXPECT_TRUE(r.interferences.empty());
  ASSERT_EQ(r.contacts.size(), 3u);  // plates 0-1, 1-2, 2-3
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(r.contacts[i].a, i);
    EXPECT_EQ(r.contacts[i].b, i + 1);
  }
  // z rays through the plates' interior cross every shared face; x and y rays none.
  const auto rays = axis_grid_rays(w->scene.bounds(), 16);
  std::size_t z_through = 0, hitting = 0;
  for (const Ray& ray : rays) {
    const bool inside_xy = ray.org.x > 0 && ray.org.x < 1 && ray.org.y > 0 && ray.org.y < 1;
    const bool inside_yz = ray.org.y > 0 && ray.org.y < 1 && ray.org.z > 0 && ray.org.z < 1;
    const bool inside_zx = ray.org.z > 0 && ray.org.z < 1 && ray.org.x > 0 && ray.org.x < 1;
    if (ray.dir.z != 0) z_through += inside_xy, hitting += inside_xy;
    if (ray.dir.x != 0) hitting += inside_yz;
    if (ray.dir.y != 0) hitting += inside_zx;
  }
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(r.contacts[i].count, z_through);
  // Gribble's statistic: every z ray meets equal-t pairs; x and y rays meet none.
  EXPECT_EQ(r.coplanar.rays, rays.size());
  EXPECT_EQ(r.coplanar.rays_hitting, hitting);
  EXPECT_EQ(r.coplanar.rays_equal_t, z_through);
  EXPECT_EQ(r.coplanar.rays_within_eps, z_through);
  EXPECT_NEAR(r.coplanar.share_equal(), double(z_through) / double(hitting), 1e-12);
}

TEST(GribbleStatistic, NearlyCoplanarFacesCountOnlyWithinEpsilon) {
  // A gap of 1e-7 between two boxes: not equal t, but within epsilon (1e-5 of the diagonal).
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({1 + 1e-7, 0, 0}, {2, 1, 1})});
  const int axes[] = {0};
  const RayOverlapReport r = analyse_ray_overlaps(w->accel, axis_grid_rays(w->scene.bounds(), 8, axes));
  EXPECT_GT(r.coplanar.rays_hitting, 0u);
  EXPECT_EQ(r.coplanar.rays_equal_t, 0u);
  EXPECT_EQ(r.coplanar.rays_within_eps, r.coplanar.rays_hitting);
  // A separate box far away: neither.
  auto lone = make_world({gen::box({0, 0, 0}, {1, 1, 1})});
  const RayOverlapReport q = ray_report(*lone, 8);
  EXPECT_GT(q.coplanar.rays_hitting, 0u);
  EXPECT_EQ(q.coplanar.rays_within_eps, 0u);
  EXPECT_EQ(q.coplanar.rays_equal_t, 0u);
}

TEST(Interference, DuplicatedFacesInsideOneSolidAreNotOverlaps) {
  const gen::Mesh b = gen::box({0, 0, 0}, {1, 1, 1});
  for (bool alternate : {false, true}) {
    auto w = make_world({gen::duplicated(b, 2, alternate), gen::box({3, 0, 0}, {4, 1, 1})});
    const RayOverlapReport r = ray_report(*w, 8);
    EXPECT_TRUE(r.interferences.empty());
    EXPECT_TRUE(r.contacts.empty());
    EXPECT_EQ(r.rays_ending_inside, 0u);
    EXPECT_GT(r.coplanar.rays_equal_t, 0u);
  }
}

TEST(Interference, IdenticalSolidsOverlapCompletely) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 2, 3}), gen::box({0, 0, 0}, {1, 2, 3})});
  const RayOverlapReport r = ray_report(*w, 8);
  ASSERT_EQ(r.interferences.size(), 1u);
  EXPECT_NEAR(r.interferences[0].axis_max_depth[0], 1.0, 1e-6);
  EXPECT_NEAR(r.interferences[0].axis_max_depth[2], 3.0, 1e-6);
  EXPECT_NEAR(r.interferences[0].penetration, 1.0, 1e-6);
  EXPECT_TRUE(r.contacts.empty());
  // Coplanar: every face pair, same facing.
  const CoplanarReport c = find_coplanar_overlaps(w->scene);
  ASSERT_EQ(c.solid_pairs.size(), 1u);
  EXPECT_EQ(c.solid_pairs[0].same_facing, c.solid_pairs[0].pairs);
  EXPECT_NEAR(c.solid_pairs[0].area, 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-9);
}

TEST(Coplanar, PartialContactArea) {
  // b's -x face covers a quarter of a's +x face.
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({1, 0.5, 0.5}, {2, 1.5, 1.5})});
  const CoplanarReport c = find_coplanar_overlaps(w->scene);
  ASSERT_EQ(c.solid_pairs.size(), 1u);
  EXPECT_NEAR(c.solid_pairs[0].area, 0.25, 1e-12);
  EXPECT_EQ(c.solid_pairs[0].opposite_facing, c.solid_pairs[0].pairs);
  for (const CoplanarPair& p : c.pairs) {
    EXPECT_TRUE(p.exact);
    EXPECT_GT(p.area, 0);
  }
}

TEST(Coplanar, ToleranceFindsNearlyCoplanarFaces) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({1 + 1e-7, 0, 0}, {2, 1, 1})});
  EXPECT_TRUE(find_coplanar_overlaps(w->scene).pairs.empty());
  CoplanarOptions o;
  o.tolerance = 1e-6;
  const CoplanarReport c = find_coplanar_overlaps(w->scene, o);
  ASSERT_EQ(c.solid_pairs.size(), 1u);
  EXPECT_EQ(c.solid_pairs[0].exact_pairs, 0u);
  EXPECT_NEAR(c.solid_pairs[0].area, 1.0, 1e-6);
  o.tolerance = 1e-8;
  EXPECT_TRUE(find_coplanar_overlaps(w->scene, o).pairs.empty());
  o.tolerance = -1;
  EXPECT_THROW(find_coplanar_overlaps(w->scene, o), std::invalid_argument);
}

TEST(Coplanar, DuplicatedFaceAndTriangleArrays) {
  gen::Mesh b = gen::box({0, 0, 0}, {1, 1, 1});
  b.triangles.push_back(b.triangles[10]);  // +z face, first triangle, again
  auto w = make_world({b, gen::box({1, 0, 0}, {2, 1, 1})});
  const CoplanarReport c = find_coplanar_overlaps(w->scene);
  ASSERT_EQ(c.solid_pairs.size(), 2u);
  EXPECT_EQ(c.solid_pairs[0].a, 0u);
  EXPECT_EQ(c.solid_pairs[0].b, 0u);
  EXPECT_EQ(c.solid_pairs[0].pairs, 1u);
  EXPECT_EQ(c.solid_pairs[0].same_facing, 1u);
  EXPECT_NEAR(c.solid_pairs[0].area, 0.5, 1e-12);
  // Adjacent coplanar triangles of one face share only an edge: not reported.
  const TriangleOverlapArrays a = triangle_overlap_arrays(w->scene, &c, nullptr);
  ASSERT_EQ(a.size(), 25u);
  EXPECT_EQ(a.coplanar_count[10], 1u);
  EXPECT_EQ(a.coplanar_count[12], 1u);
  EXPECT_EQ(a.coplanar_partner[10], 0);
  EXPECT_EQ(a.coplanar_count[11], 0u);
  EXPECT_EQ(a.coplanar_partner[11], -1);
  // +x face of solid 0 (triangles 2, 3) touches solid 1's -x face (triangles 13 + 0, 1).
  EXPECT_GT(a.coplanar_count[2], 0u);
  EXPECT_EQ(a.coplanar_partner[2], 1);
  EXPECT_EQ(a.coplanar_partner[13], 0);
  EXPECT_EQ(a.solid[13], 1u);
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a.overlap_count[i], a.coplanar_count[i]);
}

TEST(TriangleArrays, InterferenceHitsMarkTheClashingFaces) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({0.8, 0.1, 0.1}, {1.8, 0.9, 0.9})});
  const RayOverlapReport r = ray_report(*w, 16);
  const TriangleOverlapArrays a = triangle_overlap_arrays(w->scene, nullptr, &r);
  // a's +x face (2, 3) closes the overlap on x rays; b's -x face (12 + 0, 1) opens it. a's -x
  // face (0, 1) is never part of the overlap.
  EXPECT_GT(a.interference_hits[2] + a.interference_hits[3], 0u);
  EXPECT_GT(a.interference_hits[12] + a.interference_hits[13], 0u);
  EXPECT_EQ(a.interference_hits[0] + a.interference_hits[1], 0u);
  EXPECT_EQ(a.overlap_count[2], a.interference_hits[2]);
}

TEST(RayOverlaps, CancelAndBadOptions) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1})});
  const auto rays = axis_grid_rays(w->scene.bounds(), 64);
  const RayOverlapReport r =
      analyse_ray_overlaps(w->accel, rays, {}, [](std::size_t, std::size_t) { return false; });
  EXPECT_FALSE(r.completed);
  RayOverlapOptions o;
  o.kernel = KernelKind::epsilon;
  EXPECT_THROW(analyse_ray_overlaps(w->accel, rays, o), std::invalid_argument);
}

}  // namespace
}  // namespace pierce::test
