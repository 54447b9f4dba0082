// Closest-point queries on the double BVH: the answer does not depend on the
// BVH's layout.
#include <gtest/gtest.h>

#include <random>

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
  std::vector<std::uint32_t> stack;
  for (const bool embree_builder : {true, false}) {
    BvhBuildOptions opts;
    opts.embree_builder = embree_builder;
    opts.max_leaf_size = 2;
    const Bvhd bvh = build_bvh<double>(scene, opts);
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

}  // namespace
}  // namespace pierce::test
