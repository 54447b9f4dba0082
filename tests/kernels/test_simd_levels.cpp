// Every SIMD level of the wide-BVH traversal computes the same hits, bit for bit, as the scalar
// path: the SIMD node and triangle tests only reject what the scalar arithmetic rejects. Hard rays
// (through vertices and edges, axis-parallel, along shared faces) on touching and duplicated
// faces; every exact kernel, both tie orders. (The whole suite also runs at each level in ctest:
// kernels.simd_scalar, kernels.simd_avx2.)
#include "pierce/simd/simd_level.h"
#include "test_util.h"

namespace pierce::test {
namespace {

// Restores the level in use when a test ends.
struct LevelGuard {
  SimdLevel saved = simd_level();
  ~LevelGuard() { set_simd_level(saved); }
};

// The levels this machine has, scalar first.
std::vector<SimdLevel> levels_here() {
  std::vector<SimdLevel> levels{SimdLevel::scalar};
  if (int(best_simd_level()) >= int(SimdLevel::avx2)) levels.push_back(SimdLevel::avx2);
  if (best_simd_level() == SimdLevel::avx512) levels.push_back(SimdLevel::avx512);
  return levels;
}

TEST(SimdLevels, NamesParseAndClamp) {
  LevelGuard guard;
  for (SimdLevel l : {SimdLevel::scalar, SimdLevel::avx2, SimdLevel::avx512}) {
    EXPECT_EQ(parse_simd_level(simd_level_name(l)), l);
    const SimdLevel set = set_simd_level(l);
    EXPECT_LE(int(set), int(best_simd_level()));
    EXPECT_LE(int(set), int(l));
    EXPECT_EQ(simd_level(), set);
  }
  EXPECT_FALSE(parse_simd_level("sse9"));
  EXPECT_EQ(set_simd_level(SimdLevel::scalar), SimdLevel::scalar);
}

TEST(SimdLevels, IdenticalHitsAtEveryLevel) {
  LevelGuard guard;
  HardCases cases = hard_cases(11);
  const auto& w = cases.world;
  std::vector<Ray>& rays = cases.rays;
  for (int i = 0; i < 100; ++i) {  // axis-parallel, along the plates' shared faces and edges
    const double x = (i % 10) / 9.0, y = (i / 10) / 9.0;
    rays.push_back({{x, y, -1.0}, {0, 0, 1}});
    rays.push_back({{-1.0, x, 0.1 * (i % 7)}, {1, 0, 0}});
  }

  const std::vector<SimdLevel> levels = levels_here();
  for (const TieOrder tie : kTieOrders) {
    for (const KernelKind kind : exact_kernels()) {
      if (uses_embree(kind)) continue;
      std::vector<std::vector<Hit>> want;
      for (const SimdLevel level : levels) {
        ASSERT_EQ(set_simd_level(level), level);
        HitIterator it(w->accel, kind, KernelOptions{HitOrder{tie}});
        for (std::size_t i = 0; i < rays.size(); ++i) {
          const std::vector<Hit> got = kernel_hits(it, rays[i]);
          if (level == SimdLevel::scalar) {
            want.push_back(got);
            continue;
          }
          ASSERT_TRUE(same_hits(want[i], got)) << kernel_name(kind) << " at " << simd_level_name(level) << ", "
                                               << tie_name(tie) << ", ray " << i << " " << str(rays[i]);
        }
      }
    }
  }
}

// The leaf blocks store each triangle's corners in its summation order, but a hit is reported in
// the input's terms. One triangle in each of its six corner orders, stacked along z so that one ray
// meets them all, at every level: u and v weigh the input's corners 1 and 2 (the point they give
// is where the ray is), enter is the facing of the input's winding, ng its normal.
TEST(SimdLevels, HitsAreInTheInputCornerOrder) {
  LevelGuard guard;
  const Vec3d corners[3] = {{0.1, 0.2, 0.0}, {0.9, 0.3, 0.0}, {0.4, 0.8, 0.0}};
  const int orders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  std::vector<gen::Mesh> meshes;
  for (int k = 0; k < 6; ++k) {
    gen::Mesh m{"order" + std::to_string(k), {}, {{0, 1, 2}}};
    for (int i = 0; i < 3; ++i) m.vertices.push_back(corners[orders[k][i]] + Vec3d{0.0, 0.0, 0.25 * k});
    meshes.push_back(m);
  }
  const auto w = make_world(meshes);
  const Vec3d through = corners[0] * 0.2 + corners[1] * 0.3 + corners[2] * 0.5;
  Vec3d dir{0.01, -0.02, 1.0};
  dir = dir * (1.0 / length(dir));
  const Ray ray{through - dir * 2.0, dir};
  for (const SimdLevel level : levels_here()) {
    ASSERT_EQ(set_simd_level(level), level);
    HitIterator it(w->accel, KernelKind::filter);
    const std::vector<Hit> hits = kernel_hits(it, ray);
    ASSERT_EQ(hits.size(), 6u) << simd_level_name(level);
    for (const Hit& h : hits) {
      const std::vector<Vec3d>& q = meshes[h.geom].vertices;
      const Vec3d at = q[0] * (1.0 - double(h.u) - double(h.v)) + q[1] * double(h.u) + q[2] * double(h.v);
      const Vec3d on_ray = ray.org + ray.dir * h.t;
      EXPECT_NEAR(at.x, on_ray.x, 1e-5) << meshes[h.geom].name << " at " << simd_level_name(level);
      EXPECT_NEAR(at.y, on_ray.y, 1e-5) << meshes[h.geom].name << " at " << simd_level_name(level);
      EXPECT_EQ(h.enter, dot(ray.dir, cross(q[1] - q[0], q[2] - q[0])) < 0.0) << meshes[h.geom].name;
      const Vec3f f0(q[0]), f1(q[1]), f2(q[2]);
      EXPECT_EQ(h.ng, Vec3f(cross(f1 - f0, f2 - f0))) << meshes[h.geom].name;
    }
  }
}

}  // namespace
}  // namespace pierce::test
