// Iterator state: many iterators advanced in an interleaved order, one iterator reused across rays
// (also abandoning a sequence half-way), iterators on several threads, and the TBB batch API,
// each compared with the uninterrupted brute-force sequence.
#include <atomic>
#include <numeric>
#include <random>
#include <thread>

#include "test_util.h"

namespace pierce::test {
namespace {

struct Fixture {
  std::unique_ptr<World> world;
  std::vector<Ray> rays;
  std::vector<std::vector<Hit>> want;  // geom_prim order
};

Fixture make_fixture(std::size_t n_rays) {
  auto meshes = gen::stacked_plates(8);
  meshes.push_back(gen::duplicated(gen::box({0.3, 0.3, 0.1}, {0.7, 0.7, 0.5}, "dup"), 4, true));
  meshes.push_back(gen::random_soup(400, 0.25, 21));
  meshes.push_back(gen::translated(gen::blob(2, 3), {0.5, 0.5, 0.4}));
  Fixture f{make_world(meshes), {}, {}};
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> U(0.05, 0.95), D(-0.2, 0.2);
  for (std::size_t i = 0; i < n_rays / 2; ++i) f.rays.push_back({{U(rng), U(rng), -1.5}, {D(rng), D(rng), 1.0}});
  for (const Ray& r : random_rays(f.world->scene.bounds(), n_rays - n_rays / 2, 23)) f.rays.push_back(r);
  for (const Ray& r : f.rays) f.want.push_back(reference_hits(f.world->scene, r, {}));
  return f;
}

TEST(Resume, InterleavedIterators) {
  const Fixture f = make_fixture(48);
  std::mt19937_64 rng(5);
  for (KernelKind k : exact_kernels()) {
    std::vector<HitIterator> its;
    std::vector<std::vector<Hit>> got(f.rays.size());
    std::vector<char> live(f.rays.size(), 1);
    for (std::size_t i = 0; i < f.rays.size(); ++i) {
      its.emplace_back(f.world->accel, k);
      its.back().begin(f.rays[i], i % 4 == 0 ? 3 : 0);  // some with a max-hits hint too
    }
    std::vector<std::size_t> turn(f.rays.size());
    std::iota(turn.begin(), turn.end(), 0);
    for (std::size_t remaining = f.rays.size(); remaining > 0;) {
      std::shuffle(turn.begin(), turn.end(), rng);
      for (std::size_t i : turn) {
        if (!live[i]) continue;
        for (std::size_t steps = 1 + rng() % 3; steps > 0 && live[i]; --steps) {
          Hit h;
          if (its[i].next(h)) {
            got[i].push_back(h);
            if (got[i].size() > f.want[i].size() + 5) live[i] = 0, --remaining;  // runaway
          } else {
            live[i] = 0, --remaining;
          }
        }
      }
    }
    for (std::size_t i = 0; i < f.rays.size(); ++i)
      ASSERT_TRUE(same_hits(f.want[i], got[i])) << kernel_name(k) << " ray " << i << " " << str(f.rays[i]);
  }
}

TEST(Resume, OneIteratorAcrossRaysAbandoningSequences) {
  const Fixture f = make_fixture(48);
  std::mt19937_64 rng(6);
  for (KernelKind k : kAllKernels) {  // epsilon too: reuse must not leak state between rays
    HitIterator it(f.world->accel, k);
    std::vector<std::vector<Hit>> fresh;  // epsilon's own sequences from a new iterator per ray
    for (const Ray& r : f.rays) {
      HitIterator one(f.world->accel, k);
      fresh.push_back(kernel_hits(one, r));
    }
    for (int round = 0; round < 2; ++round)
      for (std::size_t i = 0; i < f.rays.size(); ++i) {
        // Start another ray and drop it after a few hits, then run ray i completely.
        it.begin(f.rays[rng() % f.rays.size()], rng() % 2 ? 0 : 4);
        Hit h;
        for (std::size_t s = rng() % 6; s > 0 && it.next(h);) --s;
        const auto got = kernel_hits(it, f.rays[i]);
        ASSERT_TRUE(same_hits(fresh[i], got)) << kernel_name(k) << " ray " << i;
        if (is_exact(k)) {
          ASSERT_TRUE(same_hits(f.want[i], got)) << kernel_name(k) << " ray " << i;
        }
      }
  }
}

TEST(Resume, IteratorsOnSeveralThreads) {
  const Fixture f = make_fixture(64);
  const auto kernels = exact_kernels();
  std::atomic<int> mismatches{0}, checked{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      std::mt19937_64 rng(100 + t);
      // Each thread: its own iterators for every kernel, advanced in a thread-specific interleaving.
      std::vector<HitIterator> its;
      for (KernelKind k : kernels) its.emplace_back(f.world->accel, k);
      for (int pass = 0; pass < 2; ++pass)
        for (std::size_t i = 0; i < f.rays.size(); ++i) {
          const std::size_t ray = (i * 7 + std::size_t(t) * 13 + std::size_t(pass)) % f.rays.size();
          std::vector<std::vector<Hit>> got(its.size());
          for (auto& it : its) it.begin(f.rays[ray], rng() % 3 == 0 ? 2 : 0);
          for (bool any = true; any;) {
            any = false;
            for (std::size_t j = 0; j < its.size(); ++j) {
              Hit h;
              if (got[j].size() <= f.want[ray].size() && its[j].next(h)) got[j].push_back(h), any = true;
            }
          }
          for (std::size_t j = 0; j < its.size(); ++j) {
            mismatches += !same_hits(f.want[ray], got[j]);
            ++checked;
          }
        }
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(mismatches.load(), 0);
  EXPECT_EQ(checked.load(), int(4 * 2 * f.rays.size() * kernels.size()));
}

TEST(Resume, BatchEqualsSerialAndIsDeterministic) {
  const Fixture f = make_fixture(600);
  for (KernelKind k : kAllKernels)
    for (std::size_t max_hits : {0, 5}) {
      SCOPED_TRACE(testing::Message() << kernel_name(k) << " max_hits " << max_hits);
      HitIterator it(f.world->accel, k);
      std::vector<std::vector<Hit>> serial;
      for (const Ray& r : f.rays) serial.push_back(kernel_hits(it, r, max_hits));
      std::atomic<std::size_t> last_done{0};
      HitBatch batch, again;
      ASSERT_TRUE(trace_batch(f.world->accel, k, f.rays, max_hits, batch, {}, [&](std::size_t done, std::size_t) {
        std::size_t prev = last_done.load();
        while (done > prev && !last_done.compare_exchange_weak(prev, done)) {
        }
        return true;
      }));
      ASSERT_TRUE(trace_batch(f.world->accel, k, f.rays, max_hits, again));
      EXPECT_EQ(last_done.load(), f.rays.size());
      ASSERT_EQ(batch.rays(), f.rays.size());
      for (std::size_t i = 0; i < f.rays.size(); ++i) {
        ASSERT_TRUE(same_hits(serial[i], batch.of(i))) << "ray " << i;
        ASSERT_TRUE(same_hits(batch.of(i), again.of(i))) << "ray " << i;
        if (is_exact(k)) {
          const std::size_t n = max_hits ? std::min(max_hits, f.want[i].size()) : f.want[i].size();
          ASSERT_TRUE(same_hits({f.want[i].begin(), f.want[i].begin() + std::ptrdiff_t(n)}, batch.of(i))) << "ray " << i;
        }
      }
    }
}

TEST(Resume, BatchCancel) {
  // Many cheap rays: far more TBB chunks than any machine has cores, so cancelling on the first
  // progress report must leave rays untraced.
  const auto w = make_world(gen::stacked_plates(2));
  std::vector<Ray> rays;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> U(0.05, 0.95);
  for (int i = 0; i < 100000; ++i) rays.push_back({{U(rng), U(rng), -1.0}, {0, 0, 1}});
  HitBatch out;
  EXPECT_FALSE(trace_batch(w->accel, KernelKind::filter, rays, 0, out, {}, [](std::size_t, std::size_t) { return false; }));
  ASSERT_EQ(out.rays(), rays.size());
  std::size_t traced = 0;
  for (std::size_t i = 0; i < out.rays(); ++i)
    if (!out.of(i).empty()) {
      ++traced;
      ASSERT_TRUE(same_hits(reference_hits(w->scene, rays[i], {}), out.of(i))) << "ray " << i;  // complete
    }
  EXPECT_GT(traced, 0u);
  EXPECT_LT(traced, rays.size()) << "cancel must stop the batch early";
}

}  // namespace
}  // namespace pierce::test
