#pragma once
// What every kernel on Pierce's wide BVH holds and does the same way: the BVH, the hit order, the
// SIMD level (chosen once), the prepared ray, the depth-first stack of pending nodes, the counter
// policy, and how a traversal is seeded and run. The kernels differ only in their traversal policy
// and in what they keep between next() calls.
#include <algorithm>
#include <limits>
#include <type_traits>
#include <vector>

#include "pierce/hit.h"
#include "pierce/traverse.h"

namespace pierce {

// The last hit a kernel returned: the next one must come after it in the total order, so the
// search resumes at its t and skips what ranks at or before it.
struct ResumeAfter {
  Hit last;
  bool have = false;

  void clear() { have = false; }
  void set(const Hit& h) { last = h, have = true; }
  // True if `key` was returned already or ranks before what was.
  bool done(const HitOrder& order, const HitKey& key) const { return have && !order.less(last, key); }
  template <typename T>
  T lower(T tmin) const {
    return have ? std::max(tmin, T(last.t)) : tmin;
  }
};

// Every hit in the ray's [tmin, tmax], in the order the traversal meets them (breadth first: the
// order does not matter, the caller sorts): `filter`'s traversal, and `queue`'s breadth-first pass.
template <typename T>
struct GatherInRange : TraversalPolicy<T> {
  static constexpr bool kAnyOrder = true;
  const TraversalRay<T>& r;
  std::vector<Hit>& hits;
  GatherInRange(const TraversalRay<T>& ray, std::vector<Hit>& out) : r(ray), hits(out) {}
  T lo() const { return r.tmin; }
  T hi() const { return r.tmax; }
  // Nothing is ever culled (a node is pushed only if it is entered by hi()): the loop's check
  // against +inf folds away.
  T cull_bound() const { return std::numeric_limits<T>::infinity(); }
  void hit(const TriBlock<T>& b, int l, const TriangleHit<T>& h) { hits.push_back(make_hit(b, l, h)); }
};

// C: the counter policy (counters.h).
template <typename T, class C>
class WideKernel {
 public:
  C counters;

  // Every own-BVH kernel is constructed so (the kernels inherit it).
  explicit WideKernel(const WideBvh<T>& bvh, HitOrder order = {}) : bvh_(&bvh), order_(order), simd_(simd_level()) {
    pending_.reserve(bvh.stack_capacity());
  }

 protected:

  // The ray's TraversalRay and, at a SIMD level, its SimdRay: once per ray, however many
  // traversals it takes (restart's, queue's and buffered's later passes reuse them).
  void prepare(const Ray& ray) {
    if constexpr (kHasSimdRay) {
      if (simd_ != SimdLevel::scalar) {
        simd::prepare_simd_ray(ray, bvh_->scene_max_abs, ray_, simd_ray_);
        return;
      }
    }
    ray_.assign(ray, bvh_->scene_max_abs);
  }
  bool traceable() const { return !bvh_->empty() && ray_.valid(); }
  // A new traversal of [lo, hi] from the root.
  void seed_root(T lo, T hi) {
    pending_.clear();
    seed(*bvh_, ray_, lo, hi, pending_, counters);
  }
  // Every hit of the prepared ray in [tmin, tmax], appended to `out` in the order the traversal
  // met them: one traversal, breadth first (GatherInRange). `filter` and `queue`'s gathering pass
  // sort them after it, each as far as its caller needs. Inlined into both, so that `queue`'s
  // gathering pass costs no call more than `filter`'s.
  [[gnu::always_inline]] void gather_in_range(std::vector<Hit>& out) {
    seed_root(ray_.tmin, ray_.tmax);
    GatherInRange<T> p{ray_, out};
    run(p);
  }
  // Traverses until every pending node is done (true) or the policy suspends (false).
  template <class Policy>
  bool run(Policy& p) {
    // (At the scalar level traverse_at does not read the SimdRay, which prepare() then left alone.)
    if constexpr (kHasSimdRay) return detail::traverse_at(simd_, *bvh_, ray_, &simd_ray_, pending_, p, counters);
    return detail::traverse_at(simd_, *bvh_, ray_, nullptr, pending_, p, counters);
  }

  const WideBvh<T>* bvh_;
  HitOrder order_;
  SimdLevel simd_;
  TraversalRay<T> ray_;
  static constexpr bool kHasSimdRay = std::is_same_v<T, float>;  // the SIMD levels run on float
  struct NoSimdRay {};
  [[no_unique_address]] std::conditional_t<kHasSimdRay, simd::SimdRay, NoSimdRay> simd_ray_{};  // made by prepare()
  NodeStack<T> pending_;
};

}  // namespace pierce
