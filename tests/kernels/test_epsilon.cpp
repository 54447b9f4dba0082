// The epsilon baseline is documented as inexact: on touching and duplicated coplanar faces it must
// actually miss or repeat crossings that the construction (and every exact kernel) counts.
#include <limits>
#include <map>
#include <random>

#include "pierce/embree_accel.h"
#include "test_util.h"

namespace pierce::test {
namespace {

// Crossings per (geom, prim): a miss shows as a lower count, a repeat as a count above one.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> tally(const std::vector<Hit>& hits) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> m;
  for (const Hit& h : hits) ++m[{h.geom, h.prim}];
  return m;
}

// embree_first_hit is `epsilon`'s first hit, and gives none for rays Embree cannot take.
TEST(Epsilon, EmbreeFirstHitIsEpsilonsFirstHit) {
  const auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1})});
  const EmbreeAccel& acc = w->accel.embree();
  HitIterator eps(w->accel, KernelKind::epsilon);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-0.2, 1.2), D(-1, 1);
  int hits = 0;
  for (int i = 0; i < 100; ++i) {
    const Ray r{{U(rng), U(rng), -1.0}, {D(rng), D(rng), 1}};
    const auto want = kernel_hits(eps, r);
    Hit got;
    ASSERT_EQ(embree_first_hit(acc, r, got), !want.empty()) << str(r);
    if (want.empty()) continue;
    ++hits;
    EXPECT_EQ(got.t, want.front().t) << str(r);
    EXPECT_EQ(got.geom, want.front().geom);
    EXPECT_EQ(got.prim, want.front().prim);
    EXPECT_EQ(got.enter, want.front().enter);
  }
  EXPECT_GT(hits, 20);
  Hit h;
  const Vec3d inside{0.5, 0.5, 0.5};
  EXPECT_FALSE(embree_first_hit(acc, {inside, {0, 0, 0}}, h)) << "zero direction";
  EXPECT_FALSE(embree_first_hit(acc, {inside, {0, 0, 1}, 0.0, std::numeric_limits<double>::quiet_NaN()}, h))
      << "NaN tmax";
  EXPECT_FALSE(embree_first_hit(acc, {inside, {0, 0, 1}, 1.0, 0.5}, h)) << "empty range";
  EXPECT_FALSE(embree_first_hit(acc, {inside, {0, 0, 1}, -2.0, -1.0}, h)) << "range behind the origin";
  EXPECT_TRUE(embree_first_hit(acc, {inside, {0, 0, 1}}, h));
  EXPECT_NEAR(h.t, 0.5, 0x1p-20);  // Embree's float intersector: exact to float rounding
}

TEST(Epsilon, MissesCrossingsOfTouchingPlates) {
  const int n = 10;
  const auto w = make_world(gen::stacked_plates(n));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(0.1, 0.9), D(-0.05, 0.05);
  HitIterator eps(w->accel, KernelKind::epsilon);
  HitIterator exact(w->accel, KernelKind::restart);
  int rays = 0;
  for (int i = 0; i < 50; ++i) {
    const Vec3d dir = i % 2 ? Vec3d{0, 0, 1} : Vec3d{D(rng), D(rng), 1};
    const Ray r{{U(rng), U(rng), -1.0}, dir};
    ASSERT_EQ(kernel_hits(exact, r).size(), std::size_t(2 * n)) << str(r);  // the construction's count
    const auto got = kernel_hits(eps, r);
    // Each of the n-1 shared planes holds two crossings at one t; a relaunch from t + epsilon
    // can keep at most one of them.
    EXPECT_LT(got.size(), std::size_t(2 * n)) << str(r);
    EXPECT_LE(got.size(), std::size_t(n + 1)) << str(r);
    ++rays;
  }
  EXPECT_EQ(rays, 50);
}

TEST(Epsilon, MissesOrRepeatsDuplicatedFaces) {
  for (bool alternate : {false, true}) {
    SCOPED_TRACE(alternate ? "alternate winding" : "same winding");
    const int copies = 6;
    const auto w = make_world({gen::duplicated(gen::box({0, 0, 0}, {1, 1, 1}), copies, alternate)});
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> U(0.3, 0.7), D(-0.1, 0.1);  // stays inside the box
    HitIterator eps(w->accel, KernelKind::epsilon);
    HitIterator exact(w->accel, KernelKind::queue);
    int wrong = 0;
    for (int i = 0; i < 50; ++i) {
      const Ray r{{U(rng), U(rng), -1.0}, {D(rng), D(rng), 1}};
      const auto want = kernel_hits(exact, r);
      ASSERT_EQ(want.size(), std::size_t(2 * copies)) << str(r);
      const auto want_tally = tally(want);
      const auto got_tally = tally(kernel_hits(eps, r));
      EXPECT_NE(got_tally, want_tally) << "epsilon found every duplicated crossing exactly once: " << str(r);
      wrong += got_tally != want_tally;
    }
    EXPECT_EQ(wrong, 50);
  }
}

// Its errors are real, not an artefact of how hits are compared: on generic rays through a soup,
// away from coplanar faces, it agrees with the exact kernels.
TEST(Epsilon, AgreesOnGenericRays) {
  const auto w = make_world({gen::blob(3, 5)});
  HitIterator eps(w->accel, KernelKind::epsilon);
  HitIterator exact(w->accel, KernelKind::filter);
  int same = 0;
  const auto rays = random_rays(w->scene.bounds(), 200, 9);
  for (const Ray& r : rays) same += tally(kernel_hits(eps, r)) == tally(kernel_hits(exact, r));
  EXPECT_GT(same, 190);
}

// A triangle whose float corners lie exactly on one line has no area and is never hit (Pierce's
// degenerate flag), but Embree's test of it, on rounded edges, can accept rays passing near the
// line. The epsilon kernel leaves such triangles out of its Embree scene, keeping every other id.
TEST(Epsilon, NeverReportsDegenerateTriangles) {
  // Corners on the line s * (1, 2, 3), far apart in magnitude: Embree's float edges round differently
  // per axis (tiny is 0.75 ulp of 1000), so its normal is not zero.
  const float tiny = 0x1.8p-15f;
  std::vector<Vec3d> v = {{-1e6, -1e6, 1e4},   {1e6, -1e6, 1e4},   {0, 1e6, 1e4},
                          {tiny, 2 * tiny, 3 * tiny}, {1000, 2000, 3000}, {3000, 6000, 9000},
                          {-1e6, -1e6, -1e4},  {1e6, -1e6, -1e4},  {0, 1e6, -1e4}};
  Scene built;
  built.add_mesh(v, {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
  const auto w = std::make_unique<World>(std::move(built));
  const Scene& scene = w->scene;
  ASSERT_TRUE(scene.geometry(0).degenerate[1]);
  // Rays from above through points of the line, down to the plane z = -1e4 (prim 2).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> S(1100.0, 2900.0), D(-1.0, 1.0), E(-3e-4, 3e-4);
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) {
    const double s = S(rng);
    const Vec3d q{s + E(rng), 2 * s + E(rng), 3 * s + E(rng)}, d{D(rng), D(rng), -1.0};
    rays.push_back(Ray{q - d * 10.0, d});
  }
  // Plain Embree on the same triangles does hit the degenerate one: the case is real.
  RTCDevice device = rtcNewDevice("threads=1");
  RTCScene plain = rtcNewScene(device);
  attach_native_triangles(device, plain, scene, DegenerateTriangles::keep);
  rtcCommitScene(plain);
  int plain_hits_on_line = 0;
  for (const Ray& r : rays) {
    RTCRayHit rh = native_rayhit(r.org, r.dir, 0.f, std::numeric_limits<float>::infinity());
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(plain, &ctx, &rh);
    plain_hits_on_line += rh.hit.geomID == 0 && rh.hit.primID == 1;
  }
  rtcReleaseScene(plain);
  rtcReleaseDevice(device);
  EXPECT_GT(plain_hits_on_line, 0) << plain_hits_on_line;

  HitIterator eps(w->accel, KernelKind::epsilon);
  for (const Ray& r : rays) {
    const auto got = kernel_hits(eps, r);
    ASSERT_EQ(got.size(), 1u) << str(r);
    EXPECT_EQ(got[0].prim, 2u) << str(r);
  }
}

// A kernel builds only what it uses: the epsilon kernel traces Embree's native triangles
// and needs neither the exact Embree scene nor the float binary BVH whose triangles that scene
// holds; an exact Embree kernel builds both. Accel::memory_bytes counts the binary BVH once built.
TEST(Epsilon, BuildsNeitherTheExactSceneNorItsBvh) {
  const auto w = make_world({gen::blob(3, 5)});
  const std::size_t wide_only = w->accel.memory_bytes();
  const auto rays = random_rays(w->scene.bounds(), 20, 3);
  HitIterator eps(w->accel, KernelKind::epsilon);
  std::size_t hits = 0;
  for (const Ray& r : rays) hits += kernel_hits(eps, r).size();
  EXPECT_GT(hits, 0u);
  EXPECT_EQ(w->accel.memory_bytes(), wide_only);
  HitIterator exact(w->accel, KernelKind::embree_restart);
  for (const Ray& r : rays) kernel_hits(exact, r);
  EXPECT_GT(w->accel.memory_bytes(), wide_only);
}

}  // namespace
}  // namespace pierce::test
