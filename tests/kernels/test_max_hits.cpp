// The max-hits hint: N-closest kernels (nodecull, embree-nodecull) fetch hits in batches of N but
// continuing next() past N still yields the complete sequence; every kernel accepts the hint; and
// collect_hits with max_hits returns exactly the first N.
#include <algorithm>
#include <random>

#include "test_util.h"

namespace pierce::test {
namespace {

struct Fixture {
  std::unique_ptr<World> world;
  std::vector<Ray> rays;
};

// Ties everywhere (touching plates, 7 copies of one box) plus a soup, and rays with many hits.
Fixture make_fixture() {
  auto meshes = gen::stacked_plates(10);
  meshes.push_back(gen::duplicated(gen::box({0.25, 0.25, 0.25}, {0.75, 0.75, 0.75}, "dup"), 7, false));
  meshes.push_back(gen::random_soup(300, 0.3, 8));
  Fixture f{make_world(meshes), {}};
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> U(0.05, 0.95), D(-0.1, 0.1);
  for (int i = 0; i < 25; ++i) f.rays.push_back({{U(rng), U(rng), -1.0}, {D(rng), D(rng), 1.0}});
  for (int i = 0; i < 10; ++i) f.rays.push_back({{U(rng), U(rng), 2.0}, {0, 0, -1.0}});
  for (const Ray& r : random_rays(f.world->scene.bounds(), 25, 13)) f.rays.push_back(r);
  return f;
}

constexpr std::size_t kHints[] = {1, 5, 15};

TEST(MaxHits, NodeCullContinuesPastTheHint) {
  const Fixture f = make_fixture();
  for (TieOrder tie : kTieOrders) {
    SCOPED_TRACE(tie_name(tie));
    for (KernelKind k : {KernelKind::nodecull, KernelKind::embree_nodecull}) {
      HitIterator it(f.world->accel, k, {HitOrder{tie}});
      for (std::size_t n : kHints)
        for (const Ray& r : f.rays) {
          const auto want = reference_hits(f.world->scene, r, {tie});
          it.begin(r, n);
          std::vector<Hit> got;
          Hit h;
          while (got.size() <= want.size() + 5 && it.next(h)) got.push_back(h);
          ASSERT_TRUE(same_hits(want, got)) << kernel_name(k) << " hint " << n << " " << str(r);
          EXPECT_FALSE(it.next(h)) << "an exhausted iterator stays exhausted";
        }
    }
  }
}

// `queue`'s first pass in either order, and switching between them from ray to ray (adaptive: near
// to far while culling defers much, as at hint 1 here; breadth first once it defers nothing, as at
// hint 1000, where no ray closes its bound), gives the complete sequence.
TEST(MaxHits, QueueFirstPassInEitherOrder) {
  const Fixture f = make_fixture();
  const WideBvhf& bvh = f.world->accel.wide();
  for (TieOrder tie : kTieOrders) {
    SCOPED_TRACE(tie_name(tie));
    for (QueueFirstPass pass : {QueueFirstPass::depth_first, QueueFirstPass::breadth_first, QueueFirstPass::adaptive}) {
      QueueKernel<float> k(bvh, {tie}, pass);
      std::size_t breadth_first_rays[2] = {0, 0};  // at hint 1 and at hint 1000
      for (std::size_t n : {std::size_t(1), std::size_t(5), std::size_t(15), std::size_t(1000)})
        for (std::size_t i = 0; i < (n == 1000 ? 4 : 1) * f.rays.size(); ++i) {
          const Ray& r = f.rays[i % f.rays.size()];
          const auto want = reference_hits(f.world->scene, r, {tie});
          if (n == 1 || n == 1000) breadth_first_rays[n == 1000] += k.breadth_first();
          k.begin(r, n);
          std::vector<Hit> got;
          Hit h;
          while (got.size() <= want.size() + 5 && k.next(h)) got.push_back(h);
          ASSERT_TRUE(same_hits(want, got)) << "pass " << int(pass) << " hint " << n << " " << str(r);
        }
      if (pass == QueueFirstPass::adaptive) {
        EXPECT_EQ(breadth_first_rays[0], 0u) << "at hint 1 culling defers much: near to far";
        EXPECT_GT(breadth_first_rays[1], 0u) << "at hint 1000 it defers nothing: breadth first";
      }
    }
  }
}

// `queue`'s gathering pass hands a caller that wants N hits (HitIterator::collect) every hit, the
// first N of them in order and the rest after them (sort_first_hits): rays of up to 70 hits here,
// against hints below and above 16 (the insertion and the partial_sort paths).
TEST(MaxHits, QueueGatheringPassSortsTheHitsAskedFor) {
  const Fixture f = make_fixture();
  for (TieOrder tie : kTieOrders) {
    SCOPED_TRACE(tie_name(tie));
    QueueKernel<float> k(f.world->accel.wide(), {tie}, QueueFirstPass::breadth_first);
    const HitOrder order{tie};
    for (std::size_t n : {std::size_t(1), std::size_t(5), std::size_t(15), std::size_t(20), std::size_t(1000)})
      for (const Ray& r : f.rays) {
        const auto want = reference_hits(f.world->scene, r, {tie});
        std::vector<Hit> got{Hit{}};  // begin_into appends
        ASSERT_TRUE(k.begin_into(r, n, got)) << "breadth first, the pass gathers";
        got.erase(got.begin());
        ASSERT_EQ(got.size(), want.size()) << "hint " << n << " " << str(r);
        const std::size_t sorted = std::min(n, want.size());
        const std::vector<Hit> front(got.begin(), got.begin() + std::ptrdiff_t(sorted));
        EXPECT_TRUE(same_hits({want.begin(), want.begin() + std::ptrdiff_t(sorted)}, front))
            << "the first " << n << " in order; hint " << n << " " << str(r);
        std::sort(got.begin(), got.end(), order);
        EXPECT_TRUE(same_hits(want, got)) << "and every other hit after them; hint " << n << " " << str(r);
      }
  }
}

// Adaptive `queue` probes depth first less often while the probes find little to cull (hint 30:
// 17 of the 60 rays hold 30 hits or more, and their bounds close near their ends); not at all while
// no gathered ray holds as many hits as the hint (hint 1000: a probe could defer nothing), nor while
// fewer than one in eight do (the most hits any ray holds: culling could pay on too few rays); and
// runs near to far again once culling defers much (hint 1).
TEST(MaxHits, QueueProbesOnlyWhereCullingCanPay) {
  const Fixture f = make_fixture();
  QueueKernel<float> k(f.world->accel.wide());
  auto run = [&](std::size_t hint, std::size_t rays, std::size_t count_from) {
    std::size_t depth_first = 0;
    Hit h;
    for (std::size_t i = 0; i < rays; ++i) {
      if (i >= count_from) depth_first += !k.breadth_first();
      k.begin(f.rays[i % f.rays.size()], hint);
      while (k.next(h)) {
      }
    }
    return depth_first;
  };
  // Every 32nd ray would be 128 of the last 4096.
  const std::size_t probes = run(30, 8192, 4096);
  EXPECT_GT(probes, 0u) << "rays hold 30 hits: it still probes";
  EXPECT_LT(probes, 4096u / 32) << "less often than every 32nd ray while the probes find little to cull";
  EXPECT_EQ(run(1000, 4096, 2048), 0u) << "no ray holds 1000 hits: no probe";
  std::size_t most = 0, holding = 0;  // the most hits a ray holds, and how many rays hold that many
  for (const Ray& r : f.rays) {
    const std::size_t hits = reference_hits(f.world->scene, r, {}).size();
    if (hits > most) most = hits, holding = 0;
    holding += hits == most;
  }
  ASSERT_LT(holding * QueueKernel<float>::kProbeShare, f.rays.size()) << "the fixture's longest rays must be few";
  EXPECT_EQ(run(most, 4096, 2048), 0u) << holding << " of " << f.rays.size() << " rays hold " << most
                                       << " hits: too few for a probe";
  EXPECT_EQ(run(1, 2048, 1536), 512u) << "at hint 1 culling defers much: near to far again";
}

TEST(MaxHits, EveryKernelAcceptsTheHint) {
  const Fixture f = make_fixture();
  std::size_t long_rays = 0;
  for (const Ray& r : f.rays) long_rays += reference_hits(f.world->scene, r, {}).size() > 15;
  ASSERT_GT(long_rays, 20u) << "the fixture must have rays longer than the largest hint";
  for (KernelKind k : exact_kernels()) {
    HitIterator it(f.world->accel, k);
    for (std::size_t n : kHints)
      for (const Ray& r : f.rays) {
        const auto want = reference_hits(f.world->scene, r, {});
        it.begin(r, n);
        std::vector<Hit> got;
        Hit h;
        while (got.size() <= want.size() + 5 && it.next(h)) got.push_back(h);
        ASSERT_TRUE(same_hits(want, got)) << kernel_name(k) << " hint " << n << " " << str(r);
      }
  }
}

TEST(MaxHits, CollectHitsTruncates) {
  const Fixture f = make_fixture();
  for (TieOrder tie : kTieOrders) {
    SCOPED_TRACE(tie_name(tie));
    for (KernelKind k : exact_kernels()) {
      HitIterator it(f.world->accel, k, {HitOrder{tie}});
      for (const Ray& r : f.rays) {
        const auto all = reference_hits(f.world->scene, r, {tie});
        for (std::size_t n : {std::size_t(1), std::size_t(5), std::size_t(15), all.size(), all.size() + 3}) {
          if (n == 0) continue;  // 0 means "all"
          const std::vector<Hit> want(all.begin(), all.begin() + std::ptrdiff_t(std::min(n, all.size())));
          std::vector<Hit> got{Hit{}};  // collect_hits appends
          collect_hits(it, r, n, got);
          got.erase(got.begin());
          ASSERT_TRUE(same_hits(want, got)) << kernel_name(k) << " max_hits " << n << " " << str(r);
        }
        std::vector<Hit> got;
        collect_hits(it, r, 0, got);
        ASSERT_TRUE(same_hits(all, got)) << kernel_name(k) << " max_hits 0 " << str(r);
      }
    }
  }
}

}  // namespace
}  // namespace pierce::test
