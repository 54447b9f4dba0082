// Every exact kernel returns exactly the brute-force hit list (same hits, same order, same t) on
// every scene family, at several scales and offsets, under both tie policies; and the reference
// itself matches what each scene's construction says (counts, parity, facing).
#include <set>
#include <tuple>

#include "scenes.h"

namespace pierce::test {
namespace {

const Xform kXforms[] = {
    {"unit", 1.0, {0, 0, 0}},
    {"offset1e5", 1.0, {1e5, 1e5, 1e5}},
    {"offset_mixed", 1.0, {-1e5, 3e4, 1e5}},
    {"scale1em4", 1e-4, {0, 0, 0}},
    {"scale1e4", 1e4, {0, 0, 0}},
};

const Family kFamilies[] = {
    Family::soup,           Family::blob,           Family::plates,
    Family::plates_reversed, Family::plates_thickness, Family::duplicated_same,
    Family::duplicated_alternate, Family::overlapping, Family::cube_grid,
    Family::voxel_block,    Family::deep_plates,
};

::testing::AssertionResult no_repeats(const std::vector<Hit>& hits) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
  for (const Hit& h : hits)
    if (!seen.insert({h.geom, h.prim}).second)
      return ::testing::AssertionFailure() << "triangle (" << h.geom << ", " << h.prim << ") crossed twice";
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult matches_construction(const Expect& e, const std::vector<Hit>& hits, std::size_t geoms) {
  if (e.count >= 0 && int(hits.size()) != e.count)
    return ::testing::AssertionFailure() << "construction says " << e.count << " crossings, got " << hits.size();
  if (e.closed) return closed_parity(hits, geoms, e.alternate);
  return ::testing::AssertionSuccess();
}

class Agreement : public ::testing::TestWithParam<std::tuple<Family, Xform>> {};

TEST_P(Agreement, ExactKernelsMatchReference) {
  const auto& [family, xform] = GetParam();
  const Case c = build_case(family, xform);
  ASSERT_FALSE(c.probes.empty());
  const auto w = make_world(c.meshes);
  const std::size_t geoms = w->scene.geometries().size();

  for (TieOrder tie : kTieOrders) {
    const HitOrder order{tie};
    SCOPED_TRACE(tie_name(tie));
    std::vector<std::vector<Hit>> ref(c.probes.size());
    std::size_t total = 0;
    for (std::size_t i = 0; i < c.probes.size(); ++i) {
      ref[i] = reference_hits(w->scene, c.probes[i].ray, order);
      total += ref[i].size();
      ASSERT_TRUE(matches_construction(c.probes[i].expect, ref[i], geoms)) << "probe " << i << " " << str(c.probes[i].ray);
      ASSERT_TRUE(no_repeats(ref[i])) << "probe " << i << " " << str(c.probes[i].ray);
      ASSERT_TRUE(ordered(ref[i], order)) << "probe " << i;
    }
    EXPECT_GT(total, 0u);

    for (KernelKind k : exact_kernels()) {
      HitIterator it(w->accel, k, {order});
      int failures = 0;
      for (std::size_t i = 0; i < c.probes.size() && failures < 3; ++i) {
        const auto got = kernel_hits(it, c.probes[i].ray);
        const auto same = same_hits(ref[i], got);
        if (!same) ++failures;
        EXPECT_TRUE(same) << kernel_name(k) << ", probe " << i << " " << str(c.probes[i].ray);
      }
    }
  }
}

std::string case_name(const ::testing::TestParamInfo<Agreement::ParamType>& info) {
  return family_name(std::get<0>(info.param)) + "_" + std::get<1>(info.param).name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, Agreement, ::testing::Combine(::testing::ValuesIn(kFamilies), ::testing::ValuesIn(kXforms)),
                         case_name);

// On touching plates whose geometry ids decrease upwards, the two crossings at each shared plane
// have the same t (same point in space) and the tie policy alone decides their order:
// geom_prim puts the entered (lower id) plate first, leave_before_enter the left one.
TEST(TieOrder, TouchingPlatesShareTAndFollowThePolicy) {
  const int n = 20;
  auto plates = gen::stacked_plates(n);
  std::reverse(plates.begin(), plates.end());  // geometry g is plate n-1-g
  const auto w = make_world(plates);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> U(0.3, 0.7);  // stays inside the footprint over 3 units of z
  for (TieOrder tie : kTieOrders) {
    SCOPED_TRACE(tie_name(tie));
    for (KernelKind k : exact_kernels()) {
      HitIterator it(w->accel, k, {HitOrder{tie}});
      for (int i = 0; i < 10; ++i) {
        // Steep but not axis-aligned, so t comes from the full shear.
        const Vec3d dir = i < 5 ? Vec3d{0, 0, 1} : Vec3d{0.2 * (U(rng) - 0.5), 0.2 * (U(rng) - 0.5), 1};
        const Ray r{{U(rng), U(rng), -1.0}, dir};
        const auto hits = kernel_hits(it, r);
        ASSERT_EQ(hits.size(), std::size_t(2 * n)) << kernel_name(k) << " " << str(r);
        // hits[0] enters plate 0 (geom n-1); then at each shared plane j one leaving, one entering.
        EXPECT_TRUE(hits[0].enter);
        EXPECT_FALSE(hits.back().enter);
        for (int j = 1; j < n; ++j) {
          const Hit& a = hits[std::size_t(2 * j - 1)];
          const Hit& b = hits[std::size_t(2 * j)];
          EXPECT_EQ(a.t, b.t) << kernel_name(k) << " plane " << j << " " << str(r) << ": " << str(a) << " " << str(b);
          const Hit& leave = a.enter ? b : a;
          const Hit& enter = a.enter ? a : b;
          EXPECT_FALSE(leave.enter);
          EXPECT_TRUE(enter.enter);
          EXPECT_EQ(leave.geom, std::uint32_t(n - j)) << "plate j-1 = geometry n-j";
          EXPECT_EQ(enter.geom, std::uint32_t(n - 1 - j));
          if (a.t == b.t) {
            EXPECT_EQ(a.enter, tie == TieOrder::geom_prim) << kernel_name(k) << " plane " << j;
          }
        }
      }
    }
  }
}

// Copies of one face listed with rotated corners and either winding are the same surface: every
// kernel reports all their crossings at one t, so only the tie policy orders them.
TEST(TieOrder, DuplicatedFacesInAnyCornerOrderShareT) {
  const gen::Mesh base = gen::box({0, 0, 0}, {1, 1, 1});
  gen::Mesh m{"rotated", base.vertices, {}};
  for (int copy = 0; copy < 6; ++copy)
    for (Tri t : base.triangles) {
      std::rotate(t.begin(), t.begin() + copy % 3, t.end());
      if (copy >= 3) std::swap(t[1], t[2]);
      m.triangles.push_back(t);
    }
  const auto w = make_world({m});
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> U(0.3, 0.7), D(-0.1, 0.1);
  for (TieOrder tie : kTieOrders)
    for (KernelKind k : exact_kernels()) {
      HitIterator it(w->accel, k, {HitOrder{tie}});
      for (int i = 0; i < 20; ++i) {
        const Ray r{{U(rng), U(rng), -1.0}, {D(rng), D(rng), 1.0}};
        const auto hits = kernel_hits(it, r);
        ASSERT_EQ(hits.size(), 12u) << kernel_name(k) << " " << str(r);
        for (std::size_t j = 1; j < 6; ++j) {
          EXPECT_EQ(hits[j].t, hits[0].t) << kernel_name(k) << " " << str(hits[j]);
          EXPECT_EQ(hits[6 + j].t, hits[6].t) << kernel_name(k) << " " << str(hits[6 + j]);
        }
        if (tie == TieOrder::leave_before_enter) {  // at the bottom face the 3 reversed copies leave first
          for (std::size_t j = 0; j < 6; ++j) EXPECT_EQ(hits[j].enter, j >= 3) << kernel_name(k) << " hit " << j;
        }
      }
    }
}

}  // namespace
}  // namespace pierce::test
