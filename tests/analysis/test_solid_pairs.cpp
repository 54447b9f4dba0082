// Contact, clash and clearance between solids, and the triangle-triangle distance under them.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "analysis_scenes.h"
#include "pierce/analysis/solid_pairs.h"

namespace pierce::test {
namespace {

using namespace pierce::analysis;

SolidPairReport pairs_of(const World& w, double clearance, int grid_n = 64, bool triangle_clearance = true) {
  SolidPairOptions o;
  o.clearance = clearance;
  o.grid_n = grid_n;
  o.triangle_clearance = triangle_clearance;
  return analyse_solid_pairs(w.accel, o);
}

// The same pairs, kinds and, for clearance, the same gaps and points bit for bit.
void expect_same_pairs(const SolidPairReport& a, const SolidPairReport& b) {
  ASSERT_EQ(a.pairs.size(), b.pairs.size());
  for (std::size_t k = 0; k < a.pairs.size(); ++k) {
    const SolidPair &x = a.pairs[k], &y = b.pairs[k];
    EXPECT_EQ(std::tie(x.solid_a, x.solid_b, x.kind), std::tie(y.solid_a, y.solid_b, y.kind)) << k;
    if (x.kind == PairKind::clearance) {
      EXPECT_TRUE(x.gap == y.gap && x.point == y.point && x.point_b == y.point_b) << k;
    }
  }
}

TEST(TriangleDistance, ParallelCrossingAndEdgeToEdge) {
  const Vec3d a[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  // Parallel, 0.25 above a's corner region: the corner (0, 0, 0) is nearest.
  const Vec3d above[3] = {{0, 0, 0.25}, {1, 0, 0.25}, {0, 1, 0.25}};
  const TrianglePairDistance p = triangle_distance(a, above);
  EXPECT_EQ(p.dist2, 0.0625);
  EXPECT_EQ(p.on_a.z, 0.0);
  EXPECT_EQ(p.on_b.z, 0.25);
  // Piercing a's interior: distance 0 at the crossing point.
  const Vec3d pierce[3] = {{0.2, 0.2, -1}, {0.2, 0.2, 1}, {0.3, 0.2, 1}};
  const TrianglePairDistance c = triangle_distance(a, pierce);
  EXPECT_EQ(c.dist2, 0.0);
  EXPECT_NEAR(c.on_a.x, 0.2, 1e-15);
  EXPECT_NEAR(c.on_a.z, 0.0, 1e-15);
  // Skew: b stands in the plane x = 0.5 from z = 2 up, its lowest edge crossing over a: the
  // nearest points are 2 apart, on a's line x = 0.5 below that edge (edge-to-edge, not a corner).
  const Vec3d skew[3] = {{0.5, -1, 2}, {0.5, 2, 2}, {0.5, 0.5, 5}};
  const TrianglePairDistance s = triangle_distance(a, skew);
  EXPECT_NEAR(s.dist2, 4.0, 1e-12);
  EXPECT_NEAR(s.on_a.x, 0.5, 1e-12);
  EXPECT_EQ(s.on_a.z, 0.0);
  EXPECT_NEAR(s.on_b.z, 2.0, 1e-12);
}

TEST(SolidPairs, TouchingBlocksAreInContact) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "b")});
  for (double d : {0.0, 0.5}) {
    const SolidPairReport r = pairs_of(*w, d);
    ASSERT_TRUE(r.completed);
    ASSERT_EQ(r.pairs.size(), 1u) << d;
    const SolidPair& p = r.pairs[0];
    EXPECT_EQ(p.kind, PairKind::contact);
    EXPECT_EQ(p.solid_a, 0u);
    EXPECT_EQ(p.solid_b, 1u);
    EXPECT_EQ(p.gap, 0.0);
    EXPECT_TRUE(std::isnan(p.depth));
    EXPECT_NEAR(p.point.x, 1.0, 1e-12);  // on the shared face
  }
}

TEST(SolidPairs, DifferentlyTessellatedSharedFaceIsContact) {
  // a's face x = 1 is 2 triangles, b's a 4 x 4 grid of 32.
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gridded_box({1, 0, 0}, {2, 1, 1}, 4, "b")});
  const SolidPairReport r = pairs_of(*w, 0.1);
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_EQ(r.pairs[0].kind, PairKind::contact);
  EXPECT_EQ(r.pairs[0].gap, 0.0);
  // Every triangle of the shared face, on either side, touches the other solid.
  const Scene& s = w->scene;
  for (std::uint32_t g = 0; g < 2; ++g)
    for (std::uint32_t t = 0; t < s.geometry(g).triangles.size(); ++t) {
      bool on_face = true;
      for (auto v : s.geometry(g).triangles[t]) on_face = on_face && s.geometry(g).vertices[v].x == 1.0;
      if (on_face) {
        EXPECT_EQ(r.triangle_clearance[r.tri_offset[g] + t], 0.0) << g << " " << t;
      }
    }
}

TEST(SolidPairs, GapBelowTheClearanceIsMeasuredExactly) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1.3, 0, 0}, {2.3, 1, 1}, "b")});
  const SolidPairReport r = pairs_of(*w, 0.5);
  ASSERT_EQ(r.pairs.size(), 1u);
  const SolidPair& p = r.pairs[0];
  EXPECT_EQ(p.kind, PairKind::clearance);
  EXPECT_NEAR(p.gap, 0.3, 1e-9);
  // Both closest points on the facing faces, facing each other.
  EXPECT_EQ(p.point.x, 1.0);
  EXPECT_EQ(p.point_b.x, 1.3);
  EXPECT_EQ(p.point.y, p.point_b.y);
  EXPECT_EQ(p.point.z, p.point_b.z);
  for (double c : {p.point.y, p.point.z}) {
    EXPECT_GE(c, 0.0);
    EXPECT_LE(c, 1.0);
  }
  // Per triangle: 0.3 where a triangle reaches x = 1 (the facing face and the sides' edges),
  // capped at 0.5 on a's far face x = 0.
  const Geometry& a = w->scene.geometry(0);
  for (std::uint32_t t = 0; t < a.triangles.size(); ++t) {
    double xmax = 0;
    for (auto v : a.triangles[t]) xmax = std::max(xmax, a.vertices[v].x);
    EXPECT_NEAR(r.triangle_clearance[t], xmax == 1.0 ? 0.3 : 0.5, 1e-9) << t;
  }
  // Not below a clearance of 0.3 or less, nor at 0.
  EXPECT_TRUE(pairs_of(*w, 0.3).pairs.empty());
  EXPECT_TRUE(pairs_of(*w, 0.0).pairs.empty());
  EXPECT_EQ(pairs_of(*w, 0.30001).pairs.size(), 1u);
}

TEST(SolidPairs, SlabInterpenetrationIsAClashOfKnownDepth) {
  // b reaches 0.5 into a along x over a's whole 10 x 10 face: the overlap is a 0.5 x 10 x 10 slab.
  auto w = make_world({gen::box({0, 0, 0}, {10, 10, 10}, "a"), gen::box({9.5, -1, -1}, {19.5, 11, 11}, "b")});
  const SolidPairReport r = pairs_of(*w, 0.0);
  ASSERT_EQ(r.pairs.size(), 1u);
  const SolidPair& p = r.pairs[0];
  EXPECT_EQ(p.kind, PairKind::clash);
  EXPECT_NEAR(p.depth, 0.5, 0.005);
  EXPECT_NEAR(p.overlap_length, 10.0, 1e-6);
  EXPECT_TRUE(std::isnan(p.gap));
  // The depth interval runs along x through the slab.
  EXPECT_NEAR(p.point.x, 9.5, 1e-6);  // crossings in float
  EXPECT_NEAR(p.point_b.x, 10.0, 1e-6);
  EXPECT_EQ(p.point.y, p.point_b.y);
  // Volume 50: the x rays measure 0.5 each; their 64 x 64 cells (0.19 wide) cover the 10 x 10
  // cross-section to within a cell at each edge.
  EXPECT_NEAR(p.volume, 50.0, 0.5 * 4 * 10 * 0.2);
}

TEST(SolidPairs, AssemblyReportsEachPairOnceInOrder) {
  // a-b touch, b-c clash by 0.2 in x, c-d 0.25 apart, e 1 from d; a-c 0.8 apart, b-d 1.05.
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "b"),
                       gen::box({1.8, 0.2, 0.2}, {2.8, 0.8, 0.8}, "c"), gen::box({3.05, 0, 0}, {4, 1, 1}, "d"),
                       gen::box({5, 0, 0}, {6, 1, 1}, "e")});
  const SolidPairReport r = pairs_of(*w, 0.5);
  ASSERT_EQ(r.pairs.size(), 3u);
  EXPECT_EQ(r.pairs[0].kind, PairKind::clash);
  EXPECT_EQ(r.pairs[0].solid_a, 1u);
  EXPECT_EQ(r.pairs[0].solid_b, 2u);
  EXPECT_NEAR(r.pairs[0].depth, 0.2, 0.002);
  EXPECT_EQ(r.pairs[1].kind, PairKind::contact);
  EXPECT_EQ(r.pairs[1].solid_a, 0u);
  EXPECT_EQ(r.pairs[1].solid_b, 1u);
  EXPECT_EQ(r.pairs[2].kind, PairKind::clearance);
  EXPECT_EQ(r.pairs[2].solid_a, 2u);
  EXPECT_EQ(r.pairs[2].solid_b, 3u);
  EXPECT_NEAR(r.pairs[2].gap, 0.25, 1e-9);
  // At D = 0 the clearance goes, contact and clash stay; e's triangles stay at D everywhere.
  const SolidPairReport r0 = pairs_of(*w, 0.0);
  ASSERT_EQ(r0.pairs.size(), 2u);
  EXPECT_EQ(r0.pairs[0].kind, PairKind::clash);
  EXPECT_EQ(r0.pairs[1].kind, PairKind::contact);
  for (std::size_t i = r.tri_offset[4]; i < r.tri_offset[5]; ++i) EXPECT_EQ(r.triangle_clearance[i], 0.5);
}

// Bumpy blobs close enough to clash or pass within the clearance: every triangle's clearance and
// every clearance pair's gap are the minima over all triangle pairs of two solids, checked by
// measuring them all; the report is the same on one thread and on all, and its pairs the same
// without the map.
TEST(SolidPairs, ClearanceIsTheMinimumOverAllTrianglePairs) {
  constexpr double kClearance = 0.3;
  std::vector<gen::Mesh> solids;
  for (int i = 0; i < 4; ++i) solids.push_back(gen::translated(gen::blob(2, std::uint64_t(3 + i)), {2.1 * (i % 2), 2.1 * (i / 2), 0}));
  solids.push_back(gen::box({-1.2, -1.2, -1.6}, {3.3, 3.3, -1.2}, "floor"));
  auto w = make_world(solids);
  const Scene& scene = w->scene;
  const SolidPairReport all_threads = pairs_of(*w, kClearance);
  SolidPairReport one_thread;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = pairs_of(*w, kClearance);
  }
  expect_same_pairs(all_threads, one_thread);
  EXPECT_EQ(all_threads.triangle_clearance, one_thread.triangle_clearance);
  const SolidPairReport without_map = pairs_of(*w, kClearance, 64, false);
  EXPECT_TRUE(without_map.triangle_clearance.empty());
  expect_same_pairs(all_threads, without_map);

  // Brute force: the least distance from each triangle to each other solid.
  const std::size_t solid_count = scene.geometries().size();
  std::vector<std::vector<double>> least(all_threads.tri_offset.back(), std::vector<double>(solid_count, INFINITY));
  for (std::uint32_t g = 0; g < solid_count; ++g)
    for (std::uint32_t h = 0; h < solid_count; ++h) {
      if (g == h) continue;
      const Geometry &ga = scene.geometry(g), &gb = scene.geometry(h);
      for (std::size_t i = 0; i < ga.triangles.size(); ++i) {
        const Vec3d a[3] = {ga.vertices[ga.triangles[i][0]], ga.vertices[ga.triangles[i][1]], ga.vertices[ga.triangles[i][2]]};
        double& out = least[all_threads.tri_offset[g] + i][h];
        for (const Tri& t : gb.triangles) {
          const Vec3d b[3] = {gb.vertices[t[0]], gb.vertices[t[1]], gb.vertices[t[2]]};
          out = std::min(out, triangle_distance(a, b).dist2);
        }
      }
    }
  std::size_t near_triangles = 0;
  for (std::size_t i = 0; i < least.size(); ++i) {
    const double nearest = std::sqrt(*std::min_element(least[i].begin(), least[i].end()));
    // Contact and clash set a triangle's clearance to 0 where the rays or faces show it; elsewhere
    // it is the exact distance, capped.
    if (all_threads.triangle_clearance[i] == 0 && nearest < kClearance) continue;
    EXPECT_EQ(all_threads.triangle_clearance[i], std::min(nearest, kClearance)) << i;
    near_triangles += nearest < kClearance;
  }
  EXPECT_GT(near_triangles, 50u);
  std::size_t clearance_pairs = 0;
  for (const SolidPair& p : all_threads.pairs) {
    if (p.kind != PairKind::clearance) continue;
    ++clearance_pairs;
    double gap2 = INFINITY;
    for (std::size_t i = all_threads.tri_offset[p.solid_a]; i < all_threads.tri_offset[p.solid_a + 1]; ++i)
      gap2 = std::min(gap2, least[i][p.solid_b]);
    EXPECT_EQ(p.gap, std::sqrt(gap2)) << p.solid_a << "-" << p.solid_b;
    EXPECT_NEAR(length(p.point - p.point_b), p.gap, 1e-12);
  }
  EXPECT_GT(clearance_pairs, 0u);
  // Every pair within the clearance is reported, whatever its kind.
  for (std::uint32_t g = 0; g < solid_count; ++g)
    for (std::uint32_t h = g + 1; h < solid_count; ++h) {
      double gap2 = INFINITY;
      for (std::size_t i = all_threads.tri_offset[g]; i < all_threads.tri_offset[g + 1]; ++i) gap2 = std::min(gap2, least[i][h]);
      const bool reported = std::any_of(all_threads.pairs.begin(), all_threads.pairs.end(),
                                        [&](const SolidPair& p) { return p.solid_a == g && p.solid_b == h; });
      EXPECT_EQ(reported, std::sqrt(gap2) < kClearance) << g << "-" << h;
    }
}

// a's triangles within the clearance of b all lie nearer to c, a lid over both: the a-b pair is
// still measured and reported (0.2 apart), as are a-c and b-c (0.1).
TEST(SolidPairs, PairBehindANearerSolidIsReported) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1.2, 0, 0.5}, {2, 1, 1}, "b"),
                       gen::box({-0.5, -0.5, 1.1}, {2.5, 1.5, 1.5}, "c")});
  for (const bool triangle_clearance : {true, false}) {
    const SolidPairReport r = pairs_of(*w, 0.3, 64, triangle_clearance);
    ASSERT_EQ(r.pairs.size(), 3u);
    for (const SolidPair& p : r.pairs) EXPECT_EQ(p.kind, PairKind::clearance);
    EXPECT_EQ(r.pairs[2].solid_a, 0u);
    EXPECT_EQ(r.pairs[2].solid_b, 1u);
    EXPECT_NEAR(r.pairs[2].gap, 0.2, 1e-12);
    EXPECT_NEAR(r.pairs[0].gap, 0.1, 1e-12);
    EXPECT_NEAR(r.pairs[1].gap, 0.1, 1e-12);
  }
}

TEST(SolidPairs, BadOptionsThrow) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a")});
  SolidPairOptions o;
  o.clearance = -1;
  EXPECT_THROW(analyse_solid_pairs(w->accel, o), std::invalid_argument);
  o.clearance = std::nan("");
  EXPECT_THROW(analyse_solid_pairs(w->accel, o), std::invalid_argument);
  o.clearance = 0;
  o.grid_n = 0;
  EXPECT_THROW(analyse_solid_pairs(w->accel, o), std::invalid_argument);
}

}  // namespace
}  // namespace pierce::test
