// Ray partitions from the exact hit stream: touching, overlapping, nested, duplicated, open and
// grazing solids, and rays that start inside a solid.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "pierce/analysis/ray_partitions.h"
#include "pierce/generators.h"
#include "pierce/kernel.h"

namespace pierce {
namespace {

// Traces `ray` as a full line with `kind`, builds partitions and clips them to the ray.
RayPartitions classify(const Scene& scene, const Ray& ray, KernelKind kind = KernelKind::queue) {
  Accel accel(scene);
  HitIterator it(accel, kind, KernelOptions{HitOrder{TieOrder::leave_before_enter}});
  std::vector<Hit> hits;
  collect_hits(it, full_line_ray(ray, scene.bounds()), 0, hits);
  PartitionBuilder builder(scene.geometries().size());
  RayPartitions out;
  builder.build(hits, out);
  clip_partitions(out, ray.tmin, ray.tmax);
  return out;
}

std::vector<std::uint32_t> solids(const RayPartitions& r, std::size_t i) {
  auto s = r.solids_of(r.partitions.at(i));
  return {s.begin(), s.end()};
}

Ray along_x(double y, double z, double x0 = -5.0) { return Ray{{x0, y, z}, {1, 0, 0}}; }

class PartitionsPerKernel : public ::testing::TestWithParam<KernelKind> {};

TEST_P(PartitionsPerKernel, TouchingBoxesGiveAdjacentPartitionsWithoutGapOrOverlap) {
  const Scene scene = gen::to_scene({gen::box({0, 0, 0}, {1, 1, 1}, "a"), gen::box({1, 0, 0}, {2, 1, 1}, "b")});
  const RayPartitions r = classify(scene, along_x(0.5, 0.5), GetParam());
  ASSERT_EQ(r.partitions.size(), 2u);
  EXPECT_DOUBLE_EQ(r.partitions[0].t_in, 5.0);
  EXPECT_EQ(r.partitions[0].t_out, r.partitions[1].t_in);  // exactly adjacent: no gap
  EXPECT_DOUBLE_EQ(r.partitions[0].t_out, 6.0);
  EXPECT_DOUBLE_EQ(r.partitions[1].t_out, 7.0);
  EXPECT_EQ(solids(r, 0), std::vector<std::uint32_t>{0});
  EXPECT_EQ(solids(r, 1), std::vector<std::uint32_t>{1});
  EXPECT_EQ(r.unmatched_leaves, 0u);
  EXPECT_EQ(r.unclosed, 0u);
}

TEST_P(PartitionsPerKernel, StackedPlatesThroughSharedEdgesGiveOnePartitionPerPlate) {
  // (0.5, 0.5) runs through the faces' diagonal edges and the plates' shared faces.
  const Scene scene = gen::to_scene(gen::stacked_plates(10, 1.0, 0.1));
  for (Vec3d org : {Vec3d{0.5, 0.5, -1}, Vec3d{0.25, 0.25, -1}, Vec3d{0.3, 0.7, -1}}) {
    const RayPartitions r = classify(scene, Ray{org, {0, 0, 1}}, GetParam());
    ASSERT_EQ(r.partitions.size(), 10u) << org.x << "," << org.y;
    for (std::size_t i = 0; i < 10; ++i) {
      EXPECT_EQ(solids(r, i), std::vector<std::uint32_t>{std::uint32_t(i)});
      EXPECT_NEAR(r.partitions[i].t_out - r.partitions[i].t_in, 0.1, 1e-6);
      if (i > 0) {
        EXPECT_EQ(r.partitions[i - 1].t_out, r.partitions[i].t_in);
      }
    }
  }
}

TEST_P(PartitionsPerKernel, RaysInTheSideFacesAreWhollyInsideOrOutside) {
  // A ray lying in the side faces' planes is decided by the tie rule: all plates or none, never a
  // half-open or overlapping answer.
  const Scene scene = gen::to_scene(gen::stacked_plates(10, 1.0, 0.1));
  for (Vec3d org : {Vec3d{0, 0, -1}, Vec3d{1, 0.5, -1}, Vec3d{0, 0.5, -1}, Vec3d{1, 1, -1}}) {
    const RayPartitions r = classify(scene, Ray{org, {0, 0, 1}}, GetParam());
    EXPECT_TRUE(r.partitions.empty() || r.partitions.size() == 10u) << org.x << "," << org.y;
    EXPECT_EQ(r.unmatched_leaves, 0u);
    EXPECT_EQ(r.unclosed, 0u);
    for (const Partition& p : r.partitions) EXPECT_EQ(p.count, 1u);
  }
}

std::string kernel_param_name(const ::testing::TestParamInfo<KernelKind>& info) {
  std::string n(kernel_name(info.param));
  std::replace(n.begin(), n.end(), '-', '_');
  return n;
}

INSTANTIATE_TEST_SUITE_P(ExactKernels, PartitionsPerKernel,
                         ::testing::Values(KernelKind::restart, KernelKind::queue, KernelKind::nodecull,
                                           KernelKind::filter, KernelKind::buffered, KernelKind::embree_restart,
                                           KernelKind::embree_filter, KernelKind::embree_nodecull),
                         kernel_param_name);

TEST(Partitions, InterpenetratingBoxesGiveAnOverlapOfTheRightDepth) {
  const Scene scene = gen::to_scene({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({0.7, 0.2, 0.2}, {1.7, 0.8, 0.8})});
  const RayPartitions r = classify(scene, along_x(0.5, 0.5));
  ASSERT_EQ(r.partitions.size(), 3u);
  EXPECT_EQ(solids(r, 0), std::vector<std::uint32_t>{0});
  EXPECT_EQ(solids(r, 1), (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(solids(r, 2), std::vector<std::uint32_t>{1});
  EXPECT_NEAR(r.partitions[1].t_out - r.partitions[1].t_in, 0.3, 1e-6);
  EXPECT_EQ(r.partitions[1].in_hit.geom, 1u);
  EXPECT_EQ(r.partitions[1].out_hit.geom, 0u);
}

TEST(Partitions, NestedSolidIsAnOverlapInsideTheOuterOne) {
  const Scene scene = gen::to_scene({gen::box({0, 0, 0}, {3, 3, 3}), gen::box({1, 1, 1}, {2, 2, 2})});
  const RayPartitions r = classify(scene, along_x(1.5, 1.5));
  ASSERT_EQ(r.partitions.size(), 3u);
  EXPECT_EQ(solids(r, 1), (std::vector<std::uint32_t>{0, 1}));
  EXPECT_DOUBLE_EQ(r.partitions[1].t_in, 6.0);
  EXPECT_DOUBLE_EQ(r.partitions[1].t_out, 7.0);
}

TEST(Partitions, GapBetweenSeparatedSolidsStaysOpen) {
  const Scene scene = gen::to_scene({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({1.5, 0, 0}, {2, 1, 1})});
  const RayPartitions r = classify(scene, along_x(0.5, 0.5));
  ASSERT_EQ(r.partitions.size(), 2u);
  EXPECT_NEAR(r.partitions[1].t_in - r.partitions[0].t_out, 0.5, 1e-6);
}

TEST(Partitions, RayStartingInsideIsClippedAndKnowsItIsInside) {
  const Scene scene = gen::to_scene({gen::box({0, 0, 0}, {1, 1, 1}), gen::box({1, 0, 0}, {2, 1, 1})});
  Ray ray{{0.25, 0.5, 0.5}, {1, 0, 0}, 0.0, 1.0};  // ends inside the second box
  const RayPartitions r = classify(scene, ray);
  ASSERT_EQ(r.partitions.size(), 2u);
  EXPECT_DOUBLE_EQ(r.partitions[0].t_in, 0.0);
  EXPECT_FALSE(r.partitions[0].in_hit.valid());
  EXPECT_TRUE(r.partitions[0].out_hit.valid());
  EXPECT_DOUBLE_EQ(r.partitions[1].t_out, 1.0);
  EXPECT_FALSE(r.partitions[1].out_hit.valid());
}

TEST(Partitions, DuplicatedCoplanarFacesCountOnce) {
  const Scene scene = gen::to_scene({gen::duplicated(gen::box({0, 0, 0}, {1, 1, 1}), 3, false)});
  const RayPartitions r = classify(scene, along_x(0.5, 0.5));
  ASSERT_EQ(r.partitions.size(), 1u);
  EXPECT_DOUBLE_EQ(r.partitions[0].t_out - r.partitions[0].t_in, 1.0);
  EXPECT_EQ(r.unclosed, 0u);
}

TEST(Partitions, OpenMeshInventsNoInterval) {
  gen::Mesh open = gen::box({0, 0, 0}, {1, 1, 1});
  // Drop the two triangles of the x = 1 face: rays along +x enter and never leave.
  std::vector<Tri> kept;
  for (const Tri& t : open.triangles) {
    bool on_x1 = true;
    for (auto i : t) on_x1 = on_x1 && open.vertices[i].x == 1.0;
    if (!on_x1) kept.push_back(t);
  }
  ASSERT_EQ(kept.size(), 10u);
  open.triangles = kept;
  const Scene scene = gen::to_scene({open, gen::box({3, 0, 0}, {4, 1, 1})});
  const RayPartitions r = classify(scene, along_x(0.5, 0.5));
  EXPECT_EQ(r.unclosed, 1u);
  // The open box's entry without exit claims nothing: only the closed box remains, no overlap.
  ASSERT_EQ(r.partitions.size(), 1u);
  EXPECT_EQ(solids(r, 0), std::vector<std::uint32_t>{1});
  EXPECT_DOUBLE_EQ(r.partitions[0].t_in, 8.0);
  EXPECT_DOUBLE_EQ(r.partitions[0].t_out, 9.0);
  const RayPartitions back = classify(scene, Ray{{10, 0.5, 0.5}, {-1, 0, 0}});
  EXPECT_EQ(back.unmatched_leaves, 1u);  // leaves the open box through x = 0 without having entered
  ASSERT_EQ(back.partitions.size(), 1u);
  EXPECT_EQ(solids(back, 0), std::vector<std::uint32_t>{1});
}

TEST(Partitions, RayGrazingAnEdgeClaimsNothing) {
  const Scene scene = gen::to_scene({gen::box({0, 0, 0}, {1, 1, 1})});
  // Passes through the vertical edge x = 1, y = 0 only.
  const RayPartitions r = classify(scene, Ray{{0, -1, 0.5}, {1, 1, 0}});
  EXPECT_EQ(r.unmatched_leaves, 0u);
  EXPECT_EQ(r.unclosed, 0u);
  for (const Partition& p : r.partitions) EXPECT_LT(p.t_in, p.t_out);
  EXPECT_TRUE(r.partitions.empty());
}

TEST(Partitions, OrderOfHitsAtEqualTDoesNotMatter) {
  // Synthetic stream: solid 0 [1,2], solid 1 [2,3] and solid 2 [2,2.5] starting where 0 ends.
  auto hit = [](double t, std::uint32_t g, std::uint32_t prim, bool enter) {
    Hit h;
    h.t = t, h.geom = g, h.prim = prim, h.enter = enter;
    return h;
  };
  std::vector<Hit> hits = {hit(1, 0, 0, true),  hit(2, 0, 1, false), hit(2, 1, 0, true),
                           hit(2, 2, 0, true),  hit(2.5, 2, 1, false), hit(3, 1, 1, false)};
  PartitionBuilder builder(3);
  RayPartitions ref;
  builder.build(hits, ref);
  ASSERT_EQ(ref.partitions.size(), 3u);
  EXPECT_EQ(solids(ref, 1), (std::vector<std::uint32_t>{1, 2}));
  std::mt19937 rng(3);
  for (int i = 0; i < 20; ++i) {
    std::shuffle(hits.begin() + 1, hits.begin() + 4, rng);
    RayPartitions r;
    builder.build(hits, r);
    ASSERT_EQ(r.partitions.size(), ref.partitions.size());
    for (std::size_t k = 0; k < r.partitions.size(); ++k) {
      EXPECT_EQ(r.partitions[k].t_in, ref.partitions[k].t_in);
      EXPECT_EQ(r.partitions[k].t_out, ref.partitions[k].t_out);
      EXPECT_EQ(solids(r, k), solids(ref, k));
    }
  }
}

}  // namespace
}  // namespace pierce
