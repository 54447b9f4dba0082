// Proximity queries on the double wide BVH (run on the one traversal): the answer does not depend
// on the BVH's layout, and is what a brute-force search over every triangle gives.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>

#include "pierce/analysis/bvh_query.h"
#include "pierce/bvh_builder.h"
#include "pierce/scene.h"

namespace pierce::test {
namespace {

using namespace pierce::analysis;

// Many copies of one triangle, scattered among other triangles so that both builders put them in
// different leaves: every copy is equally near, and the lowest prim must give the point.
TEST(ClosestPoint, EquallyNearTrianglesGiveTheLowestPrim) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  std::vector<Vec3d> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<Tri> tris;
  std::vector<std::uint32_t> copies;
  for (std::uint32_t i = 0; i < 400; ++i) {
    if (i % 7 == 3) {
      copies.push_back(std::uint32_t(tris.size()));
      tris.push_back({0, 1, 2});
      continue;
    }
    // Small triangles far from the query points (|z| >= 5).
    const Vec3d c{u(rng), u(rng), (i % 2 ? 1.0 : -1.0) * (5.0 + std::abs(u(rng)))};
    const auto base = std::uint32_t(v.size());
    v.push_back(c), v.push_back(c + Vec3d{0.1, 0, 0}), v.push_back(c + Vec3d{0, 0.1, 0});
    tris.push_back({base, base + 1, base + 2});
  }
  Scene scene;
  scene.add_mesh(v, tris);
  const Vec3d queries[] = {{0.25, 0.25, 1.0}, {0.5, 0.5, 0.0}, {-1.0, -1.0, 0.5}, {2.0, 0.0, -0.5}, {0.3, 0.1, 0.0}};
  NodeStack<double> stack;
  for (const bool float_areas : {true, false}) {
    BvhBuildOptions opts;
    opts.float_areas = float_areas;
    opts.max_leaf_size = 2;
    const WideBvhd bvh = build_wide_bvh<double>(scene, opts);
    for (const Vec3d& q : queries) {
      const ClosestPoint cp = closest_point(bvh, q, std::numeric_limits<double>::infinity(), {}, stack);
      ASSERT_TRUE(cp.found());
      EXPECT_EQ(cp.prim, copies.front()) << q.x << "," << q.y << "," << q.z;
      // Excluding the lowest copy hands the tie to the next one.
      const std::uint32_t first[] = {copies.front()};
      const ClosestPoint next = closest_point(bvh, q, std::numeric_limits<double>::infinity(), first, stack);
      ASSERT_TRUE(next.found());
      EXPECT_EQ(next.prim, copies[1]);
    }
  }
}


// A soup of random triangles in two geometries: closest_point (with and without an exclusion, and
// within a radius) and for_each_overlapping (on the double BVH, and on the float BVH with the
// scene's double corners) give what checking every triangle gives.
TEST(ProximityQueries, MatchBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), s(0.02, 0.3);
  Scene scene;
  std::vector<Triangle<double>> all;
  for (std::uint32_t g = 0; g < 2; ++g) {
    std::vector<Vec3d> v;
    std::vector<Tri> tris;
    for (std::uint32_t i = 0; i < 700; ++i) {
      const Vec3d c{u(rng), u(rng), u(rng)};
      const double r = s(rng);
      const auto base = std::uint32_t(v.size());
      v.push_back(c), v.push_back(c + Vec3d{r * u(rng), r * u(rng), r * u(rng)});
      v.push_back(c + Vec3d{r * u(rng), r * u(rng), r * u(rng)});
      tris.push_back({base, base + 1, base + 2});
      all.push_back({v[base], v[base + 1], v[base + 2], g, i});
    }
    scene.add_mesh(v, tris);
  }
  const WideBvhd bvh = build_wide_bvh<double>(scene);
  ASSERT_EQ(bvh.triangles, all.size());
  const WideBvhf bvh_float = build_wide_bvh<float>(scene);
  NodeStack<double> stack;
  NodeStack<float> stack_float;
  for (int k = 0; k < 300; ++k) {
    const Vec3d q{1.5 * u(rng), 1.5 * u(rng), 1.5 * u(rng)};
    const std::uint32_t skip[] = {std::uint32_t(k % 700)};
    for (const bool excluding : {false, true}) {
      for (const double radius2 : {std::numeric_limits<double>::infinity(), 0.01}) {
        ClosestPoint want;
        want.dist2 = radius2;
        for (const Triangle<double>& t : all) {
          if (excluding && t.prim == skip[0]) continue;
          const Vec3d c = closest_point_on_triangle(q, t.v0, t.v1, t.v2);
          const double d2 = dot(c - q, c - q);
          const bool first_of_tie =
              d2 == want.dist2 && (!want.found() || std::tie(t.geom, t.prim) < std::tie(want.geom, want.prim));
          if (d2 < want.dist2 || first_of_tie) want = {d2, c, t.geom, t.prim};
        }
        const std::span<const std::uint32_t> exclude =
            excluding ? std::span<const std::uint32_t>(skip) : std::span<const std::uint32_t>();
        const ClosestPoint got = closest_point(bvh, q, radius2, exclude, stack);
        ASSERT_EQ(got.found(), want.found()) << k;
        if (!want.found()) continue;
        EXPECT_EQ(got.dist2, want.dist2) << k;
        EXPECT_EQ(got.geom, want.geom) << k;
        EXPECT_EQ(got.prim, want.prim) << k;
        EXPECT_EQ(got.point, want.point) << k;
      }
    }
    // A random box, and a point box on a triangle's highest corner: a closed test touching it.
    BBoxd random_box, corner_box;
    random_box.extend(q), random_box.extend(q + Vec3d{0.2 * s(rng), 0.2 * s(rng), 0.2 * s(rng)});
    const Triangle<double>& touched = all[std::size_t(k) * 7 % all.size()];
    corner_box.extend(vmax(touched.v0, vmax(touched.v1, touched.v2)));
    const BBoxd boxes[] = {random_box, corner_box};
    for (int which = 0; which < 2; ++which) {
      const BBoxd& box = boxes[which];
      std::vector<std::pair<std::uint32_t, std::uint32_t>> want, got, got_float;
      for (const Triangle<double>& t : all) {
        BBoxd tb;
        tb.extend(t.v0), tb.extend(t.v1), tb.extend(t.v2);
        if (boxes_overlap(tb, box)) want.emplace_back(t.geom, t.prim);
      }
      auto collect = [&](std::vector<std::pair<std::uint32_t, std::uint32_t>>& out) {
        return [&](const Triangle<double>& t) {
          const Triangle<double>& input = all[t.geom * 700 + t.prim];
          EXPECT_TRUE(t.v0 == input.v0 && t.v1 == input.v1 && t.v2 == input.v2) << "corners in the input's order";
          out.emplace_back(t.geom, t.prim);
        };
      };
      for_each_overlapping(bvh, box, stack, collect(got));
      for_each_overlapping(scene, bvh_float, box, stack_float, collect(got_float));
      std::sort(want.begin(), want.end());
      std::sort(got.begin(), got.end());
      std::sort(got_float.begin(), got_float.end());
      EXPECT_EQ(got, want) << k;
      EXPECT_EQ(got_float, want) << "float BVH, " << k;
      EXPECT_FALSE(which == 1 && want.empty()) << "the touched triangle is found";
    }
  }
}

}  // namespace
}  // namespace pierce::test
