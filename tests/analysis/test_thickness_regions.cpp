// Thin and thick walls as regions: pocket floors of known thickness, position and area.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "../common/test_world.h"
#include "pocket_block.h"
#include "pierce/analysis/mesh_topology.h"
#include "pierce/analysis/thickness.h"

namespace pierce::test {
namespace {

using analysis::compute_thickness;
using analysis::SampleAt;
using analysis::ThicknessOptions;
using analysis::ThicknessRegion;
using analysis::ThicknessResult;

constexpr Vec3d kBlock{40, 30, 10};
// Floors of 0.5 and 1.0 (thin under 1.5), one of exactly 1.5 (not thin) and one of 2.0; the
// walls between pockets and sides are 4 thick.
const std::vector<Pocket> kPockets{{4, 12, 4, 10, 0.5}, {16, 24, 4, 10, 1.0}, {28, 36, 4, 10, 2.0}, {16, 24, 16, 26, 1.5}};
constexpr double kPocketArea = 8 * 6;

// Every sample's region id agrees with its flag, and each region with its samples (sample
// points: per vertex, coincident vertices once).
void check_ids(const ThicknessResult& r, const ThicknessOptions& o, const Scene& scene) {
  const std::size_t thin = r.thin_regions.size();
  std::vector<std::size_t> count(thin + r.thick_regions.size(), 0);
  std::vector<double> extreme(count.size(), std::numeric_limits<double>::quiet_NaN());
  ASSERT_EQ(r.region.size(), r.size());
  std::vector<std::vector<std::uint32_t>> weld(scene.geometries().size());
  if (o.per == SampleAt::vertex)
    for (std::size_t g = 0; g < weld.size(); ++g) weld[g] = analysis::weld_by_position(scene.geometry(std::uint32_t(g)).vertices);
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double t = r.thickness[i];
    const bool is_thin = std::isfinite(t) && t < o.min_thickness;
    const bool is_thick = std::isfinite(t) && t > o.max_thickness;
    const std::int32_t id = r.region[i];
    if (!is_thin && !is_thick) {
      EXPECT_EQ(id, -1) << "sample " << i << " thickness " << t;
      continue;
    }
    ASSERT_GE(id, 0) << "sample " << i;
    ASSERT_LT(std::size_t(id), count.size());
    EXPECT_EQ(is_thin, std::size_t(id) < thin) << "sample " << i;
    const ThicknessRegion& reg = is_thin ? r.thin_regions[std::size_t(id)] : r.thick_regions[std::size_t(id) - thin];
    EXPECT_EQ(reg.solid, r.solid[i]);
    EXPECT_EQ(reg.thick, is_thick);
    if (is_thin) {
      EXPECT_GE(t, reg.thickness);
    } else {
      EXPECT_LE(t, reg.thickness);
    }
    const std::uint32_t v = r.element[i];
    count[std::size_t(id)] += o.per == SampleAt::face || weld[r.solid[i]][v] == v;
    double& e = extreme[std::size_t(id)];
    if (std::isnan(e) || (is_thin ? t < e : t > e)) e = t;
  }
  for (std::size_t k = 0; k < count.size(); ++k)
    EXPECT_EQ(extreme[k], k < thin ? r.thin_regions[k].thickness : r.thick_regions[k - thin].thickness);
  for (std::size_t k = 0; k < count.size(); ++k)
    EXPECT_EQ(count[k], k < thin ? r.thin_regions[k].samples : r.thick_regions[k - thin].samples);
  for (std::size_t k = 1; k < thin; ++k) EXPECT_LE(r.thin_regions[k - 1].thickness, r.thin_regions[k].thickness);
  for (std::size_t k = 1; k < r.thick_regions.size(); ++k)
    EXPECT_GE(r.thick_regions[k - 1].thickness, r.thick_regions[k].thickness);
}

// The region is the floor of pocket p: its thinnest sample lies on the floor or under it, its
// exit on the other side, its minimum the floor's thickness, its area both sides within 10 %.
void expect_floor(const ThicknessRegion& reg, const Pocket& p, double area_tol) {
  EXPECT_NEAR(reg.thickness, p.floor, 1e-9 * p.floor);
  for (const Vec3d& q : {reg.point, reg.exit}) {
    EXPECT_GE(q.x, p.x0 - 1e-9);
    EXPECT_LE(q.x, p.x1 + 1e-9);
    EXPECT_GE(q.y, p.y0 - 1e-9);
    EXPECT_LE(q.y, p.y1 + 1e-9);
  }
  EXPECT_NEAR(std::abs(reg.point.z - reg.exit.z), p.floor, 1e-9);
  EXPECT_NEAR(reg.area, 2 * kPocketArea, area_tol * 2 * kPocketArea);
  EXPECT_TRUE(reg.faces.empty());  // a mesh
}

class PocketFloors : public ::testing::TestWithParam<SampleAt> {
 protected:
  // The test's sampling, thin below min_thickness, thick above max_thickness.
  ThicknessOptions options(double min_thickness, double max_thickness = std::numeric_limits<double>::infinity()) const {
    ThicknessOptions o;
    o.per = GetParam();
    o.min_thickness = min_thickness;
    o.max_thickness = max_thickness;
    return o;
  }
};

TEST_P(PocketFloors, EachThinFloorIsOneRegionWithItsMinimumAndArea) {
  const auto world = make_world({pocket_block(kBlock, kPockets, 1.0)});
  ThicknessOptions o = options(1.5);
  const ThicknessResult r = compute_thickness(world->accel, o);
  check_ids(r, o, world->scene);
  ASSERT_EQ(r.thin_regions.size(), 2u);  // floors 0.5 and 1.0; not 1.5 (exactly T) nor 2.0
  expect_floor(r.thin_regions[0], kPockets[0], 0.10);
  expect_floor(r.thin_regions[1], kPockets[1], 0.10);
  EXPECT_TRUE(r.thick_regions.empty());
}

TEST_P(PocketFloors, FineMeshAreaComesFromTheSamples) {
  // Grid steps of 0.2, below the finest refinement of a 10-wide floor: no rays are traced for
  // the area, the samples share out their triangles.
  const auto world = make_world({pocket_block(kBlock, kPockets, 0.2)});
  ThicknessOptions o = options(1.5);
  const ThicknessResult r = compute_thickness(world->accel, o);
  check_ids(r, o, world->scene);
  ASSERT_EQ(r.thin_regions.size(), 2u);
  expect_floor(r.thin_regions[0], kPockets[0], 0.10);
  expect_floor(r.thin_regions[1], kPockets[1], 0.10);
}

TEST_P(PocketFloors, AWallOfExactlyTheThresholdIsNotThin) {
  const auto world = make_world({pocket_block(kBlock, kPockets, 1.0)});
  ThicknessOptions o = options(1.0);  // the second floor is exactly 1.0
  const ThicknessResult r = compute_thickness(world->accel, o);
  check_ids(r, o, world->scene);
  ASSERT_EQ(r.thin_regions.size(), 1u);
  expect_floor(r.thin_regions[0], kPockets[0], 0.10);
}

TEST_P(PocketFloors, CoarseMeshAreaIsRefined) {
  // The bottom is two 40 x 30 triangles: the floor's underside is found by refinement only.
  const auto world = make_world({coarse_pocket_block(kBlock, kPockets[0])});
  ThicknessOptions o = options(1.5);
  const ThicknessResult r = compute_thickness(world->accel, o);
  check_ids(r, o, world->scene);
  ASSERT_EQ(r.thin_regions.size(), 1u);
  const ThicknessRegion& reg = r.thin_regions[0];
  EXPECT_NEAR(reg.area, 2 * kPocketArea, 0.10 * 2 * kPocketArea);
  // Per vertex the floor's only samples are its corners, whose rays run diagonally.
  // Per vertex the ray runs along the corner's averaged normal, exact to its rounding only.
  if (o.per == SampleAt::face) {
    EXPECT_NEAR(reg.thickness, 0.5, 1e-9);
  } else {
    EXPECT_NEAR(reg.thickness, 0.5 * std::sqrt(3.0), 1e-6);
  }
}

TEST_P(PocketFloors, ThickRegionsAboveMax) {
  const auto world = make_world({pocket_block(kBlock, kPockets, 1.0)});
  ThicknessOptions o = options(1.5, 5);
  const ThicknessResult r = compute_thickness(world->accel, o);
  check_ids(r, o, world->scene);
  ASSERT_EQ(r.thin_regions.size(), 2u);
  ASSERT_FALSE(r.thick_regions.empty());
  double max_t = 0;
  for (std::size_t i = 0; i < r.size(); ++i)
    if (std::isfinite(r.thickness[i])) max_t = std::max(max_t, r.thickness[i]);
  EXPECT_EQ(r.thick_regions[0].thickness, max_t);
  // Per face the longest ray crosses the block along x under the floors, at the sides' bottom.
  if (o.per == SampleAt::face) {
    EXPECT_NEAR(r.thick_regions[0].thickness, 40, 40e-9);
  }
  for (const ThicknessRegion& reg : r.thick_regions) EXPECT_GT(reg.area, 0);
}

TEST_P(PocketFloors, NoThresholdNoRegions) {
  const auto world = make_world({pocket_block(kBlock, kPockets, 2.0)});
  const ThicknessResult r = compute_thickness(world->accel, options(0));
  EXPECT_TRUE(r.thin_regions.empty());
  EXPECT_TRUE(r.thick_regions.empty());
  ASSERT_EQ(r.region.size(), r.size());
  for (std::int32_t id : r.region) EXPECT_EQ(id, -1);
}

TEST_P(PocketFloors, ConeAndSphereGroupByTheSameRule) {
  const auto world = make_world({pocket_block(kBlock, kPockets, 1.0)});
  for (auto method : {analysis::ThicknessMethod::cone, analysis::ThicknessMethod::sphere}) {
    ThicknessOptions o = options(1.5);
    o.method = method;
    o.cone_rays = 9;
    const ThicknessResult r = compute_thickness(world->accel, o);
    check_ids(r, o, world->scene);
    ASSERT_FALSE(r.thin_regions.empty()) << enum_name(method);
    const ThicknessRegion& g = r.thin_regions[0];
    EXPECT_GT(g.area, 0) << enum_name(method);
    // The cone's thinnest is on or under the thinnest floor. (The sphere method's ball at a sharp
    // edge of the block is bounded by the faces away from it only: small; see thickness.h.)
    if (method == analysis::ThicknessMethod::sphere) continue;
    EXPECT_GE(g.point.x, kPockets[0].x0 - 1e-9) << enum_name(method);
    EXPECT_LE(g.point.x, kPockets[0].x1 + 1e-9) << enum_name(method);
    EXPECT_GE(g.point.y, kPockets[0].y0 - 1e-9) << enum_name(method);
    EXPECT_LE(g.point.y, kPockets[0].y1 + 1e-9) << enum_name(method);
  }
}

// A map measured in two parts (every other element, as two processes would) and assembled is
// the map of one run: rows, statistics and regions, whatever order the parts come in.
TEST_P(PocketFloors, AssembledFromPartsIsOneRun) {
  const auto world = make_world({pocket_block(kBlock, kPockets, 1.0)});
  ThicknessOptions o = options(1.5, 5);
  const ThicknessResult whole = compute_thickness(world->accel, o);
  const Geometry& geo = world->scene.geometry(0);
  const std::size_t n = o.per == SampleAt::vertex ? geo.vertices.size() : geo.triangles.size();
  std::vector<analysis::MeasuredSample> rows;
  for (int part = 1; part >= 0; --part) {
    ThicknessOptions measure = o;
    measure.min_thickness = 0, measure.max_thickness = std::numeric_limits<double>::infinity();
    measure.sample_mask.assign(1, std::vector<std::uint8_t>(n, 0));
    for (std::size_t e = std::size_t(part); e < n; e += 2) measure.sample_mask[0][e] = 1;
    const ThicknessResult r = compute_thickness(world->accel, measure);
    for (std::size_t i = 0; i < r.size(); ++i)
      rows.push_back({r.solid[i], r.element[i], r.point[i], r.normal[i], r.thickness[i], r.status[i], 0, r.exit_triangle[i]});
  }
  ThicknessOptions all = o;
  all.sample_mask.assign(1, std::vector<std::uint8_t>(n, 1));
  const ThicknessResult a = analysis::assemble_thickness(world->accel, all, rows);
  ASSERT_EQ(a.size(), whole.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.element[i], whole.element[i]);
    EXPECT_EQ(std::isnan(a.thickness[i]) ? -1.0 : a.thickness[i], std::isnan(whole.thickness[i]) ? -1.0 : whole.thickness[i]);
    EXPECT_EQ(a.status[i], whole.status[i]);
    EXPECT_EQ(a.thin[i], whole.thin[i]);
    EXPECT_EQ(a.region[i], whole.region[i]) << "sample " << i;
  }
  ASSERT_EQ(a.thin_regions.size(), whole.thin_regions.size());
  ASSERT_EQ(a.thick_regions.size(), whole.thick_regions.size());
  for (std::size_t k = 0; k < a.thin_regions.size() + a.thick_regions.size(); ++k) {
    const bool thin = k < a.thin_regions.size();
    const ThicknessRegion& x = thin ? a.thin_regions[k] : a.thick_regions[k - a.thin_regions.size()];
    const ThicknessRegion& y = thin ? whole.thin_regions[k] : whole.thick_regions[k - whole.thin_regions.size()];
    EXPECT_EQ(x.thickness, y.thickness);
    EXPECT_EQ(x.point, y.point);
    EXPECT_EQ(x.exit, y.exit);
    EXPECT_EQ(x.area, y.area);
    EXPECT_EQ(x.samples, y.samples);
  }
  EXPECT_EQ(a.solids[0].thin, whole.solids[0].thin);
  EXPECT_EQ(a.solids[0].summary.min, whole.solids[0].summary.min);
  std::erase_if(rows, [](const analysis::MeasuredSample& m) { return m.element == 0; });  // a sample without its row
  EXPECT_THROW(analysis::assemble_thickness(world->accel, all, rows), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Sampling, PocketFloors, ::testing::Values(SampleAt::vertex, SampleAt::face),
                         [](const auto& info) { return info.param == SampleAt::vertex ? "vertex" : "face"; });

TEST(ThicknessRegions, MaxBelowMinIsRejected) {
  const auto world = make_world({gen::box({0, 0, 0}, {1, 1, 1})});
  ThicknessOptions o;
  o.min_thickness = 2;
  o.max_thickness = 1;
  EXPECT_THROW(compute_thickness(world->accel, o), std::invalid_argument);
}

}  // namespace
}  // namespace pierce::test
