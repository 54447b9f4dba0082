// The kernels on Pierce's (wide) BVH must be exact for any valid tree, not only for the SAH builder's
// trees: random topologies with heavily overlapping nodes (and tiny leaves, and huge ones) stress
// the culling and release rules, and each kernel must still return the brute-force list.
#include <cstring>
#include <map>
#include <numeric>
#include <random>

#include <tbb/global_control.h>

#include "pierce/bvh_builder.h"
#include "test_util.h"

namespace pierce::test {
namespace {

// Any binary tree over the scene's non-degenerate triangles, split at random positions of a
// random permutation, with exact (tight) boxes.
Bvhf random_bvh(const Scene& scene, std::mt19937_64& rng, std::uint32_t max_leaf) {
  Bvhf bvh;
  bvh.scene_max_abs = scene.bounds().max_abs_coord();
  std::vector<Triangle<float>> tris;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      if (geo.degenerate[p]) continue;
      const Tri& t = geo.triangles[p];
      tris.push_back({Vec3f(geo.vertices[t[0]]), Vec3f(geo.vertices[t[1]]), Vec3f(geo.vertices[t[2]]), g, p});
    }
  }
  std::shuffle(tris.begin(), tris.end(), rng);
  bvh.tris.assign(tris.begin(), tris.end());
  if (tris.empty()) return bvh;
  bvh.nodes.emplace_back();
  struct Todo {
    std::uint32_t node, begin, end;
  };
  std::vector<Todo> todo{{0, 0, std::uint32_t(tris.size())}};
  while (!todo.empty()) {
    const Todo t = todo.back();
    todo.pop_back();
    BBoxf box;
    for (std::uint32_t i = t.begin; i < t.end; ++i) {
      box.extend(tris[i].v0), box.extend(tris[i].v1), box.extend(tris[i].v2);
    }
    bvh.nodes[t.node].box = box;
    const std::uint32_t n = t.end - t.begin;
    if (n <= max_leaf && (n == 1 || rng() % 3 == 0)) {
      bvh.nodes[t.node].first = t.begin;
      bvh.nodes[t.node].count = n;
      continue;
    }
    const std::uint32_t mid = t.begin + 1 + std::uint32_t(rng() % (n - 1));
    const auto left = std::uint32_t(bvh.nodes.size());
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    bvh.nodes[t.node].first = left;
    bvh.nodes[t.node].count = 0;
    todo.push_back({left, t.begin, mid});
    todo.push_back({left + 1, mid, t.end});
  }
  return bvh;
}

// Brute-force lists for both tie policies, computed once per scene (independent of the tree).
struct Expected {
  std::vector<Ray> rays;
  std::vector<std::vector<Hit>> by_tie[2];
  Expected(const Scene& scene, std::vector<Ray> r) : rays(std::move(r)) {
    for (int t = 0; t < 2; ++t)
      for (const Ray& ray : rays) by_tie[t].push_back(reference_hits(scene, ray, {kTieOrders[t]}));
  }
};

template <typename Kernel>
void check_kernel(const char* name, const WideBvhf& bvh, const Expected& ex, int tie, std::size_t max_hits) {
  Kernel k(bvh, {kTieOrders[tie]});
  int failures = 0;
  const auto& rays = ex.rays;
  for (std::size_t i = 0; i < rays.size() && failures < 3; ++i) {
    const auto& want = ex.by_tie[tie][i];
    k.begin(rays[i], max_hits);
    std::vector<Hit> got;
    Hit h;
    while (got.size() <= want.size() + 10 && k.next(h)) got.push_back(h);
    const auto same = same_hits(want, got);
    if (!same) ++failures;
    EXPECT_TRUE(same) << name << " max_hits " << max_hits << ", ray " << i << " " << str(rays[i]);
  }
}

// `queue` with its first pass forced to one order (the default picks by the recent rays).
template <QueueFirstPass kPass>
struct QueueWith : QueueKernel<float> {
  QueueWith(const WideBvhf& bvh, HitOrder order) : QueueKernel<float>(bvh, order, kPass) {}
};

void check_wide(const WideBvhf& bvh, const Expected& ex) {
  for (int tie = 0; tie < 2; ++tie) {
    SCOPED_TRACE(tie_name(kTieOrders[tie]));
    check_kernel<RestartKernel<float>>("restart", bvh, ex, tie, 0);
    check_kernel<QueueKernel<float>>("queue", bvh, ex, tie, 0);
    for (std::size_t n : {0, 1, 3, 16}) {
      check_kernel<QueueWith<QueueFirstPass::depth_first>>("queue depth first", bvh, ex, tie, n);
      check_kernel<QueueWith<QueueFirstPass::breadth_first>>("queue breadth first", bvh, ex, tie, n);
    }
    check_kernel<AllHitsKernel<float>>("filter", bvh, ex, tie, 0);
    check_kernel<BufferedKernel<float>>("buffered", bvh, ex, tie, 0);
    for (std::size_t n : {0, 1, 3, 16}) check_kernel<NodeCullKernel<float>>("nodecull", bvh, ex, tie, n);
  }
}

// The kernels run on the wide BVH collapsed from the random binary tree: random wide layouts too.
void check_all(const Bvhf& binary, const Expected& ex) { check_wide(build_wide_bvh(binary), ex); }

// Big random triangles: every ray crosses dozens, and every node overlaps most others.
TEST(BvhLayouts, RandomTreesOverDenseSoup) {
  std::mt19937_64 rng(42);
  gen::Mesh soup = gen::random_soup(1500, 1.0, 3);
  const Scene scene = gen::to_scene({soup});
  const Expected ex(scene, random_rays(scene.bounds(), 40, 4));
  std::size_t hits = 0;
  for (const auto& h : ex.by_tie[0]) hits += h.size();
  ASSERT_GT(hits, 40u * 16u) << "rays must overflow the buffered kernel's 16 entries";
  for (std::uint32_t max_leaf : {1u, 4u, 40u}) {
    for (int tree = 0; tree < 3; ++tree) {
      SCOPED_TRACE(testing::Message() << "max_leaf " << max_leaf << " tree " << tree);
      const Bvhf bvh = random_bvh(scene, rng, max_leaf);
      check_all(bvh, ex);
    }
  }
}

// Stacked touching plates and duplicated faces: many equal t, long rays.
TEST(BvhLayouts, RandomTreesOverTiesAndDepth) {
  std::mt19937_64 rng(43);
  auto meshes = gen::stacked_plates(30);
  meshes.push_back(gen::duplicated(gen::box({0.2, 0.2, 0.5}, {0.8, 0.8, 2.5}, "dup"), 5, true));
  const Scene scene = gen::to_scene(meshes);
  std::vector<Ray> rays = random_rays(scene.bounds(), 30, 5);
  std::uniform_real_distribution<double> U(0.05, 0.95);
  for (int i = 0; i < 30; ++i) rays.push_back({{U(rng), U(rng), -1.0}, {0, 0, 1}});
  const Expected ex(scene, rays);
  for (std::uint32_t max_leaf : {1u, 8u}) {
    for (int tree = 0; tree < 3; ++tree) {
      SCOPED_TRACE(testing::Message() << "max_leaf " << max_leaf << " tree " << tree);
      const Bvhf bvh = random_bvh(scene, rng, max_leaf);
      check_all(bvh, ex);
    }
  }
}

// A hand-made layout for the buffered kernel's release rule: a node entered early but holding
// only a late hit (a slanted triangle) is processed after a full buffer dropped hits; the hits it
// blocked are then released and a later node's hit must not overtake the dropped ones.
TEST(BvhLayouts, BufferedReleaseAfterOverflow) {
  gen::Mesh m;
  m.name = "layout";
  // 24 small squares' triangles across the ray x = y = 0.5 at z = 1.0, 1.05, ..., 2.15.
  for (int i = 0; i < 24; ++i) {
    const double z = 1.0 + 0.05 * i;
    const auto b = std::uint32_t(m.vertices.size());
    m.vertices.push_back({0.4, 0.4, z});
    m.vertices.push_back({0.7, 0.4, z});
    m.vertices.push_back({0.4, 0.7, z});
    m.triangles.push_back({b, b + 1, b + 2});
  }
  // Slanted triangle: box starts at z = 1.2, crossed by the ray at z = 1.25.
  {
    const auto b = std::uint32_t(m.vertices.size());
    m.vertices.push_back({0.45, 0.3, 1.2});
    m.vertices.push_back({0.45, 0.7, 1.2});
    m.vertices.push_back({0.9, 0.5, 3.5});
    m.triangles.push_back({b, b + 1, b + 2});
  }
  // A late triangle in its own node, entered at z = 2.6.
  {
    const auto b = std::uint32_t(m.vertices.size());
    m.vertices.push_back({0.3, 0.3, 2.6});
    m.vertices.push_back({0.8, 0.3, 2.6});
    m.vertices.push_back({0.3, 0.8, 2.6});
    m.triangles.push_back({b, b + 1, b + 2});
  }
  const Scene scene = gen::to_scene({m});
  const Ray ray{{0.5, 0.5, 0.0}, {0, 0, 1}};
  ASSERT_EQ(reference_hits(scene, ray, {}).size(), 26u);

  // root -> [M, Q]; M -> [L, R]; L: leaves of 8 squares; R: the slanted triangle; Q: the late one.
  Bvhf bvh;
  bvh.scene_max_abs = scene.bounds().max_abs_coord();
  const Geometry& geo = scene.geometry(0);
  for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
    const Tri& t = geo.triangles[p];
    bvh.tris.push_back({Vec3f(geo.vertices[t[0]]), Vec3f(geo.vertices[t[1]]), Vec3f(geo.vertices[t[2]]), 0, p});
  }
  auto box_of = [&](std::uint32_t first, std::uint32_t count) {
    BBoxf b;
    for (std::uint32_t i = first; i < first + count; ++i)
      b.extend(bvh.tris[i].v0), b.extend(bvh.tris[i].v1), b.extend(bvh.tris[i].v2);
    return b;
  };
  auto leaf = [&](std::uint32_t first, std::uint32_t count) {
    return BvhNode<float>{box_of(first, count), first, count};
  };
  auto join = [](const BvhNode<float>& a, const BvhNode<float>& b, std::uint32_t first) {
    BvhNode<float> n{a.box, first, 0};
    n.box.extend(b.box);
    return n;
  };
  // Node indices: 0 root, 1 M, 2 Q, 3 L, 4 R, 5 L0, 6 L', 7 L1, 8 L2.
  HugePageVector<BvhNode<float>> nodes(9);
  nodes[5] = leaf(0, 8), nodes[7] = leaf(8, 8), nodes[8] = leaf(16, 8);
  nodes[6] = join(nodes[7], nodes[8], 7);
  nodes[3] = join(nodes[5], nodes[6], 5);
  nodes[4] = leaf(24, 1);
  nodes[1] = join(nodes[3], nodes[4], 3);
  nodes[2] = leaf(25, 1);
  nodes[0] = join(nodes[1], nodes[2], 1);
  bvh.nodes = nodes;
  check_all(bvh, Expected(scene, {ray}));
}

}  // namespace
}  // namespace pierce::test

namespace pierce::test {
namespace {

// The binned SAH builder, with float areas (scenes within Embree's coordinate range) and with
// double areas (beyond it), gives trees every kernel is exact on, with boxes that are exact unions.
// Plates, duplicated faces and a random soup: the builders' test scene.
Scene builder_scene() {
  auto meshes = gen::stacked_plates(12);
  meshes.push_back(gen::duplicated(gen::box({0.2, 0.2, 0.5}, {0.8, 0.8, 1.5}, "dup"), 4, true));
  meshes.push_back(gen::random_soup(600, 0.3, 9));
  return gen::to_scene(meshes);
}

TEST(BvhLayouts, FloatAndDoubleAreaBuilds) {
  const Scene scene = builder_scene();
  const Expected ex(scene, random_rays(scene.bounds(), 60, 8));
  for (const bool float_areas : {true, false}) {
    SCOPED_TRACE(float_areas ? "float areas" : "double areas");
    BvhBuildOptions opts;
    opts.float_areas = float_areas;
    const Bvhf bvh = build_bvh<float>(scene, opts);
    ASSERT_FALSE(bvh.nodes.empty());
    for (const BvhNode<float>& n : bvh.nodes) {  // every box is exactly the union of what is below it
      BBoxf want;
      if (n.is_leaf()) {
        for (std::uint32_t i = n.first; i < n.first + n.count; ++i)
          want.extend(bvh.tris[i].v0), want.extend(bvh.tris[i].v1), want.extend(bvh.tris[i].v2);
      } else {
        want.extend(bvh.nodes[n.first].box), want.extend(bvh.nodes[n.first + 1].box);
      }
      ASSERT_EQ(n.box.lo, want.lo);
      ASSERT_EQ(n.box.hi, want.hi);
    }
    check_all(bvh, ex);
  }
}

}  // namespace
}  // namespace pierce::test

namespace pierce::test {
namespace {

// The exact box of the subtree at `ref`; fails the test where a stored child box is not exactly
// the union of the triangles below it. Counts each (geom, prim) seen.
BBoxf exact_subtree_box(const WideBvhf& bvh, NodeRef ref, std::map<std::pair<std::uint32_t, std::uint32_t>, int>& seen) {
  BBoxf box;
  if (is_leaf(ref)) {
    for (std::uint32_t b = leaf_first_block(ref); b < leaf_first_block(ref) + leaf_block_count(ref); ++b) {
      const TriBlock<float>& blk = bvh.blocks[b];
      for (int l = 0; l < kBlockLanes; ++l) {
        if (!(blk.valid >> l & 1)) continue;
        ++seen[{blk.geom[l], blk.prim[l]}];
        for (int c = 0; c < 3; ++c) box.extend(blk.corner(c, l));
      }
    }
    return box;
  }
  const WideNode<float>& n = bvh.nodes[ref];
  for (int s = 0; s < kWideArity; ++s) {
    if (!(n.valid() >> s & 1)) continue;
    const BBoxf child = exact_subtree_box(bvh, n.child[s], seen);
    EXPECT_EQ(Vec3f(n.lo[0][s], n.lo[1][s], n.lo[2][s]), child.lo) << "node " << ref << " slot " << s;
    EXPECT_EQ(Vec3f(n.hi[0][s], n.hi[1][s], n.hi[2][s]), child.hi) << "node " << ref << " slot " << s;
    box.extend(child);
  }
  return box;
}

// The direct 8-wide build: exact boxes, every non-degenerate triangle exactly once, exact kernels.
void check_direct_build(const Scene& scene, const Expected& ex, const BvhBuildOptions& opts) {
  const WideBvhf bvh = build_wide_bvh<float>(scene, opts);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> seen;
  const BBoxf box = exact_subtree_box(bvh, bvh.root, seen);
  EXPECT_EQ(box.lo, bvh.bounds.lo);
  EXPECT_EQ(box.hi, bvh.bounds.hi);
  std::size_t want = 0;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g)
    for (std::uint32_t p = 0; p < scene.geometry(g).triangles.size(); ++p) {
      if (scene.geometry(g).degenerate[p]) continue;
      ++want;
      EXPECT_EQ(seen[std::make_pair(g, p)], 1) << "geom " << g << " prim " << p;
    }
  EXPECT_EQ(seen.size(), want);
  EXPECT_EQ(bvh.triangles, want);
  check_wide(bvh, ex);
}

// The binned float builder, and Pierce's binary build collapsed where that is off, at several
// leaf sizes.
TEST(BvhLayouts, DirectWideBuild) {
  const Scene scene = builder_scene();
  const Expected ex(scene, random_rays(scene.bounds(), 60, 8));
  for (const bool binned : {true, false}) {
    for (const int max_leaf : {1, 8, 32}) {
      SCOPED_TRACE(testing::Message() << (binned ? "binned builder" : "binary builder collapsed") << ", max_leaf_size "
                                      << max_leaf);
      BvhBuildOptions opts;
      opts.float_areas = binned;
      opts.max_leaf_size = opts.wide_max_leaf_size = max_leaf;
      check_direct_build(scene, ex, opts);
    }
  }
}

// Hundreds of triangles with the same centroid: no plane separates them, so the binned builder
// splits them by index until each leaf holds at most wide_max_leaf_size, and the tree stays shallow.
TEST(BvhLayouts, DirectWideBuildOfCoincidentStack) {
  const Scene scene =
      gen::to_scene({gen::duplicated(gen::box({0.2, 0.2, 0.5}, {0.8, 0.8, 1.5}, "stack"), 300, true),
                     gen::random_soup(200, 0.3, 4)});
  const Expected ex(scene, random_rays(scene.bounds(), 40, 5));
  for (const int max_leaf : {1, 16}) {
    SCOPED_TRACE(testing::Message() << "max_leaf_size " << max_leaf);
    BvhBuildOptions opts;
    opts.wide_max_leaf_size = max_leaf;
    check_direct_build(scene, ex, opts);
    const WideBvhf bvh = build_wide_bvh<float>(scene, opts);
    EXPECT_LE(bvh.depth, 12u);  // 3800 triangles: halving by index is at most 12 levels
  }
}

// Above 65 536 references a range is binned in parallel; the bins merge by min, max and sums, and
// every subtree is partitioned by one task, so the BVH is the same bit for bit at any thread count.
TEST(BvhLayouts, BinnedBuildIsTheSameForAnyThreadCount) {
  const Scene scene = gen::to_scene({gen::blob(6)});  // 81 920 triangles
  auto build_with = [&](std::size_t threads) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return build_wide_bvh<float>(scene);
  };
  const WideBvhf one = build_with(1);
  for (const std::size_t threads : {2, 4}) {
    SCOPED_TRACE(testing::Message() << threads << " threads");
    const WideBvhf many = build_with(threads);
    ASSERT_EQ(one.nodes.size(), many.nodes.size());
    ASSERT_EQ(one.blocks.size(), many.blocks.size());
    EXPECT_EQ(one.root, many.root);
    EXPECT_EQ(one.depth, many.depth);
    EXPECT_EQ(std::memcmp(one.nodes.data(), many.nodes.data(), one.nodes.size() * sizeof(WideNode<float>)), 0);
    EXPECT_EQ(std::memcmp(one.blocks.data(), many.blocks.data(), one.blocks.size() * sizeof(TriBlock<float>)), 0);
  }
}

}  // namespace
}  // namespace pierce::test
