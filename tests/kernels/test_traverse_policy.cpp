// traverse() with a policy written by a user of the library: Gribble's every-node callback
// (node()) and leaf-node callback (hit()) see the traversal, and a plain "gather everything" policy
// returns exactly what the filter kernel returns. Also on a heap (front-to-back) container.
#include <algorithm>

#include "pierce/traverse.h"
#include "test_util.h"

namespace pierce::test {
namespace {

struct GatherWithCallbacks : TraversalPolicy<float> {
  const TraversalRay<float>& r;
  std::vector<Hit> hits;
  std::size_t nodes = 0, leaves = 0;
  float last_tn = -std::numeric_limits<float>::infinity();
  bool front_to_back = true;  // every node entered no earlier than the one before
  explicit GatherWithCallbacks(const TraversalRay<float>& ray) : r(ray) {}
  float lo() const { return r.tmin; }
  float hi() const { return r.tmax; }
  float cull_bound() const { return r.tmax; }
  void node(NodeRef ref, float tn) {
    ++nodes;
    leaves += is_leaf(ref) ? 1 : 0;
    front_to_back = front_to_back && tn >= last_tn;
    last_tn = tn;
  }
  void hit(const TriBlock<float>& b, int lane, const TriangleHit<float>& th) { hits.push_back(make_hit(b, lane, th)); }
};

template <class Container>
GatherWithCallbacks run(const Accel& accel, const Ray& ray, Container& pending) {
  const TraversalRay<float> r = TraversalRay<float>::make(ray, accel.wide().scene_max_abs);
  GatherWithCallbacks p(r);
  Counters c;
  pending.clear();
  seed(accel.wide(), r, r.tmin, r.tmax, pending, c);
  EXPECT_TRUE(traverse(simd_level(), accel.wide(), r, pending, p, c));
  std::sort(p.hits.begin(), p.hits.end(), HitOrder{});
  return p;
}

TEST(TraversePolicy, CallbacksSeeEveryNodeAndHit) {
  auto meshes = gen::stacked_plates(8);
  meshes.push_back(gen::translated(gen::blob(3), {0.5, 0.5, 2.0}));
  const auto w = make_world(meshes);
  const std::vector<Ray> rays = random_rays(w->scene.bounds(), 200, 21);
  HitIterator filter(w->accel, KernelKind::filter);
  NodeStack<float> stack;
  stack.reserve(w->accel.wide().stack_capacity());
  NodeHeap<float> heap;
  std::size_t rays_with_hits = 0;
  for (const Ray& ray : rays) {
    const std::vector<Hit> want = kernel_hits(filter, ray);
    const GatherWithCallbacks depth_first = run(w->accel, ray, stack);
    const GatherWithCallbacks front_to_back = run(w->accel, ray, heap);
    EXPECT_TRUE(same_hits(want, depth_first.hits)) << str(ray);
    EXPECT_TRUE(same_hits(want, front_to_back.hits)) << str(ray);
    EXPECT_TRUE(front_to_back.front_to_back) << "a heap visits nodes by entry distance: " << str(ray);
    EXPECT_EQ(depth_first.nodes, front_to_back.nodes) << "the same nodes, in another order: " << str(ray);
    if (want.empty()) continue;
    ++rays_with_hits;
    EXPECT_GT(depth_first.leaves, 0u);
    EXPECT_GE(depth_first.nodes, depth_first.leaves);
  }
  EXPECT_GT(rays_with_hits, 50u);
}

// A policy that takes every hit of a fixed range is traversed breadth first (FifoCursor), which can
// outgrow a depth-first stack: from a one-entry stack, the buffer must grow and the hits and visited
// nodes stay the filter's.
struct GatherAnyOrder : GatherWithCallbacks {
  static constexpr bool kAnyOrder = true;
  using GatherWithCallbacks::GatherWithCallbacks;
};

TEST(TraversePolicy, AnyOrderGrowsItsStackAndVisitsTheSameNodes) {
  const auto w = make_world({gen::random_soup(3000, 0.2, 5)});
  const std::vector<Ray> rays = random_rays(w->scene.bounds(), 200, 8);
  HitIterator filter(w->accel, KernelKind::filter);
  NodeStack<float> deep, tiny;
  deep.reserve(w->accel.wide().stack_capacity());
  tiny.reserve(1);
  const std::size_t tiny_start = tiny.capacity();
  std::size_t hits = 0;
  for (const Ray& ray : rays) {
    const std::vector<Hit> want = kernel_hits(filter, ray);
    const TraversalRay<float> r = TraversalRay<float>::make(ray, w->accel.wide().scene_max_abs);
    GatherWithCallbacks depth_first(r);
    GatherAnyOrder delayed(r);
    Counters c;
    deep.clear();
    seed(w->accel.wide(), r, r.tmin, r.tmax, deep, c);
    ASSERT_TRUE(traverse(simd_level(), w->accel.wide(), r, deep, depth_first, c));
    tiny.clear();
    seed(w->accel.wide(), r, r.tmin, r.tmax, tiny, c);
    ASSERT_TRUE(traverse(simd_level(), w->accel.wide(), r, tiny, delayed, c));
    std::sort(delayed.hits.begin(), delayed.hits.end(), HitOrder{});
    EXPECT_TRUE(same_hits(want, delayed.hits)) << str(ray);
    EXPECT_EQ(delayed.nodes, depth_first.nodes) << "the same nodes, in another order: " << str(ray);
    hits += want.size();
  }
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(tiny.capacity(), tiny_start) << "the one-entry stack had to grow";
}

}  // namespace
}  // namespace pierce::test
