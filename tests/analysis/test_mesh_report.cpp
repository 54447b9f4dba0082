// Mesh diagnostics and the exact predicates they and the coplanar search rely on.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "analysis_scenes.h"
#include "pierce/exact_predicates.h"
#include "pierce/analysis/mesh_topology.h"
#include "pierce/analysis/mesh_report.h"

namespace pierce::test {
namespace {

using namespace pierce::analysis;

TEST(MeshReport, ClosedOpenDuplicatedAndFlipped) {
  const gen::Mesh b = gen::box({0, 0, 0}, {2, 1, 1}, "closed");
  gen::Mesh open = b;
  open.name = "open";
  open.triangles.resize(10);  // no +z face
  gen::Mesh dup = b;
  dup.name = "dup";
  dup.triangles.push_back(b.triangles[10]);
  dup.triangles.push_back(b.triangles[11]);
  gen::Mesh flip = b;
  flip.name = "flip";
  std::swap(flip.triangles[0][1], flip.triangles[0][2]);
  gen::Mesh inward = flipped(b);
  inward.name = "inward";
  auto w = make_world({b, open, dup, flip, inward});
  const auto rep = mesh_report(w->scene);
  ASSERT_EQ(rep.size(), 5u);

  EXPECT_EQ(rep[0].name, "closed");
  EXPECT_EQ(rep[0].triangles, 12u);
  EXPECT_EQ(rep[0].edges, 18u);
  EXPECT_TRUE(rep[0].closed);
  EXPECT_TRUE(rep[0].consistently_oriented);
  EXPECT_NEAR(rep[0].volume, 2.0, 1e-12);
  EXPECT_NEAR(rep[0].area, 10.0, 1e-12);
  EXPECT_EQ(rep[0].bounds.hi, (Vec3d{2, 1, 1}));

  EXPECT_FALSE(rep[1].closed);
  EXPECT_EQ(rep[1].boundary_edges, 4u);

  EXPECT_FALSE(rep[2].closed);
  EXPECT_EQ(rep[2].non_manifold_edges, 5u);  // the face's four sides and its diagonal
  EXPECT_EQ(rep[2].duplicates, 2u);

  EXPECT_TRUE(rep[3].closed);
  EXPECT_FALSE(rep[3].consistently_oriented);
  EXPECT_EQ(rep[3].inconsistent_edges, 3u);

  EXPECT_TRUE(rep[4].consistently_oriented);
  EXPECT_NEAR(rep[4].volume, -2.0, 1e-12);
}

TEST(MeshReport, WeldsUnsharedVerticesAndCountsDegenerates) {
  const gen::Mesh b = gen::box({0, 0, 0}, {1, 1, 1});
  gen::Mesh soup = triangle_soup(b);
  soup.triangles.push_back({0, 0, 0});  // degenerate, no edge
  auto w = make_world({soup});
  const auto rep = mesh_report(w->scene);
  EXPECT_EQ(rep[0].vertices, 36u);
  EXPECT_EQ(rep[0].welded_vertices, 8u);
  EXPECT_EQ(rep[0].degenerate, 1u);
  EXPECT_TRUE(rep[0].closed);
}

// first_occurrence against the definition (lowest index with the same welded corners, any
// winding), on random triangles over few vertices, so there are many repeats, and with a fan of
// 200 triangles around one vertex (longer than the pairwise-compared buckets).
TEST(MeshTopology, FirstOccurrenceIsTheLowestIndexWithTheSameCorners) {
  std::mt19937 rng(5);
  Geometry g;
  for (int i = 0; i < 40; ++i) g.vertices.push_back({double(i), double(i * i % 7), 0});
  g.vertices.push_back(g.vertices[3]);  // a welded duplicate of vertex 3
  const auto nv = std::uint32_t(g.vertices.size());
  auto pick = [&](std::uint32_t n) { return std::uint32_t(rng() % n); };
  for (int i = 0; i < 3000; ++i) g.triangles.push_back({pick(12), pick(12), pick(nv)});
  for (std::uint32_t k = 0; k < 200; ++k) g.triangles.push_back({0, 1 + k % 39, 1 + (k * 7 + 3) % 39});
  const auto weld = weld_by_position(g.vertices);
  const auto first = first_occurrence(g, weld);
  auto key = [&](std::size_t i) {
    std::array<std::uint32_t, 3> w{weld[g.triangles[i][0]], weld[g.triangles[i][1]], weld[g.triangles[i][2]]};
    std::sort(w.begin(), w.end());
    return w;
  };
  std::size_t repeats = 0;
  for (std::size_t i = 0; i < g.triangles.size(); ++i) {
    std::size_t want = i;
    for (std::size_t j = 0; j < i; ++j)
      if (key(j) == key(i)) {
        want = j;
        break;
      }
    ASSERT_EQ(first[i], want) << "triangle " << i;
    repeats += want != i;
  }
  EXPECT_GT(repeats, 500u);
}

TEST(ExactPredicates, DecideWhereDoublesRound) {
  // Points on the plane x + y + z = 1 with 26-bit coordinates: exactly coplanar, but the
  // determinant's products need up to 81 bits and round in double.
  std::mt19937_64 rng(3);
  auto coord = [&] { return double(rng() >> 38) * 0x1p-26; };
  auto on_plane = [&] {
    const double x = coord(), y = coord();
    return Vec3d{x, y, 1.0 - x - y};
  };
  auto naive = [](Vec3d a, Vec3d b, Vec3d c, Vec3d d) { return dot(cross(b - a, c - a), d - a); };
  int naive_wrong = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3d a = on_plane(), b = on_plane(), c = on_plane(), d = on_plane();
    if (orient3d(a, b, c, a + Vec3d{1, 1, 1}) == 0) continue;  // a, b, c collinear
    ASSERT_EQ(orient3d(a, b, c, d), 0) << i;
    naive_wrong += naive(a, b, c, d) != 0.0;
    // One ulp-scale step off the plane is seen, on the right side.
    const int up = orient3d(a, b, c, a + Vec3d{1, 1, 1});
    ASSERT_EQ(orient3d(a, b, c, d + Vec3d{0, 0, 0x1p-50}), up) << i;
    ASSERT_EQ(orient3d(a, b, c, d - Vec3d{0, 0, 0x1p-50}), -up) << i;
  }
  EXPECT_GT(naive_wrong, 0);  // the test exercises cases plain doubles get wrong

  // Kettner et al.'s classroom example: points one ulp apart near (0.5, 0.5) against the line
  // y = x through (12, 12) and (24, 24). The true side is the sign of j - i.
  int naive2_wrong = 0;
  const Vec2d q{12, 12}, r{24, 24};
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Vec2d p{0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53};
      const int truth = (j > i) - (j < i);
      ASSERT_EQ(orient2d(q, r, p), truth) << i << " " << j;
      const double naive = (r.x - q.x) * (p.y - q.y) - (r.y - q.y) * (p.x - q.x);
      naive2_wrong += ((naive > 0) - (naive < 0)) != truth;
    }
  EXPECT_GT(naive2_wrong, 0);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, -1}), -1);
}

}  // namespace
}  // namespace pierce::test
