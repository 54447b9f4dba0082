// A wide kernel's per-ray setup at the SIMD levels (simd::prepare_simd_ray) computes the
// TraversalRay and the SimdRay together, in registers. Every field must be what
// TraversalRay::assign() and SimdRay's constructor give, bit for bit, on every kind of ray: random
// directions, axis-aligned and diagonal ones (ties for the largest axis), zero and negative-zero
// components, components that round to zero, to subnormals or to infinity in float, infinities
// and NaNs, and ranges that a float cannot hold.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "pierce/simd/simd_level.h"
#include "pierce/simd/wide_ops.h"
#include "test_util.h"

namespace pierce::test {
namespace {

template <typename V>
bool same_bits(const V& a, const V& b) {
  return std::memcmp(&a, &b, sizeof(V)) == 0;
}

// "name[a]"
std::string field(const char* name, int a) { return std::string(name).append("[").append(std::to_string(a)).append("]"); }

// The first field of `got` that differs from `want`, or empty.
std::string first_difference(const TraversalRay<float>& want, const TraversalRay<float>& got) {
  for (int a = 0; a < 3; ++a) {
    const auto k = std::size_t(a);
    if (!same_bits(want.org[k], got.org[k])) return field("org", a);
    if (!same_bits(want.dir[k], got.dir[k])) return field("dir", a);
    if (!same_bits(want.inv[k], got.inv[k])) return field("inv", a);
    if (want.zero[a] != got.zero[a]) return field("zero", a);
  }
  if (want.kx != got.kx || want.ky != got.ky || want.kz != got.kz) return "kx, ky, kz";
  if (!same_bits(want.sx, got.sx) || !same_bits(want.sy, got.sy) || !same_bits(want.sz, got.sz)) return "sx, sy, sz";
  if (!same_bits(want.tmin, got.tmin) || !same_bits(want.tmax, got.tmax)) return "tmin, tmax";
  if (!same_bits(want.pad, got.pad)) return "pad";
  if (want.ok != got.ok) return "ok";
  return {};
}

std::string first_difference(const simd::SimdRay& want, const simd::SimdRay& got) {
  for (int a = 0; a < 3; ++a) {
    if (!same_bits(want.org[a], got.org[a])) return field("org", a);
    if (!same_bits(want.inv[a], got.inv[a])) return field("inv", a);
    if (!same_bits(want.swap_mask[a], got.swap_mask[a])) return field("swap_mask", a);
    if (!same_bits(want.near_c[a], got.near_c[a])) return field("near_c", a);
    if (!same_bits(want.far_c[a], got.far_c[a])) return field("far_c", a);
    if (want.near_offset[a] != got.near_offset[a] || want.far_offset[a] != got.far_offset[a]) return field("offsets", a);
    if (want.zero[a] != got.zero[a]) return field("zero", a);
  }
  if (!same_bits(want.pad, got.pad)) return "pad";
  if (!same_bits(want.okx, got.okx) || !same_bits(want.oky, got.oky) || !same_bits(want.okz, got.okz)) return "ok*";
  if (!same_bits(want.sx, got.sx) || !same_bits(want.sy, got.sy) || !same_bits(want.sz, got.sz)) return "sx, sy, sz";
  if (want.any_zero != got.any_zero) return "any_zero";
  if (want.fused != got.fused) return "fused";
  if (want.oct != got.oct) return "oct";
  if (want.kx_offset != got.kx_offset || want.ky_offset != got.ky_offset || want.kz_offset != got.kz_offset)
    return "k*_offset";
  return {};
}

class PreparedRay : public ::testing::Test {
 protected:
  void SetUp() override {
    if (int(best_simd_level()) < int(SimdLevel::avx2)) GTEST_SKIP() << "no AVX2 and FMA on this CPU";
  }
};

// A double of one of the kinds above.
double component(std::mt19937_64& rng) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  static constexpr double special[] = {0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 1e-300, -1e-300, 1e-40, -1e-42, 1e39,
                                       -1e39, 3.4028234663852886e38, inf, -inf, std::numeric_limits<double>::quiet_NaN(),
                                       0.1, -0.1, 1e20, -1e-20};
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  switch (rng() % 4) {
    case 0: return special[rng() % std::size(special)];
    case 1: return unit(rng) * std::pow(10.0, double(rng() % 61) - 30.0);
    default: return unit(rng);
  }
}

TEST_F(PreparedRay, MatchesTraversalRayAndSimdRay) {
  std::mt19937_64 rng(11);
  std::size_t valid = 0, compared = 0;
  for (int i = 0; i < 200000; ++i) {
    Ray r;
    r.org = {component(rng), component(rng), component(rng)};
    r.dir = {component(rng), component(rng), component(rng)};
    if (rng() % 4 == 0) {
      // Ties for the largest axis: equal magnitudes, either sign.
      const double m = component(rng);
      r.dir = {rng() % 2 ? m : -m, rng() % 2 ? m : -m, rng() % 3 ? m : component(rng)};
    }
    r.tmin = rng() % 3 ? 0.0 : component(rng);
    r.tmax = rng() % 3 ? std::numeric_limits<double>::infinity() : component(rng);
    const double scene_max_abs = rng() % 2 ? 1.0 : std::abs(component(rng));
    if (!std::isfinite(scene_max_abs)) continue;

    const TraversalRay<float> want = TraversalRay<float>::make(r, scene_max_abs);
    const simd::SimdRay want_simd(want, scene_max_abs);
    TraversalRay<float> got;
    simd::SimdRay got_simd;
    simd::prepare_simd_ray(r, scene_max_abs, got, got_simd);
    ASSERT_EQ(first_difference(want, got), "") << str(r) << " scene_max_abs " << scene_max_abs;
    ASSERT_EQ(first_difference(want_simd, got_simd), "") << str(r) << " scene_max_abs " << scene_max_abs;
    valid += want.valid();
    ++compared;
  }
  EXPECT_GT(valid, compared / 4) << "most rays must be traceable";
  EXPECT_LT(valid, compared) << "some must not be";
}

}  // namespace
}  // namespace pierce::test
