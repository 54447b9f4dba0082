// The prefetch mode (prefetch_mode.h) changes what a traversal asks the memory for, never what it
// finds: every exact own-BVH kernel returns the same hits, bit for bit, with the prefetch forced on
// and forced off. The automatic choice follows the BVH's size and the traversal order. (The whole
// suite also runs with PIERCE_PREFETCH=always in ctest: kernels.prefetch_always.)
#include <cstdlib>
#include <optional>

#include "pierce/prefetch_mode.h"
#include "test_util.h"

namespace pierce::test {
namespace {

// Restores the mode in use when a test ends.
struct PrefetchGuard {
  PrefetchMode saved = prefetch_mode();
  ~PrefetchGuard() { set_prefetch_mode(saved); }
};

TEST(PrefetchMode, NamesParse) {
  for (const PrefetchMode m : {PrefetchMode::automatic, PrefetchMode::always, PrefetchMode::never})
    EXPECT_EQ(parse_enum<PrefetchMode>(enum_name(m)), m);
  EXPECT_EQ(enum_name(PrefetchMode::automatic), "auto");
  EXPECT_FALSE(parse_enum<PrefetchMode>("sometimes"));
  EXPECT_THROW(parse_enum_or_throw<PrefetchMode>("sometimes"), std::invalid_argument);
}

// ctest's kernels.prefetch_always and oracle.prefetch_always rely on PIERCE_PREFETCH reaching the
// library: without it they would run the default mode and test nothing new.
TEST(PrefetchMode, EnvironmentSetsTheMode) {
  const char* env = std::getenv("PIERCE_PREFETCH");
  if (env == nullptr || *env == '\0') GTEST_SKIP() << "PIERCE_PREFETCH not set (ctest sets it in kernels.prefetch_always)";
  const std::optional<PrefetchMode> want = parse_enum<PrefetchMode>(env);
  ASSERT_TRUE(want) << "PIERCE_PREFETCH=" << env;
  EXPECT_EQ(prefetch_mode(), *want);
}

TEST(PrefetchMode, AutomaticDecidesBySizeAndOrder) {
  PrefetchGuard guard;
  constexpr std::size_t kMiB = std::size_t(1) << 20;
  set_prefetch_mode(PrefetchMode::automatic);
  EXPECT_EQ(prefetch_mode(), PrefetchMode::automatic);
  // Breadth first (any order) beyond 8 MB, depth first beyond 16 MB.
  EXPECT_FALSE(prefetches(8 * kMiB, true));
  EXPECT_TRUE(prefetches(8 * kMiB + 1, true));
  EXPECT_FALSE(prefetches(16 * kMiB, false));
  EXPECT_TRUE(prefetches(16 * kMiB + 1, false));
  EXPECT_FALSE(prefetches(12 * kMiB, false));
  set_prefetch_mode(PrefetchMode::always);
  EXPECT_TRUE(prefetches(0, false));
  EXPECT_TRUE(prefetches(0, true));
  set_prefetch_mode(PrefetchMode::never);
  EXPECT_FALSE(prefetches(std::size_t(1) << 40, false));
  EXPECT_FALSE(prefetches(std::size_t(1) << 40, true));
}

TEST(PrefetchMode, IdenticalHitsWithAndWithout) {
  PrefetchGuard guard;
  const HardCases cases = hard_cases(21);
  const auto& w = cases.world;
  const std::vector<Ray>& rays = cases.rays;

  // The float kernels' hits are also checked against brute force, so the two modes cannot agree on
  // a wrong answer (the double kernels' against each other only: the brute force is in float).
  std::vector<std::vector<Hit>> brute_force;
  for (const Ray& ray : rays) brute_force.push_back(reference_hits(w->scene, ray, {}));
  std::size_t checked = 0;
  for (const KernelKind kind : exact_kernels()) {
    if (uses_embree(kind)) continue;
    const bool in_float = kernel_precision_bits(kind) == 24;
    for (const std::size_t max_hits : {std::size_t(1), std::size_t(5), std::size_t(0)}) {
      std::vector<std::vector<Hit>> want;
      for (const PrefetchMode mode : {PrefetchMode::never, PrefetchMode::always}) {
        set_prefetch_mode(mode);
        HitIterator it(w->accel, kind, KernelOptions{});
        for (std::size_t i = 0; i < rays.size(); ++i) {
          const std::vector<Hit> got = kernel_hits(it, rays[i], max_hits);
          if (in_float) {
            std::vector<Hit> first = brute_force[i];
            if (max_hits != 0 && first.size() > max_hits) first.resize(max_hits);
            ASSERT_TRUE(same_hits(first, got)) << kernel_name(kind) << ", max_hits " << max_hits << ", prefetch "
                                               << int(mode) << ", ray " << i << " " << str(rays[i]);
            checked += got.size();
          }
          if (mode == PrefetchMode::never) {
            want.push_back(got);
            continue;
          }
          ASSERT_TRUE(same_hits(want[i], got)) << kernel_name(kind) << ", max_hits " << max_hits << ", ray " << i
                                               << " " << str(rays[i]);
        }
      }
    }
  }
  EXPECT_GT(checked, 10000u) << "the float kernels' hits were checked against brute force";
}

}  // namespace
}  // namespace pierce::test
