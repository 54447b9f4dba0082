// Traversal counters (the counting variant, KernelOptions::count): non-zero where the kernel does
// that work, and consistent: every returned hit was a valid hit, every valid hit came from a
// primitive test. The plain variant counts nothing and returns the same hits.
#include "test_util.h"

namespace pierce::test {
namespace {

bool on_pierce_bvh(KernelKind k) {
  return k == KernelKind::restart || k == KernelKind::queue || k == KernelKind::nodecull ||
         k == KernelKind::filter || k == KernelKind::buffered;
}

TEST(Counters, NonZeroAndConsistent) {
  auto meshes = gen::stacked_plates(6);
  meshes.push_back(gen::random_soup(300, 0.2, 3));
  const auto w = make_world(meshes);
  const auto rays = random_rays(w->scene.bounds(), 100, 4);
  for (KernelKind k : kAllKernels) {
    SCOPED_TRACE(kernel_name(k));
    KernelOptions counting;
    counting.count = true;
    HitIterator it(w->accel, k, counting);  // constructed, then moved into place: counting must survive that
    std::vector<HitIterator> moved;
    moved.push_back(std::move(it));
    HitIterator& m = moved.back();
    HitIterator plain(w->accel, k);
    std::size_t returned = 0;
    for (const Ray& r : rays) {
      const auto hits = kernel_hits(m, r);
      EXPECT_TRUE(same_hits(kernel_hits(plain, r), hits)) << "counting changed the answer";
      returned += hits.size();
    }
    EXPECT_EQ(plain.counters().traversal_steps, 0u) << "the plain variant counts nothing";
    ASSERT_GT(returned, 0u);
    const Counters c = m.counters();
    EXPECT_GT(c.traversal_steps, 0u);
    if (k == KernelKind::epsilon) continue;  // Embree's native triangles: only relaunches are counted
    EXPECT_GT(c.prim_tests, 0u);
    EXPECT_GE(c.prim_tests, c.valid_hits);
    EXPECT_GE(c.valid_hits, returned);
    if (on_pierce_bvh(k)) {
      EXPECT_GT(c.node_tests, 0u);
      EXPECT_GE(c.node_tests, c.traversal_steps) << "every processed node was tested first";
    }
    // Counters accumulate: more rays, larger counts.
    for (const Ray& r : rays) kernel_hits(m, r);
    const Counters c2 = m.counters();
    EXPECT_GT(c2.prim_tests, c.prim_tests);
    EXPECT_GE(c2.valid_hits, 2 * returned);
  }
}

}  // namespace
}  // namespace pierce::test
