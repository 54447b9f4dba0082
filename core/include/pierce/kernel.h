#pragma once
// The kernels behind one iterator API: begin(ray[, max_hits]) then next(hit) until false.
// Every kernel except `epsilon` returns exactly the same hits in the same total order.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "pierce/progress.h"
#include "pierce/embree_limits.h"
#include "pierce/kernels/all_hits.h"
#include "pierce/kernels/buffered.h"
#include "pierce/kernels/embree_kernels.h"
#include "pierce/kernels/node_cull.h"
#include "pierce/kernels/queue.h"
#include "pierce/kernels/restart.h"
#include "pierce/wide_bvh.h"

namespace pierce {

enum class KernelKind {
  epsilon,
  embree_restart,
  embree_filter,
  embree_nodecull,
  restart,
  queue,
  nodecull,
  filter,
  buffered,
  // The same kernels on a double-precision BVH of the double input (built on first use).
  restart_d,
  queue_d,
  nodecull_d,
  filter_d,
  buffered_d,
};

inline constexpr KernelKind kAllKernels[] = {
    KernelKind::epsilon,  KernelKind::embree_restart, KernelKind::embree_filter,
    KernelKind::embree_nodecull, KernelKind::restart, KernelKind::queue,
    KernelKind::nodecull, KernelKind::filter,         KernelKind::buffered,
};

// Not in kAllKernels: double precision answers for the double input, which can differ from
// the float kernels' answers where the input is not representable in float.
inline constexpr KernelKind kDoubleKernels[] = {KernelKind::restart_d, KernelKind::queue_d, KernelKind::nodecull_d,
                                                KernelKind::filter_d, KernelKind::buffered_d};

std::string_view kernel_name(KernelKind k);
// Significand bits of the kernel's arithmetic: 24 (float) or 53 (double).
int kernel_precision_bits(KernelKind k);
std::optional<KernelKind> parse_kernel(std::string_view name);
inline bool is_exact(KernelKind k) { return k != KernelKind::epsilon; }
inline bool uses_embree(KernelKind k) {
  return k == KernelKind::epsilon || k == KernelKind::embree_restart || k == KernelKind::embree_filter ||
         k == KernelKind::embree_nodecull;
}

struct KernelOptions {
  HitOrder order;
  double epsilon_rel = 1e-5;  // epsilon kernel only: relative to the scene diagonal
  // The counting variant of the kernel: HitIterator::counters() then reports its work (node tests,
  // traversal steps, primitive tests, valid hits). Off, counting costs nothing.
  bool count = false;
};

// A scene with the acceleration structures the kernels need. The float wide BVH is built with the
// Accel (every Pierce kernel uses it), directly eight wide: no binary tree is built for it. The
// rest is built on first use (thread-safe): the binary float BVH (Embree's exact
// user geometry), the double wide BVH (the *_d kernels, CSG) and Embree's scenes (embree-*,
// epsilon). So a run of an own-BVH kernel builds no Embree scene, no double BVH and no binary tree.
class Accel {
 public:
  explicit Accel(const Scene& scene);
  ~Accel();
  // Neither copyable nor movable: the Embree scenes keep pointers to the binary BVH's triangles.
  Accel(const Accel&) = delete;
  Accel& operator=(const Accel&) = delete;
  const Scene& scene() const { return *scene_; }
  const WideBvhf& wide() const { return wide_; }
  // The binary float BVH, built on the first call.
  const Bvhf& bvh() const;
  const EmbreeAccel& embree() const;
  // The double-precision wide BVH (the *_d kernels, CSG's box queries), built on the first call.
  const WideBvhd& wide_double() const;
  // Bytes held by the structures built so far.
  std::size_t memory_bytes() const;

 private:
  struct Lazy;
  const Scene* scene_;
  WideBvhf wide_;
  std::unique_ptr<Lazy> lazy_;
};

// One kernel instance; reusable across rays (no allocation once warm). Not thread-safe:
// use one per thread.
// Empty if `kind` can trace the accel's scene; otherwise why not (an Embree kernel on a scene
// beyond kEmbreeMaxCoord). HitIterator throws InputError with this message.
std::string unsupported_reason(const Accel& accel, KernelKind kind);

namespace detail {
template <class... V>
struct VariantCat;
template <class... A, class... B, class... C>
struct VariantCat<std::variant<A...>, std::variant<B...>, std::variant<C...>> {
  using type = std::variant<A..., B..., C...>;
};
template <class... V>
using variant_cat_t = typename VariantCat<V...>::type;
}  // namespace detail

class HitIterator {
 public:
  HitIterator(const Accel& accel, KernelKind kind, const KernelOptions& opts = {});
  // Out of line: the kernels (and their traversal at every SIMD level) are compiled once, in
  // kernel.cpp, not in every file that traces rays.
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);
  // begin(ray, max_hits), then every next() hit (up to max_hits, 0 = all) appended to `out`.
  void collect(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out);
  KernelKind kind() const { return kind_; }
  // The work done since construction; all zero unless constructed with KernelOptions::count.
  Counters counters() const;

  // Every kernel; those on Pierce's BVH in their plain and their counting variant (the Embree
  // ones decide at run time), in one flat variant so that a call dispatches once.
  template <class C>
  using OwnBvhKernels = std::variant<RestartKernel<float, C>, QueueKernel<float, C>, NodeCullKernel<float, C>,
                                     AllHitsKernel<float, C>, BufferedKernel<float, C>, RestartKernel<double, C>,
                                     QueueKernel<double, C>, NodeCullKernel<double, C>, AllHitsKernel<double, C>,
                                     BufferedKernel<double, C>>;
  using EmbreeKernels = std::variant<EpsilonKernel, EmbreeRestartKernel, EmbreeFilterKernel, EmbreeNodeCullKernel>;
  using Impl = detail::variant_cat_t<EmbreeKernels, OwnBvhKernels<NoCounters>, OwnBvhKernels<Counters>>;

 private:
  KernelKind kind_;
  Impl impl_;
};

// All hits of one ray (up to max_hits, 0 = all) appended to `out`.
void collect_hits(HitIterator& it, const Ray& ray, std::size_t max_hits, std::vector<Hit>& out);

// Runs many rays on all cores (parallel_for_items). result[i] holds ray i's hits, identical
// whatever the thread count. `progress(done, total)` is called from worker threads with the
// number of rays finished so far; returning false cancels (remaining rays keep empty results)
// and the function returns false.
bool trace_batch(const Accel& accel, KernelKind kind, const std::vector<Ray>& rays, std::size_t max_hits,
                 std::vector<std::vector<Hit>>& result, const KernelOptions& opts = {},
                 const Progress& progress = {});

}  // namespace pierce
