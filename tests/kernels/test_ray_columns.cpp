// trace_batch on rays given as columns (strided origins and directions, tmin/tmax per ray or one
// value): the same HitBatch, bit for bit, as tracing each ray alone and as the Ray-array path,
// whatever the thread count; the validation names the first bad ray.
#include <tbb/global_control.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "pierce/error.h"
#include "pierce/ray_columns.h"
#include "pierce/ray_validation.h"
#include "test_util.h"

namespace pierce::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Every field of every hit bit for bit (so -0.0 != 0.0), and the same offsets.
::testing::AssertionResult bit_identical(const HitBatch& want, const HitBatch& got) {
  if (want.offsets != got.offsets) return ::testing::AssertionFailure() << "offsets differ";
  if (want.hits.size() != got.hits.size()) return ::testing::AssertionFailure() << "hit counts differ";
  for (std::size_t i = 0; i < want.hits.size(); ++i) {
    const Hit& a = want.hits[i];
    const Hit& b = got.hits[i];
    const bool same = std::bit_cast<std::uint64_t>(a.t) == std::bit_cast<std::uint64_t>(b.t) && a.geom == b.geom &&
                      a.prim == b.prim && a.enter == b.enter &&
                      std::bit_cast<std::uint32_t>(a.u) == std::bit_cast<std::uint32_t>(b.u) &&
                      std::bit_cast<std::uint32_t>(a.v) == std::bit_cast<std::uint32_t>(b.v) &&
                      std::memcmp(&a.ng, &b.ng, sizeof a.ng) == 0;
    if (!same) return ::testing::AssertionFailure() << "hit " << i << ": " << str(a) << " vs " << str(b);
  }
  return ::testing::AssertionSuccess();
}

// Each ray traced alone (HitIterator::collect), laid out as a HitBatch: no trace_batch involved.
HitBatch one_by_one(const Accel& accel, KernelKind kind, std::span<const Ray> rays, std::size_t max_hits) {
  HitBatch out;
  out.offsets.push_back(0);
  HitIterator it(accel, kind);
  for (const Ray& r : rays) {
    it.collect(r, max_hits, out.hits);
    out.offsets.push_back(out.hits.size());
  }
  return out;
}

struct Scene3 {
  std::unique_ptr<World> world;
  std::vector<Ray> rays;
};

// Several thousand rays (many TBB chunks) over touching plates, a duplicated box and a soup:
// grazing and shared-edge cases as well as random ones; random per-ray tmin/tmax.
Scene3 make_scene(std::size_t n) {
  auto meshes = gen::stacked_plates(6);
  meshes.push_back(gen::duplicated(gen::box({0.3, 0.3, 0.1}, {0.7, 0.7, 0.5}, "dup"), 3, true));
  meshes.push_back(gen::random_soup(300, 0.25, 5));
  Scene3 s{make_world(meshes), {}};
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> U(0.0, 1.0), D(-0.2, 0.2), T0(0.0, 0.8), T1(1.2, 4.0);
  for (std::size_t i = 0; i < n / 2; ++i)
    s.rays.push_back({{std::round(U(rng) * 8) / 8, U(rng), -1.0}, {D(rng), 0.0, 1.0}, T0(rng), T1(rng)});
  for (const Ray& r : random_rays(s.world->scene.bounds(), n - n / 2, 32)) s.rays.push_back(r);
  return s;
}

// The rays of `rays` scattered the way a front end may hold them: origins as every other double
// of (N, 6) rows, directions in reverse row order, tmin and tmax as every third double.
struct ScatteredRays {
  std::vector<double> origins, directions, tmin, tmax;
  RayColumns columns;

  explicit ScatteredRays(std::span<const Ray> rays)
      : origins(6 * rays.size()), directions(3 * rays.size()), tmin(3 * rays.size()), tmax(3 * rays.size()) {
    const std::size_t n = rays.size();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t k = 0; k < 3; ++k) {
        origins[6 * i + 2 * k] = rays[i].org[k];
        directions[3 * (n - 1 - i) + k] = rays[i].dir[k];
      }
    for (std::size_t i = 0; i < n; ++i) tmin[3 * i] = rays[i].tmin, tmax[3 * i] = rays[i].tmax;
    constexpr auto d = static_cast<std::ptrdiff_t>(sizeof(double));
    columns.count = n;
    columns.origins = {origins.data(), 6 * d, 2 * d};
    columns.directions = {directions.data() + 3 * (n - 1), -3 * d, d};
    columns.tmin = DoubleColumn::per_ray(tmin.data(), 3 * d);
    columns.tmax = DoubleColumn::per_ray(tmax.data(), 3 * d);
  }
};

TEST(RayColumns, ColumnsOfRaysReadEveryBit) {
  const std::vector<Ray> rays{{{1, -0.0, kInf}, {kNaN, 2, -3}, -0.0, 5}, {{4, 5, 6}, {0, 0, 1}, 0.5, kInf}};
  const RayColumns c = columns_of(rays);
  ASSERT_EQ(c.size(), rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Ray r = c[i];
    EXPECT_EQ(std::memcmp(&r, &rays[i], sizeof r), 0) << "ray " << i;
  }
  EXPECT_EQ(columns_of(std::span<const Ray>{}).size(), 0u);
}

TEST(RayColumns, ScatteredColumnsRebuildTheRays) {
  const Scene3 s = make_scene(100);
  const ScatteredRays scattered(s.rays);
  for (std::size_t i = 0; i < s.rays.size(); ++i) {
    const Ray r = scattered.columns[i];
    ASSERT_EQ(std::memcmp(&r, &s.rays[i], sizeof r), 0) << "ray " << i;
  }
}

TEST(RayColumns, BatchEqualsEachRayAloneForEveryKernelAndThreadCount) {
  const Scene3 s = make_scene(3000);
  const ScatteredRays scattered(s.rays);
  for (KernelKind k : kAllKernels)
    for (std::size_t max_hits : {0, 3}) {
      SCOPED_TRACE(testing::Message() << kernel_name(k) << " max_hits " << max_hits);
      const HitBatch want = one_by_one(s.world->accel, k, s.rays, max_hits);
      ASSERT_GT(want.hits.size(), s.rays.size());  // the scene is hit, many times
      for (int threads : {1, 2, 3}) {
        SCOPED_TRACE(testing::Message() << threads << " threads");
        const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
        HitBatch from_columns, from_rays;
        ASSERT_TRUE(trace_batch(s.world->accel, k, scattered.columns, max_hits, from_columns));
        ASSERT_TRUE(trace_batch(s.world->accel, k, s.rays, max_hits, from_rays));
        EXPECT_TRUE(bit_identical(want, from_columns));
        EXPECT_TRUE(bit_identical(want, from_rays));
      }
    }
}

TEST(RayColumns, OneValueForEveryRayEqualsThatValuePerRay) {
  Scene3 s = make_scene(2000);
  for (Ray& r : s.rays) r.tmin = 0.25, r.tmax = 2.5;
  ScatteredRays scattered(s.rays);
  scattered.columns.tmin = DoubleColumn::constant(0.25);
  scattered.columns.tmax = DoubleColumn::constant(2.5);
  for (KernelKind k : exact_kernels()) {
    SCOPED_TRACE(kernel_name(k));
    HitBatch from_columns;
    ASSERT_TRUE(trace_batch(s.world->accel, k, scattered.columns, 0, from_columns));
    EXPECT_TRUE(bit_identical(one_by_one(s.world->accel, k, s.rays, 0), from_columns));
  }
  // The defaults are the whole ray, as for Ray.
  RayColumns whole = scattered.columns;
  whole.tmin = RayColumns{}.tmin;
  whole.tmax = RayColumns{}.tmax;
  EXPECT_EQ(whole[7].tmin, Ray{}.tmin);
  EXPECT_EQ(whole[7].tmax, Ray{}.tmax);
}

TEST(RayColumns, CancelledBatchGivesUntracedRaysNoHits) {
  const Scene3 s = make_scene(20000);
  const ScatteredRays scattered(s.rays);
  HitBatch out;
  EXPECT_FALSE(trace_batch(s.world->accel, KernelKind::filter, scattered.columns, 0, out, {},
                           [](std::size_t, std::size_t) { return false; }));
  ASSERT_EQ(out.rays(), s.rays.size());
  EXPECT_LT(out.hits.size(), one_by_one(s.world->accel, KernelKind::filter, s.rays, 0).hits.size());
}

// The InputError of require_valid_rays, or "" if it accepted the rays.
std::string validation_error(std::span<const Ray> rays) {
  try {
    require_valid_rays(columns_of(rays));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RayColumns, ValidationNamesTheFirstBadRay) {
  std::vector<Ray> rays(40, Ray{{0, 0, 0}, {0, 0, 1}, 0.0, kInf});
  rays[3].tmin = -kInf;  // infinite bounds are fine
  EXPECT_EQ(validation_error(rays), "");
  EXPECT_FALSE(first_invalid_ray(columns_of(rays)));

  auto with = [&](std::size_t i, auto change) {
    std::vector<Ray> r = rays;
    change(r[i]);
    return validation_error(r);
  };
  EXPECT_EQ(with(17, [](Ray& r) { r.dir = {-0.0, 0.0, -0.0}; }), "ray 17: direction is zero");
  EXPECT_EQ(with(0, [](Ray& r) { r.org.y = kNaN; }), "ray 0: origin is not finite");
  EXPECT_EQ(with(39, [](Ray& r) { r.org.z = -kInf; }), "ray 39: origin is not finite");
  EXPECT_EQ(with(5, [](Ray& r) { r.dir.x = kInf; }), "ray 5: direction is not finite");
  EXPECT_EQ(with(6, [](Ray& r) { r.tmin = kNaN; }), "ray 6: tmin/tmax is NaN");
  EXPECT_EQ(with(7, [](Ray& r) { r.tmax = kNaN; }), "ray 7: tmin/tmax is NaN");
  // The first check that fails names the problem; the lowest index wins.
  EXPECT_EQ(with(8, [](Ray& r) { r.org.x = kNaN, r.dir = {}, r.tmax = kNaN; }), "ray 8: origin is not finite");
  rays[30].dir = {};
  rays[12].tmin = kNaN;
  const auto bad = first_invalid_ray(columns_of(rays));
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->ray, 12u);
  EXPECT_STREQ(bad->reason, "tmin/tmax is NaN");
}

}  // namespace
}  // namespace pierce::test
