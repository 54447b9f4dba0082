// The oracle against hand-computed answers, independent of the kernels: if these pass, the
// property tests compare the kernels with the documented convention, not with themselves.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "oracle.h"
#include "pierce/generators.h"

namespace pierce::oracle {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Scene one_mesh(std::vector<Vec3d> v, std::vector<Tri> t) {
  Scene s;
  s.add_mesh(std::move(v), std::move(t));
  return s;
}

TEST(ExactArithmetic, SumsAndProductsAreExact) {
  const Exact a(1.0), tiny(std::ldexp(1.0, -80)), big(std::ldexp(1.0, 80));
  EXPECT_EQ(((a + tiny) - a).sign(), 1);          // 1 + 2^-80 - 1 > 0: a double would give 0
  EXPECT_EQ(compare((a + tiny) * (a - tiny), a), -1);  // 1 - 2^-160 < 1
  EXPECT_EQ(compare(big * tiny, a), 0);
  EXPECT_EQ(Exact(-3.5).sign(), -1);
  EXPECT_TRUE(Exact(0.0).is_zero());
  EXPECT_EQ(Exact(0.1).to_double(), 0.1);
  const ExactRatio third{Exact(1.0), Exact(3.0)}, two_sixths{Exact(2.0), Exact(6.0)};
  EXPECT_EQ(compare(third, two_sixths), 0);
  EXPECT_EQ(compare(ExactRatio{Exact(-1.0), Exact(-3.0)}, two_sixths), 0);
  EXPECT_EQ(third.compare_to(Exact(0.5)), -1);
}

TEST(Oracle, SingleTriangleHitAndT) {
  const Scene s = one_mesh({{0, 0, 2}, {1, 0, 2}, {0, 1, 2}}, {{0, 1, 2}});
  const Oracle<float> o(s);
  const OracleResult r = o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 0, kInf});
  ASSERT_EQ(r.hits.size(), 1u);
  EXPECT_EQ(r.hits[0].t.compare_to(Exact(2.0)), 0);
  EXPECT_FALSE(r.hits[0].enter);  // normal (1,0,0) x (0,1,0) = +z, ray along it: leaving
  EXPECT_TRUE(o.trace({{0.75, 0.75, 0}, {0, 0, 1}, 0, kInf}).hits.empty());
  // Direction scale: t halves when the direction doubles.
  const OracleResult r2 = o.trace({{0.25, 0.25, 0}, {0, 0, 2}, 0, kInf});
  ASSERT_EQ(r2.hits.size(), 1u);
  EXPECT_EQ(r2.hits[0].t.compare_to(Exact(1.0)), 0);
}

TEST(Oracle, FacingFollowsTheNormal) {
  // Normal (v1 - v0) x (v2 - v0) = +z. Enter = direction against the normal.
  const Scene s = one_mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});
  const Oracle<double> o(s);
  const OracleResult down = o.trace({{0.25, 0.25, 2}, {0, 0, -1}, 0, kInf});
  const OracleResult up = o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 0, kInf});
  ASSERT_EQ(down.hits.size(), 1u);
  ASSERT_EQ(up.hits.size(), 1u);
  EXPECT_TRUE(down.hits[0].enter);
  EXPECT_FALSE(up.hits[0].enter);
}

TEST(Oracle, SharedEdgeCountsOnce) {
  // Unit square split along its diagonal; rays through the diagonal, from both sides, both ways.
  const Scene s = one_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  const Oracle<float> o(s);
  for (const double z : {-1.0, 1.0})
    for (const double p : {0.25, 0.5, 0.75}) {
      const OracleResult r = o.trace({{p, p, z}, {0, 0, -z}, 0, kInf});
      EXPECT_EQ(r.hits.size(), 1u) << p << " " << z;
    }
  // Tilted rays through the diagonal's midpoint: still exactly one.
  for (const Vec3d d : {Vec3d{0.5, 0.25, 1}, Vec3d{-0.25, 0.75, 1}, Vec3d{0.5, -0.5, -1}}) {
    const Ray r{Vec3d{0.5, 0.5, 0} - d * 2.0, d, 0, kInf};
    EXPECT_EQ(o.trace(r).hits.size(), 1u);
  }
}

TEST(Oracle, VertexOfAFanCountsOnce) {
  // 8 triangles around the origin, both windings mixed: a ray through the centre crosses one.
  std::vector<Vec3d> v = {{0, 0, 0}};
  const double ring[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  for (const auto& p : ring) v.push_back({p[0], p[1], 0});
  std::vector<Tri> t;
  for (std::uint32_t i = 0; i < 8; ++i) {
    const std::uint32_t a = 1 + i, b = 1 + (i + 1) % 8;
    t.push_back(i % 3 == 0 ? Tri{0, b, a} : Tri{0, a, b});
  }
  const Oracle<float> o(one_mesh(v, t));
  for (const Vec3d d : {Vec3d{0, 0, 1}, Vec3d{0, 0, -1}, Vec3d{0.25, 0.5, 1}, Vec3d{-0.75, 0.25, -1}, Vec3d{1, 0.5, 0.25}})
    EXPECT_EQ(o.trace({Vec3d{0, 0, 0} - d * 4.0, d, 0, kInf}).hits.size(), 1u);
}

TEST(Oracle, ClosedBoxThroughEdgesAndVertices) {
  // A ray through a closed box's edge or vertex enters once and leaves once (or misses).
  const gen::Mesh b = gen::box({0, 0, 0}, {1, 1, 1});
  const Oracle<float> o(gen::to_scene({b}));
  int through = 0;
  for (const Vec3d p : {Vec3d{0, 0, 0.5}, Vec3d{1, 1, 0.5}, Vec3d{0, 0, 0}, Vec3d{1, 0, 1}, Vec3d{0.5, 0, 0}})
    for (const Vec3d d : {Vec3d{0.5, 0.25, 1}, Vec3d{1, -0.75, 0.5}, Vec3d{-0.25, -1, 0.5}}) {
      const OracleResult r = o.trace({p - d * 4.0, d, 0, kInf});
      ASSERT_TRUE(r.hits.size() == 0 || r.hits.size() == 2) << r.hits.size();
      if (r.hits.size() == 2) {
        ++through;
        // One entering and one leaving crossing. Where the ray clips an edge or corner both are
        // at the same t, so their order is the tie order, not "enter first".
        EXPECT_NE(r.hits[0].enter, r.hits[1].enter);
      }
    }
  EXPECT_GT(through, 0);
}

TEST(Oracle, RayInThePlaneNeverHits) {
  const Scene s = one_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  const Oracle<float> o(s);
  EXPECT_TRUE(o.trace({{-1, 0.25, 0}, {1, 0, 0}, 0, kInf}).hits.empty());
  EXPECT_TRUE(o.trace({{-1, 0, 0}, {1, 0, 0}, 0, kInf}).hits.empty());  // along an edge
}

TEST(Oracle, DegenerateTrianglesNeverHit) {
  const Scene s = one_mesh({{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 0, 3}, {1, 1, 1}});
  const Oracle<float> o(s);
  for (const Vec3d p : {Vec3d{1, 1, 1}, Vec3d{0, 0.5, 1}, Vec3d{0, 0, 1}})
    EXPECT_TRUE(o.trace({p, {0, 0, -1}, 0, kInf}).hits.empty());
}

TEST(Oracle, SegmentEndsAreInclusive) {
  const Scene s = one_mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});
  const Oracle<float> o(s);
  EXPECT_EQ(o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 0, 1}).hits.size(), 1u);          // ends on it
  EXPECT_EQ(o.trace({{0.25, 0.25, 1}, {0, 0, 1}, 0, kInf}).hits.size(), 1u);       // starts on it
  EXPECT_EQ(o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 1, 1}).hits.size(), 1u);          // point segment
  EXPECT_TRUE(o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 0, std::nextafter(1.0f, 0.f)}).hits.empty());
  EXPECT_TRUE(o.trace({{0.25, 0.25, 0}, {0, 0, 1}, std::nextafter(1.0f, 2.f), kInf}).hits.empty());
  EXPECT_EQ(o.trace({{0.25, 0.25, 2}, {0, 0, 1}, -kInf, kInf}).hits.size(), 1u);   // behind, full line
}

TEST(Oracle, OrderIsExactThenByIds) {
  // Two coincident faces (different geometries) and one 1 ulp above: exact t decides, then ids.
  Scene s;
  const double up = double(std::nextafter(1.0f, 2.f));
  s.add_mesh({{0, 0, up}, {1, 0, up}, {0, 1, up}}, {{0, 1, 2}});
  s.add_mesh({{0, 0, 1}, {0, 1, 1}, {1, 0, 1}}, {{0, 1, 2}});  // normal -z: the +z ray enters
  s.add_mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});  // normal +z: the +z ray leaves
  const Oracle<float> o(s);
  const OracleResult r = o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 0, kInf});
  ASSERT_EQ(r.hits.size(), 3u);
  EXPECT_EQ(r.hits[0].geom, 1u);
  EXPECT_EQ(r.hits[1].geom, 2u);
  EXPECT_EQ(r.hits[2].geom, 0u);
  const OracleResult lbe = o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 0, kInf}, {TieOrder::leave_before_enter});
  ASSERT_EQ(lbe.hits.size(), 3u);
  EXPECT_EQ(lbe.hits[0].geom, 2u);
  EXPECT_EQ(lbe.hits[1].geom, 1u);
  EXPECT_EQ(lbe.hits[2].geom, 0u);
}

TEST(Oracle, FloatAndDoubleSeeDifferentInput) {
  // Two faces one double ulp apart: coplanar in float, ordered by t in double.
  Scene s;
  const double up = std::nextafter(1.0, 2.0);
  s.add_mesh({{0, 0, up}, {1, 0, up}, {0, 1, up}}, {{0, 1, 2}});
  s.add_mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});
  const Ray r{{0.25, 0.25, 0}, {0, 0, 1}, 0, kInf};
  const OracleResult f = Oracle<float>(s).trace(r), d = Oracle<double>(s).trace(r);
  ASSERT_EQ(f.hits.size(), 2u);
  ASSERT_EQ(d.hits.size(), 2u);
  EXPECT_EQ(f.hits[0].geom, 0u);  // tie in float: by id
  EXPECT_EQ(d.hits[0].geom, 1u);  // exact order in double
}

TEST(Oracle, InvalidRaysAndEmptyScenesHaveNoHits) {
  const Scene s = one_mesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});
  const Oracle<float> o(s);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.trace({{0.25, 0.25, 0}, {0, 0, 0}, 0, kInf}).ray_valid);
  EXPECT_FALSE(o.trace({{nan, 0.25, 0}, {0, 0, 1}, 0, kInf}).ray_valid);
  EXPECT_FALSE(o.trace({{0.25, 0.25, 0}, {0, kInf, 1}, 0, kInf}).ray_valid);
  EXPECT_FALSE(o.trace({{0.25, 0.25, 1e300}, {0, 0, -1}, 0, kInf}).ray_valid);  // inf in float
  EXPECT_TRUE(o.trace({{0.25, 0.25, 0}, {0, 0, 1}, nan, kInf}).hits.empty());
  EXPECT_TRUE(o.trace({{0.25, 0.25, 0}, {0, 0, 1}, 3, 2}).hits.empty());
  EXPECT_TRUE(Oracle<float>(Scene{}).trace({{0, 0, 0}, {0, 0, 1}, 0, kInf}).hits.empty());
}

TEST(Oracle, OutsideTheExactClassIsReported) {
  // A ray through the diagonal of a square, but with a direction whose shear rounds: the
  // kernel's view may put the diagonal on either side. The oracle must flag or agree.
  const Scene s = one_mesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  const Oracle<float> o(s);
  int flagged = 0;
  for (int i = 1; i < 200; ++i) {
    const Vec3d d{0.1 * i / 200.0, 0.3 / 7.0, 1};
    const Ray r{Vec3d{0.5, 0.5, 0} - d * 3.0, d, 0, kInf};
    const OracleResult res = o.trace(r);
    EXPECT_EQ(res.hits.size(), 1u);
    flagged += !res.outside.empty();
    for (const auto& x : res.outside) EXPECT_TRUE(x.view_known);
  }
  EXPECT_GT(flagged, 0);  // the shear's rounding does cross the diagonal for some of these rays
}

}  // namespace
}  // namespace pierce::oracle
