// The SIMD levels' node test (SimdRay::fused_slabs, one fused multiply-add per plane) must give
// every box an interval that contains what slab() and widen() give it: then a box passes wherever
// the scalar test passes it, so "triangle hit => every enclosing box hit" holds (wide_ops.h,
// SimdRay::node_offsets, has the argument). Checked lane by lane against slab() on random boxes
// and rays, with huge offsets, tiny and huge scales, and direction components near zero (where
// the offsets leave the float range and the test falls back to slab() itself).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pierce/simd/simd_level.h"
#include "pierce/simd/wide_ops.h"
#include "pierce/slab.h"

namespace pierce::test {
namespace {

struct Intervals {
  alignas(32) float tn[kWideArity], wf[kWideArity];
  bool fused = false;
};

// The node test's intervals for the eight slots of `n`, as the SIMD levels compute them.
__attribute__((target(PIERCE_AVX2_TARGET))) Intervals simd_intervals(const TraversalRay<float>& r,
                                                                     double scene_max_abs, const WideNode<float>& n) {
  const simd::SimdRay ray(r, scene_max_abs);
  Intervals out;
  out.fused = ray.fused;
  __m256 tn, wf, outside;
  if (ray.fused) {
    ray.fused_slabs(n, tn, wf);
  } else {
    ray.slabs(n, tn, wf, outside);
  }
  _mm256_store_ps(out.tn, tn);
  _mm256_store_ps(out.wf, wf);
  return out;
}

// A float in [-scale, scale], now and then exactly on a round value (planes shared by boxes).
float coordinate(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double x = u(rng) * scale;
  return rng() % 8 == 0 ? float(std::round(x)) : float(x);
}

class FusedNodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (int(best_simd_level()) < int(SimdLevel::avx2)) GTEST_SKIP() << "no AVX2 and FMA on this CPU";
  }
};

TEST_F(FusedNodeTest, ContainsTheWidenedSlabInterval) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double scales[] = {1e-6, 1.0, 1e3, 1e6, 1e12, 1e17};
  const double offsets[] = {0.0, 1.0, 1e5, 1e9, 1e20, 1e30};
  const double tiny_components[] = {0.0, 1e-3, 1e-12, 1e-30, 1e-38, 1e-45};
  int fused = 0, fallback = 0;
  for (int i = 0; i < 60000; ++i) {
    const double scale = scales[rng() % 6];
    WideNode<float> n{};
    double max_abs = 0;
    const int filled = 1 + int(rng() % kWideArity);
    for (int s = 0; s < kWideArity; ++s)
      for (int a = 0; a < 3; ++a) {
        if (s >= filled) {  // an empty slot, as set_wide_boxes writes it
          n.lo[a][s] = std::numeric_limits<float>::infinity();
          n.hi[a][s] = -std::numeric_limits<float>::infinity();
          continue;
        }
        const float p = coordinate(rng, scale), q = rng() % 16 == 0 ? p : coordinate(rng, scale);
        n.lo[a][s] = std::min(p, q), n.hi[a][s] = std::max(p, q);
        max_abs = std::max({max_abs, std::abs(double(p)), std::abs(double(q))});
      }
    Ray ray;
    const double offset = offsets[rng() % 6];
    for (int a = 0; a < 3; ++a) ray.org[std::size_t(a)] = unit(rng) * (scale + offset);
    ray.dir = {unit(rng), unit(rng), unit(rng)};
    if (rng() % 2 == 0) ray.dir[rng() % 3] = tiny_components[rng() % 6] * (rng() % 2 ? 1 : -1);
    ray.tmin = 0, ray.tmax = std::numeric_limits<double>::infinity();
    const auto r = TraversalRay<float>::make(ray, max_abs);
    if (!r.valid()) continue;

    const Intervals got = simd_intervals(r, max_abs, n);
    (got.fused ? fused : fallback) += 1;
    for (int s = 0; s < kWideArity; ++s) {
      if (s >= filled) {
        if (got.fused) {
          EXPECT_FALSE(got.tn[s] <= got.wf[s]) << "an empty slot passes, ray " << i;
        }
        continue;
      }
      const Span<float> sp = slab(r, Vec3<float>(n.lo[0][s], n.lo[1][s], n.lo[2][s]),
                                  Vec3<float>(n.hi[0][s], n.hi[1][s], n.hi[2][s]));
      if (sp.tn == std::numeric_limits<float>::infinity()) continue;  // a parallel axis misses: `outside`
      const float wf = r.widen(sp.tf);
      ASSERT_LE(got.tn[s], sp.tn) << "entry above slab()'s, ray " << i << " slot " << s;
      if (!std::isnan(wf)) {
        ASSERT_GE(got.wf[s], wf) << "exit below widen(slab()), ray " << i << " slot " << s;
      }
      if (got.fused) {
        ASSERT_FALSE(std::isnan(got.tn[s]) || std::isnan(got.wf[s]));
        // Conservative, and not by much: the entry within a few units of 2^-24 of the largest
        // t-span an axis gives the scene from this origin, the exit within 2^-20 of it more than
        // widen() (its relative factor taken over the span rather than the exit distance).
        double span = 0;
        for (int a = 0; a < 3; ++a) span = std::max(span, (max_abs + std::abs(double(r.org[a]))) * std::abs(double(r.inv[a])));
        if (std::isfinite(sp.tn) && std::isfinite(got.tn[s])) {
          EXPECT_LE(double(sp.tn) - double(got.tn[s]), 0x1p-21 * span + 1e-30) << "ray " << i << " slot " << s;
        }
        if (std::isfinite(wf) && std::isfinite(got.wf[s])) {
          EXPECT_LE(double(got.wf[s]) - double(wf), 0x1p-19 * span + 2 * double(r.pad) + 1e-30)
              << "ray " << i << " slot " << s;
        }
      }
    }
  }
  EXPECT_GT(fused, 35000);
  EXPECT_GT(fallback, 100);  // zero and near-zero direction components
}

}  // namespace
}  // namespace pierce::test
