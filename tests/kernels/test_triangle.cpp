// The watertight ray/triangle test and its symbolic tie rule, in float and double.
#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "test_util.h"

namespace pierce::test {
namespace {

template <typename T>
bool hit_triangle(const Ray& ray, Vec3d a, Vec3d b, Vec3d c, TriangleHit<T>& th) {
  const double scene_max_abs = std::max({max_abs(a), max_abs(b), max_abs(c)});
  const auto r = TraversalRay<T>::make(ray, scene_max_abs);
  if (!r.valid()) return false;
  return intersect(r, Vec3<T>(a), Vec3<T>(b), Vec3<T>(c), r.tmin, r.tmax, th);
}

// Independent reference in double: Möller-Trumbore without tie handling, for generic rays only.
struct MtHit {
  bool hit;
  double t, u, v;
  bool enter;
  double margin;  // smallest of u, v, 1-u-v, relative: how far the ray is from an edge
};

MtHit moller_trumbore(const Ray& r, Vec3d a, Vec3d b, Vec3d c) {
  const Vec3d e1 = b - a, e2 = c - a;
  const Vec3d p = cross(r.dir, e2);
  const double det = dot(e1, p);
  const Vec3d s = r.org - a;
  const double u = dot(s, p) / det;
  const Vec3d q = cross(s, e1);
  const double v = dot(r.dir, q) / det;
  const double t = dot(e2, q) / det;
  const double margin = std::min({std::abs(u), std::abs(v), std::abs(1 - u - v)});
  const bool inside = u >= 0 && v >= 0 && u + v <= 1 && t >= r.tmin && t <= r.tmax;
  return {inside, t, u, v, dot(r.dir, cross(e1, e2)) < 0, margin};
}

template <typename T>
class TriangleTest : public ::testing::Test {};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(TriangleTest, Precisions);

// Hit, miss and facing for triangles facing each axis, both windings, rays along +axis and -axis.
TYPED_TEST(TriangleTest, AxisRaysHitMissAndFacing) {
  using T = TypeParam;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0})
      for (bool flip : {false, true})
        for (double speed : {1.0, 0.25, 3.0}) {
          SCOPED_TRACE(testing::Message() << "axis " << axis << " sign " << sign << " flip " << flip);
          Vec3d a = on_plane(axis, 0.5, 0, 0), b = on_plane(axis, 0.5, 1, 0), c = on_plane(axis, 0.5, 0, 1);
          if (flip) std::swap(b, c);
          const Vec3d normal = cross(b - a, c - a);
          const Vec3d dir = axis_unit(axis, sign * speed);
          const bool expect_enter = dot(dir, normal) < 0;
          // Origin 2 units before the plane: t = 2 / speed.
          const Ray hit_ray{on_plane(axis, 0.5 - 2 * sign, 0.2, 0.3), dir};
          TriangleHit<T> th{};
          ASSERT_TRUE(hit_triangle<T>(hit_ray, a, b, c, th));
          EXPECT_NEAR(double(th.t), 2.0 / speed, 1e-5 * (2.0 / speed));
          EXPECT_EQ(th.enter, expect_enter);
          EXPECT_NEAR(double(th.u), flip ? 0.3 : 0.2, 1e-5);
          EXPECT_NEAR(double(th.v), flip ? 0.2 : 0.3, 1e-5);
          // Outside the triangle, beyond the hypotenuse and beyond each leg.
          for (auto [p, q] : {std::pair{0.6, 0.6}, std::pair{-0.1, 0.3}, std::pair{0.3, -0.1}}) {
            const Ray miss{on_plane(axis, 0.5 - 2 * sign, p, q), dir};
            EXPECT_FALSE(hit_triangle<T>(miss, a, b, c, th)) << p << ", " << q;
          }
          // The plane is behind the ray.
          const Ray away{on_plane(axis, 0.5 - 2 * sign, 0.2, 0.3), axis_unit(axis, -sign * speed)};
          EXPECT_FALSE(hit_triangle<T>(away, a, b, c, th));
          // The segment ends before / just after the plane.
          Ray short_ray = hit_ray;
          short_ray.tmax = 1.5 / speed;
          EXPECT_FALSE(hit_triangle<T>(short_ray, a, b, c, th));
          short_ray.tmax = 2.5 / speed;
          EXPECT_TRUE(hit_triangle<T>(short_ray, a, b, c, th));
          Ray late = hit_ray;
          late.tmin = 2.5 / speed;
          EXPECT_FALSE(hit_triangle<T>(late, a, b, c, th));
        }
}

// Generic rays against generic triangles agree with an independent double-precision test.
TYPED_TEST(TriangleTest, AgreesWithMollerTrumboreOnGenericRays) {
  using T = TypeParam;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int hits = 0, misses = 0, skipped = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3d a{U(rng), U(rng), U(rng)}, b{U(rng), U(rng), U(rng)}, c{U(rng), U(rng), U(rng)};
    const Vec3d af = as_float(a), bf = as_float(b), cf = as_float(c);
    Ray r{as_float(Vec3d{3 * U(rng), 3 * U(rng), 3 * U(rng)}), {}};
    r.dir = as_float(Vec3d{U(rng), U(rng), U(rng)} * 0.4 + (af + bf + cf) * (1.0 / 3) - r.org);
    if (i % 3 == 0) r.tmax = 0.5 + U(rng);
    const MtHit ref = moller_trumbore(r, af, bf, cf);
    const double normal_len = length(cross(bf - af, cf - af)) * length(r.dir);
    if (ref.margin < 1e-4 || std::abs(dot(r.dir, cross(bf - af, cf - af))) < 1e-3 * normal_len ||
        std::abs(ref.t - r.tmax) < 1e-4 * std::abs(ref.t) || std::abs(ref.t) < 1e-4) {
      ++skipped;  // too close to an edge, the plane, or a segment end for a tolerance comparison
      continue;
    }
    TriangleHit<T> th{};
    const bool hit = hit_triangle<T>(r, af, bf, cf, th);
    ASSERT_EQ(hit, ref.hit) << str(r) << " triangle " << i;
    if (!hit) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_NEAR(double(th.t), ref.t, 1e-4 * std::max(1.0, std::abs(ref.t)));
    EXPECT_NEAR(double(th.u), ref.u, 1e-3);
    EXPECT_NEAR(double(th.v), ref.v, 1e-3);
    EXPECT_EQ(th.enter, ref.enter);
  }
  EXPECT_GT(hits, 2000);
  EXPECT_GT(misses, 2000);
  EXPECT_LT(skipped, 4000);
}

// Direction with exact dyadic components whose largest magnitude is a power of two on a random
// axis and non-zero along `keep_axis`: with origin = point - 2*dir, the sheared coordinates of
// small dyadic vertices are exact, so edge functions through `point` are exactly zero.
Vec3d dyadic_direction(std::mt19937_64& rng, int keep_axis) {
  for (;;) {
    const int major = int(rng() % 3);
    Vec3d d;
    const double big = (rng() % 2 ? 1.0 : 2.0) * (rng() % 2 ? 1.0 : -1.0);
    for (int a = 0; a < 3; ++a)
      d[std::size_t(a)] = a == major ? big : double(int(rng() % 15) - 7) / 8.0 * std::abs(big);
    if (d[std::size_t(keep_axis)] != 0.0) return d;
  }
}

// Two coplanar triangles sharing an edge, as one consistently wound quad.
struct Quad {
  std::array<Vec3d, 4> p;
  std::array<Tri, 2> tris;
};

Quad make_quad(std::array<Vec3d, 4> p, bool diag02, bool flip) {
  Quad q{p, {}};
  q.tris = diag02 ? std::array<Tri, 2>{Tri{0, 1, 2}, Tri{0, 2, 3}} : std::array<Tri, 2>{Tri{0, 1, 3}, Tri{1, 2, 3}};
  if (flip)
    for (Tri& t : q.tris) std::swap(t[1], t[2]);
  return q;
}

template <typename T>
int count_hits(const Ray& r, const std::vector<Vec3d>& v, const std::vector<Tri>& tris, bool* enter = nullptr) {
  int n = 0;
  for (const Tri& t : tris) {
    TriangleHit<T> th{};
    if (hit_triangle<T>(r, v[t[0]], v[t[1]], v[t[2]], th)) {
      ++n;
      if (enter) *enter = th.enter;
    }
  }
  return n;
}

// A ray through the shared edge of two coplanar triangles crosses exactly one, for both diagonals,
// both windings, exact-zero edge functions (dyadic rays) and rays merely aimed at the edge.
TYPED_TEST(TriangleTest, SharedEdgeCountsOnce) {
  using T = TypeParam;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (bool diag02 : {true, false})
    for (bool flip : {false, true}) {
      SCOPED_TRACE(testing::Message() << "diag02 " << diag02 << " flip " << flip);
      const Quad q = make_quad({Vec3d{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, diag02, flip);
      const std::vector<Vec3d> v(q.p.begin(), q.p.end());
      const std::vector<Tri> tris(q.tris.begin(), q.tris.end());
      const Vec3d e0 = diag02 ? v[0] : v[1], e1 = diag02 ? v[2] : v[3];
      const Vec3d normal = cross(v[tris[0][1]] - v[tris[0][0]], v[tris[0][2]] - v[tris[0][0]]);
      for (int i = 0; i < 2000; ++i) {
        Ray r;
        if (i % 2 == 0) {
          const double s = double(1 + rng() % 63) / 64.0;  // exact point on the diagonal
          const Vec3d p = e0 + (e1 - e0) * s;
          r.dir = dyadic_direction(rng, 2);
          r.org = p - r.dir * 2.0;
        } else {
          const double s = 0.01 + 0.98 * U(rng);
          const Vec3d p = as_float(e0 + (e1 - e0) * s);
          r.org = as_float(Vec3d{4 * U(rng) - 1.5, 4 * U(rng) - 1.5, (U(rng) < 0.5 ? -1 : 1) * (0.1 + 2 * U(rng))});
          r.dir = p - r.org;
        }
        bool enter = false;
        ASSERT_EQ(count_hits<T>(r, v, tris, &enter), 1) << str(r);
        EXPECT_EQ(enter, dot(r.dir, normal) < 0);
      }
    }
  // The same in random tilted planes (vertices rounded to float, rays aimed at the diagonal).
  for (int plane = 0; plane < 200; ++plane) {
    const Vec3d c{U(rng) * 4 - 2, U(rng) * 4 - 2, U(rng) * 4 - 2};
    const Vec3d e1{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5};
    Vec3d e2 = cross(e1, Vec3d{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5});
    e2 = e2 * (length(e1) / length(e2));
    const Quad q = make_quad({as_float(c), as_float(c + e1), as_float(c + e1 + e2), as_float(c + e2)},
                             plane % 2 == 0, plane % 4 >= 2);
    const std::vector<Vec3d> v(q.p.begin(), q.p.end());
    const std::vector<Tri> tris(q.tris.begin(), q.tris.end());
    const Vec3d a = plane % 2 == 0 ? v[0] : v[1], b = plane % 2 == 0 ? v[2] : v[3];
    const Vec3d n = cross(e1, e2);
    for (int i = 0; i < 50; ++i) {
      const Vec3d p = as_float(a + (b - a) * (0.02 + 0.96 * U(rng)));
      Vec3d o = p + Vec3d{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5} * 3.0;
      if (std::abs(dot(p - o, n)) < 0.2 * length(p - o) * length(n)) o = o + n * (i % 2 ? 2.0 : -2.0);
      const Ray r{as_float(o), p - as_float(o)};
      ASSERT_EQ(count_hits<T>(r, v, tris), 1) << str(r) << " plane " << plane;
    }
  }
}

// A closed fan of k triangles around a vertex; a ray through the vertex crosses exactly one.
struct Fan {
  std::vector<Vec3d> v;  // v[0] is the centre
  std::vector<Tri> tris;
};

Fan make_fan(std::mt19937_64& rng, int k, Vec3d centre, Vec3d e1, Vec3d e2, bool flip, bool round_to_float) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<double> ang;
  for (;;) {  // random angles with every gap below pi, so every triangle turns the same way
    ang.clear();
    for (int i = 0; i < k; ++i) ang.push_back(U(rng) * 2 * std::numbers::pi);
    std::sort(ang.begin(), ang.end());
    double gap = ang.front() + 2 * std::numbers::pi - ang.back();
    for (int i = 1; i < k; ++i) gap = std::max(gap, ang[std::size_t(i)] - ang[std::size_t(i) - 1]);
    if (gap < 0.9 * std::numbers::pi) break;
  }
  Fan f;
  f.v.push_back(centre);
  for (double a : ang) {
    const double r = 0.3 + 0.7 * U(rng);
    Vec3d p = centre + e1 * (r * std::cos(a)) + e2 * (r * std::sin(a));
    f.v.push_back(round_to_float ? as_float(p) : p);
  }
  for (int i = 0; i < k; ++i) {
    Tri t{0, std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % k)};
    if (flip) std::swap(t[1], t[2]);
    f.tris.push_back(t);
  }
  return f;
}

TYPED_TEST(TriangleTest, SharedVertexOfFanCountsOnce) {
  using T = TypeParam;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int k = 3; k <= 64; ++k)
    for (int rep = 0; rep < 6; ++rep) {
      const bool flip = rep % 2 == 1;
      SCOPED_TRACE(testing::Message() << "k " << k << " rep " << rep);
      if (rep < 4) {
        // Fan in z = 0 around a dyadic centre; dyadic rays through the centre make every spoke's
        // edge function exactly zero.
        const Vec3d c{double(rng() % 64) / 64.0, double(rng() % 64) / 64.0, 0.0};
        const Fan f = make_fan(rng, k, c, {1, 0, 0}, {0, 1, 0}, flip, true);
        for (int i = 0; i < 40; ++i) {
          Ray r;
          r.dir = dyadic_direction(rng, 2);
          r.org = c - r.dir * 2.0;
          ASSERT_EQ(count_hits<T>(r, f.v, f.tris), 1) << str(r);
        }
      } else {
        // Fan in a random tilted plane; rays from random points aimed at the (float) centre.
        const Vec3d c = as_float(Vec3d{U(rng), U(rng), U(rng)});
        const Vec3d e1 = Vec3d{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5};
        Vec3d e2 = cross(e1, Vec3d{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5});
        const Vec3d a = e1 * (1.0 / length(e1)), b = e2 * (1.0 / length(e2));
        const Fan f = make_fan(rng, k, c, a, b, flip, true);
        const Vec3d n = cross(a, b);
        for (int i = 0; i < 40; ++i) {
          Vec3d o = c + Vec3d{U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5} * 4.0;
          if (std::abs(dot(c - o, n)) < 0.2 * length(c - o)) o = o + n * (i % 2 ? 2.0 : -2.0);
          const Ray r{as_float(o), c - as_float(o)};
          ASSERT_EQ(count_hits<T>(r, f.v, f.tris), 1) << str(r);
        }
      }
    }
}

// A ray lying in a triangle's plane never hits it, also through its vertices and along its edges.
TYPED_TEST(TriangleTest, RayInPlaneNeverHits) {
  using T = TypeParam;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int axis = 0; axis < 3; ++axis) {
    const Vec3d a = on_plane(axis, 0.25, 0, 0), b = on_plane(axis, 0.25, 1, 0), c = on_plane(axis, 0.25, 0, 1);
    for (int i = 0; i < 3000; ++i) {
      Vec3d through;
      switch (i % 4) {
        case 0: through = on_plane(axis, 0.25, 0.25 * (1 + U(rng)), 0.25 * (1 + U(rng))); break;  // interior
        case 1: through = (i / 4) % 3 == 0 ? a : ((i / 4) % 3 == 1 ? b : c); break;            // vertex
        case 2: through = on_plane(axis, 0.25, 0.5 + 0.5 * U(rng), 0); break;                      // edge
        default: through = on_plane(axis, 0.25, 0.5, 0.5); break;                                  // hypotenuse
      }
      Vec3d dir = on_plane(axis, 0.0, U(rng), U(rng));
      if (i % 7 == 0) dir = on_plane(axis, 0.0, 1.0, -1.0);  // along the hypotenuse
      if (i % 11 == 0) dir = on_plane(axis, 0.0, 1.0, 0.0);  // along a leg
      const Ray r{through - dir * 3.0, dir};
      for (bool flip : {false, true}) {
        TriangleHit<T> th{};
        EXPECT_FALSE(flip ? hit_triangle<T>(r, a, c, b, th) : hit_triangle<T>(r, a, b, c, th)) << str(r);
      }
    }
  }
}

// Zero-area triangles (after rounding to float) are marked by the scene, left out of the BVH and
// never reported by any kernel, even for rays straight through them.
TEST(Degenerate, MarkedExcludedAndNeverHit) {
  gen::Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {2, 2, 2}, {1, 1, 1}, {2, 0, 1e-50}, {0, 1, 0}, {0.5, 0.5, 0}};
  m.triangles = {
      {0, 1, 2},  // repeated vertex
      {0, 4, 3},  // collinear
      {0, 1, 5},  // collinear once 1e-50 rounds to 0 in float
      {0, 1, 6},  // a real triangle, to show the scene is otherwise hit
      {0, 0, 0},  // a point
      {1, 7, 6},  // collinear: on the real triangle's hypotenuse
  };
  const auto w = make_world({m});
  const Geometry& g = w->scene.geometry(0);
  const std::vector<std::uint8_t> want{1, 1, 1, 0, 1, 1};
  EXPECT_EQ(g.degenerate, want);
  EXPECT_EQ(w->scene.degenerate_count(), 5u);
  ASSERT_EQ(w->accel.bvh().tris.size(), 1u);
  EXPECT_EQ(w->accel.bvh().tris[0].prim, 3u);

  // Rays straight through each degenerate triangle's points, from many directions.
  std::vector<Ray> rays;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Vec3d targets[] = {{0.5, 0, 0}, {0.5, 0.5, 0.5}, {1.5, 0, 0}, {0, 0, 0}, {0.75, 0.25, 0}, {1, 0, 0}};
  for (const Vec3d& t : targets)
    for (int i = 0; i < 30; ++i) {
      const Vec3d dir{U(rng), U(rng), U(rng)};
      rays.push_back({t - dir * 3.0, dir});
    }
  for (KernelKind k : kAllKernels) {
    HitIterator it(w->accel, k);
    int real_hits = 0;
    for (const Ray& r : rays)
      for (const Hit& h : kernel_hits(it, r)) {
        EXPECT_EQ(h.prim, 3u) << kernel_name(k) << " " << str(r) << " hit " << str(h);
        ++real_hits;
      }
    EXPECT_GT(real_hits, 0) << kernel_name(k);
  }
}

}  // namespace
}  // namespace pierce::test
