// The disagreement counts of `pierce hits --kernel all`.
#include <gtest/gtest.h>

#include "hit_diff.h"

namespace pierce::cli {
namespace {

Hit hit(double t, std::uint32_t geom, std::uint32_t prim) {
  Hit h;
  h.t = t, h.geom = geom, h.prim = prim;
  return h;
}

const std::vector<Hit> kRef = {hit(1, 0, 5), hit(2, 0, 6), hit(2, 1, 0), hit(3, 1, 1)};

HitDiff diff(const std::vector<Hit>& got) {
  HitDiff d;
  diff_hits(kRef, got, d);
  return d;
}

TEST(HitDiff, IdenticalListsAreClean) {
  const HitDiff d = diff(kRef);
  EXPECT_EQ(d.rays, 1u);
  EXPECT_TRUE(d.clean());
  EXPECT_EQ(d.missing + d.extra + d.duplicated + d.out_of_order + d.t_differs, 0u);
}

TEST(HitDiff, CountsEachKindOfDifference) {
  {
    const HitDiff d = diff({kRef[0], kRef[2], kRef[3]});
    EXPECT_EQ(d.rays_differ, 1u);
    EXPECT_EQ(d.missing, 1u);
    EXPECT_EQ(d.extra + d.duplicated + d.out_of_order + d.t_differs, 0u);
  }
  {
    const HitDiff d = diff({kRef[0], kRef[1], kRef[1], kRef[2], kRef[3]});
    EXPECT_EQ(d.duplicated, 1u);
    EXPECT_EQ(d.missing + d.extra + d.out_of_order, 0u);
  }
  {
    const HitDiff d = diff({kRef[0], kRef[1], kRef[2], hit(2.5, 7, 7), kRef[3]});
    EXPECT_EQ(d.extra, 1u);
    EXPECT_EQ(d.missing + d.duplicated + d.out_of_order, 0u);
  }
  {
    const HitDiff d = diff({kRef[0], kRef[2], kRef[1], kRef[3]});
    EXPECT_EQ(d.out_of_order, 1u);
    EXPECT_EQ(d.missing + d.extra + d.duplicated, 0u);
  }
  {
    std::vector<Hit> got = kRef;
    got[1].t = 2.0000001;
    const HitDiff d = diff(got);
    EXPECT_EQ(d.rays_differ, 1u);
    EXPECT_EQ(d.t_differs, 1u);
    EXPECT_EQ(d.missing + d.extra + d.duplicated + d.out_of_order, 0u);
  }
  {
    // An epsilon-style miss of a coincident hit plus a repeat of the one before.
    const HitDiff d = diff({kRef[0], kRef[1], kRef[1], kRef[3]});
    EXPECT_EQ(d.missing, 1u);
    EXPECT_EQ(d.duplicated, 1u);
  }
}

TEST(HitDiff, SumsOverRays) {
  HitDiff total;
  diff_hits(kRef, kRef, total);
  diff_hits(kRef, std::vector<Hit>{kRef[0]}, total);
  diff_hits(kRef, std::vector<Hit>{}, total);
  EXPECT_EQ(total.rays, 3u);
  EXPECT_EQ(total.rays_differ, 2u);
  EXPECT_EQ(total.missing, 3u + 4u);
}

TEST(HitDiff, ConsensusIsTheMostCommonList) {
  const std::vector<Hit> a = kRef, b = {kRef[0]}, c = {};
  bool majority = false;
  {
    const std::vector<std::span<const Hit>> lists = {b, a, a, c, a};
    EXPECT_EQ(consensus_index(lists, majority), 1u);
    EXPECT_TRUE(majority);
  }
  {
    const std::vector<std::span<const Hit>> lists = {b, a, a, b};
    EXPECT_EQ(consensus_index(lists, majority), 0u);  // tie: the earliest of the largest groups
    EXPECT_FALSE(majority);
  }
}

}  // namespace
}  // namespace pierce::cli
