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
  auto meshes = gen::stacked_plates(6);
  meshes.push_back(gen::duplicated(gen::box({0.2, 0.2, 0.1}, {0.7, 0.7, 0.5}, "dup"), 3, true));
  meshes.push_back(gen::blob(3));
  const auto w = make_world(meshes);
  const BBoxd box = w->scene.bounds();
  std::vector<Ray> rays = random_rays(box, 300, 11);
  const std::vector<Ray> at_vertices = vertex_rays(meshes, box, 300, 12);
  rays.insert(rays.end(), at_vertices.begin(), at_vertices.end());
  for (int i = 0; i < 100; ++i) {  // axis-parallel, along the plates' shared faces and edges
    const double x = (i % 10) / 9.0, y = (i / 10) / 9.0;
    rays.push_back({{x, y, -1.0}, {0, 0, 1}});
    rays.push_back({{-1.0, x, 0.1 * (i % 7)}, {1, 0, 0}});
  }

  std::vector<SimdLevel> levels{SimdLevel::scalar};
  if (int(best_simd_level()) >= int(SimdLevel::avx2)) levels.push_back(SimdLevel::avx2);
  if (best_simd_level() == SimdLevel::avx512) levels.push_back(SimdLevel::avx512);
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

}  // namespace
}  // namespace pierce::test
