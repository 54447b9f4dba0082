// Shotlines: partition rows with points, line of sight, obliquity and normal thickness; gaps and
// overlaps; CSG regions; rays starting inside a solid.
#include <gtest/gtest.h>

#include <cmath>

#include "csg_test_scenes.h"
#include "pierce/analysis/shotline.h"

namespace pierce::analysis {
namespace {

using csgtest::make_world;

std::vector<ShotRow> rows_of(const ShotResult& r, ShotKind kind) {
  std::vector<ShotRow> out;
  for (const ShotRow& row : r.rows)
    if (row.kind == kind) out.push_back(row);
  return out;
}

TEST(Shotline, PlateStackGivesOneRowPerPlateWithoutGaps) {
  auto w = make_world(gen::stacked_plates(20, 1.0, 0.1));
  const ShotResult r = shoot(w->accel, {Ray{{0.3, 0.4, -1}, {0, 0, 2}}});
  ASSERT_EQ(r.rows.size(), 20u);
  for (std::uint32_t i = 0; i < 20; ++i) {
    const ShotRow& row = r.rows[i];
    EXPECT_EQ(row.kind, ShotKind::solid);
    EXPECT_EQ(row.solids, std::vector<std::uint32_t>{i});
    EXPECT_NEAR(row.los, 0.1, 1e-6);  // t is in units of |dir| = 2; los is a length
    EXPECT_NEAR(row.in_point.z, 0.1 * i, 1e-6);
    EXPECT_DOUBLE_EQ(row.obliquity_in, 0.0);
    EXPECT_DOUBLE_EQ(row.obliquity_out, 0.0);
    EXPECT_NEAR(row.normal_thickness, 0.1, 1e-6);
    if (i > 0) {
      EXPECT_EQ(r.rows[i - 1].t_out, row.t_in);
    }
  }
  EXPECT_EQ(r.rays_hitting, 1u);
}

TEST(Shotline, ObliqueRayNormalThicknessIsThePlateThickness) {
  auto w = make_world({gen::box({-5, -5, 0}, {5, 5, 0.5}, "plate")});
  const double angle = 60.0 * 3.14159265358979323846 / 180.0;
  const ShotResult r = shoot(w->accel, {Ray{{0, 0, -1}, {std::sin(angle), 0, std::cos(angle)}}});
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_NEAR(r.rows[0].obliquity_in, 60.0, 1e-9);
  EXPECT_NEAR(r.rows[0].obliquity_out, 60.0, 1e-9);
  EXPECT_NEAR(r.rows[0].los, 1.0, 1e-6);  // 0.5 / cos 60
  EXPECT_NEAR(r.rows[0].normal_thickness, 0.5, 1e-6);
}

TEST(Shotline, GapsAndOverlapsAreListedInOrder) {
  // a [0,1], b [1.5,2.5] (gap 0.5), c [2.2,3] overlapping b by 0.3.
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1.5, 0, 0}, {2.5, 1, 1}, "b"),
                       gen::box({2.2, 0, 0}, {3, 1, 1}, "c")});
  const ShotResult r = shoot(w->accel, {Ray{{-1, 0.5, 0.5}, {1, 0, 0}}});
  std::vector<ShotKind> kinds;
  for (const ShotRow& row : r.rows) kinds.push_back(row.kind);
  EXPECT_EQ(kinds, (std::vector<ShotKind>{ShotKind::solid, ShotKind::gap, ShotKind::solid, ShotKind::overlap,
                                          ShotKind::solid}));
  ASSERT_EQ(r.rows.size(), 5u);
  EXPECT_NEAR(r.rows[1].los, 0.5, 1e-6);
  EXPECT_EQ(r.rows[1].solids, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_TRUE(std::isnan(r.rows[1].obliquity_in));
  EXPECT_NEAR(r.rows[3].los, 0.3, 1e-6);
  EXPECT_EQ(r.rows[3].solids, (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(r.rows[3].in_geom, 2u);   // c's face opens the overlap
  EXPECT_EQ(r.rows[3].out_geom, 1u);  // b's face closes it
}

TEST(Shotline, TouchingSolidsHaveNoGapRows) {
  auto w = make_world(gen::cube_grid(3));
  std::vector<Ray> rays;
  for (double y : {0.5, 1.0, 1.5, 2.0, 2.9})
    for (double z : {0.5, 1.0, 2.0}) rays.push_back(Ray{{-1, y, z}, {1, 0, 0}});
  const ShotResult r = shoot(w->accel, rays);
  EXPECT_TRUE(rows_of(r, ShotKind::gap).empty());
  EXPECT_TRUE(rows_of(r, ShotKind::overlap).empty());
  EXPECT_EQ(r.unmatched_leaves, 0u);
}

TEST(Shotline, CsgRegionsReplacePartitionsAndKeepOverlaps) {
  auto w = make_world({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({0.6, 0, 0}, {2, 1, 1}, "b")});
  const CsgExpr e = parse_csg("union(a, b)", w->scene);
  ShotOptions o;
  o.csg = &e;
  const ShotResult r = shoot(w->accel, {Ray{{-1, 0.5, 0.5}, {1, 0, 0}}}, o);
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_EQ(r.rows[0].kind, ShotKind::region);
  EXPECT_NEAR(r.rows[0].los, 2.0, 1e-6);
  EXPECT_EQ(r.rows[1].kind, ShotKind::overlap);
  EXPECT_NEAR(r.rows[1].los, 0.4, 1e-6);
}

TEST(Shotline, RayStartingInsideASolidStartsAtItsOrigin) {
  auto w = make_world({gen::box({0, 0, 0}, {2, 1, 1}, "a")});
  const ShotResult r = shoot(w->accel, {Ray{{0.5, 0.5, 0.5}, {1, 0, 0}}});
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_DOUBLE_EQ(r.rows[0].t_in, 0.0);
  EXPECT_NEAR(r.rows[0].los, 1.5, 1e-6);
  EXPECT_TRUE(std::isnan(r.rows[0].obliquity_in));
  EXPECT_TRUE(std::isnan(r.rows[0].normal_thickness));
  EXPECT_DOUBLE_EQ(r.rows[0].obliquity_out, 0.0);
}

}  // namespace
}  // namespace pierce::analysis
