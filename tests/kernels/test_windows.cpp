// Segments [tmin, tmax]: both ends inclusive, in the double values the caller gave. Windows that
// start or end exactly on a hit, exactly after or before one, empty, negative and whole-line
// windows, rays that start on a surface (thickness rays): every exact kernel returns the full-line
// hit list filtered by the window.
#include <cmath>
#include <limits>
#include <random>

#include "test_util.h"

namespace pierce::test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<Hit> in_window(const std::vector<Hit>& all, double lo, double hi) {
  std::vector<Hit> out;
  for (const Hit& h : all)
    if (h.t >= lo && h.t <= hi) out.push_back(h);
  return out;
}

// Windows around a ray's full-line hits: exact hit values, one double past them, empty, negative.
std::vector<std::pair<double, double>> windows_for(const std::vector<Hit>& all, std::mt19937_64& rng) {
  std::vector<std::pair<double, double>> w{{0.0, kInf}, {-kInf, kInf}, {-1.0, kInf}, {2.0, 1.0}};
  if (all.empty()) return w;
  std::uniform_int_distribution<std::size_t> pick(0, all.size() - 1);
  std::uniform_real_distribution<double> U(all.front().t - 1, all.back().t + 1);
  for (int k = 0; k < 4; ++k) {
    std::size_t i = pick(rng), j = pick(rng);
    if (i > j) std::swap(i, j);
    const double a = all[i].t, b = all[j].t;
    w.push_back({a, b});                                                    // ends exactly on hits
    w.push_back({a, a});                                                    // a single point
    w.push_back({std::nextafter(a, kInf), std::nextafter(b, -kInf)});       // just after / before them
    w.push_back({std::nextafter(a, -kInf), std::nextafter(b, kInf)});       // just around them
    w.push_back({0.0, b});                                                  // ray ends on a surface
    const double x = U(rng), y = U(rng);
    w.push_back({std::min(x, y), std::max(x, y)});
  }
  return w;
}

void check_windows(const std::vector<gen::Mesh>& meshes, const std::vector<Ray>& rays, std::uint64_t seed) {
  const auto w = make_world(meshes);
  std::mt19937_64 rng(seed);
  for (TieOrder tie : kTieOrders) {
    SCOPED_TRACE(tie_name(tie));
    const HitOrder order{tie};
    std::vector<Ray> wrays;
    std::vector<std::vector<Hit>> want;
    for (Ray r : rays) {
      r.tmin = -kInf, r.tmax = kInf;
      const auto all = reference_hits(w->scene, r, order);
      for (auto [lo, hi] : windows_for(all, rng)) {
        r.tmin = lo, r.tmax = hi;
        wrays.push_back(r);
        want.push_back(in_window(all, lo, hi));
        ASSERT_TRUE(same_hits(want.back(), reference_hits(w->scene, r, order))) << "reference, " << str(r);
      }
    }
    for (KernelKind k : exact_kernels()) {
      HitIterator it(w->accel, k, {order});
      int failures = 0;
      for (std::size_t i = 0; i < wrays.size() && failures < 3; ++i) {
        const auto same = same_hits(want[i], kernel_hits(it, wrays[i]));
        if (!same) ++failures;
        EXPECT_TRUE(same) << kernel_name(k) << " " << str(wrays[i]);
      }
    }
  }
}

TEST(Windows, PlatesIncludingThicknessRays) {
  const int n = 12;
  std::vector<Ray> rays;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(0.2, 0.8), D(-0.2, 0.2);
  for (int k = 0; k <= n; ++k) {
    rays.push_back({{U(rng), U(rng), k * 0.1}, {0, 0, k % 2 ? 1.0 : -1.0}});  // starts on plane k
    rays.push_back({{U(rng), U(rng), k * 0.1}, {D(rng), D(rng), k % 2 ? -1.0 : 1.0}});
  }
  for (int i = 0; i < 10; ++i) rays.push_back({{U(rng), U(rng), -1.0}, {D(rng), D(rng), 1.0}});
  check_windows(gen::stacked_plates(n), rays, 2);
}

TEST(Windows, SoupWithInsideOrigins) {
  std::vector<Ray> rays;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(0, 1), D(-1, 1);
  for (int i = 0; i < 30; ++i) rays.push_back({{U(rng), U(rng), U(rng)}, {D(rng), D(rng), D(rng)}});
  check_windows({gen::random_soup(600, 0.2, 4)}, rays, 5);
}

// Rays starting exactly on a vertex of a closed mesh see that vertex's surface at t = 0.
TEST(Windows, BlobFromItsOwnVertices) {
  const gen::Mesh blob = gen::blob(3, 11);
  std::vector<Ray> rays;
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> D(-1, 1);
  for (int i = 0; i < 30; ++i) {
    // Inwards, well away from the tangent plane (the blob is star-shaped around the origin).
    const Vec3d v = as_float(blob.vertices[rng() % blob.vertices.size()]);
    rays.push_back({v, v * (-1.0 / length(v)) + Vec3d{D(rng), D(rng), D(rng)} * 0.3});
  }
  check_windows({blob}, rays, 7);
  // Each one enters the surface it starts on at t = 0 and leaves it once more, farther on.
  const auto w = make_world({blob});
  for (const Ray& r : rays) {
    const auto hits = reference_hits(w->scene, r, {});
    ASSERT_FALSE(hits.empty()) << str(r);
    EXPECT_EQ(hits.front().t, 0.0) << str(r);
    EXPECT_TRUE(hits.front().enter) << str(r);
    EXPECT_FALSE(hits.back().enter) << str(r);
    EXPECT_EQ(hits.size() % 2, 0u) << str(r);
  }
}

}  // namespace
}  // namespace pierce::test
