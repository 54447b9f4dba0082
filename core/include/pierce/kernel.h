#pragma once
// The kernels behind one iterator API: begin(ray[, max_hits]) then next(hit) until false.
// Every exact kernel returns exactly the same hits in the same total order (kernel_kind.h lists
// them and says which are exact).
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "pierce/embree_limits.h"
#include "pierce/hit_batch.h"
#include "pierce/kernel_kind.h"
#include "pierce/kernel_options.h"
#include "pierce/kernels/all_hits.h"
#include "pierce/kernels/buffered.h"
#include "pierce/kernels/embree_kernels.h"
#include "pierce/kernels/node_cull.h"
#include "pierce/kernels/queue.h"
#include "pierce/kernels/restart.h"
#include "pierce/progress.h"
#include "pierce/ray_columns.h"
#include "pierce/wide_bvh.h"

namespace pierce {

// The kernel types, one entry per row of kKernelTable. A kernel on Pierce's BVH is a template on
// its precision T and its counters policy C; an Embree kernel is one class that counts at run time.
template <KernelId Id, template <class T, class C> class Kernel>
struct OwnBvhKernel {
  static constexpr KernelId id = Id;
  template <class T, class C>
  using type = Kernel<T, C>;
};
template <KernelId Id, class Kernel>
struct EmbreeKernel {
  static constexpr KernelId id = Id;
  using type = Kernel;
};
template <class... Entries>
struct KernelTypeList {};

using OwnBvhKernelTypes =
    KernelTypeList<OwnBvhKernel<KernelId::restart, RestartKernel>, OwnBvhKernel<KernelId::queue, QueueKernel>,
                   OwnBvhKernel<KernelId::nodecull, NodeCullKernel>, OwnBvhKernel<KernelId::filter, AllHitsKernel>,
                   OwnBvhKernel<KernelId::buffered, BufferedKernel>>;
using EmbreeKernelTypes =
    KernelTypeList<EmbreeKernel<KernelId::epsilon, EpsilonKernel>,
                   EmbreeKernel<KernelId::embree_restart, EmbreeRestartKernel>,
                   EmbreeKernel<KernelId::embree_filter, EmbreeFilterKernel>,
                   EmbreeKernel<KernelId::embree_nodecull, EmbreeNodeCullKernel>>;

namespace detail {
// One flat variant of every kernel type (own-BVH ones at both precisions, plain and counting), so
// that a call dispatches once.
template <class Own, class Embree>
struct KernelVariant;
template <class... Own, class... Embree>
struct KernelVariant<KernelTypeList<Own...>, KernelTypeList<Embree...>> {
  using type = std::variant<typename Embree::type..., typename Own::template type<float, NoCounters>...,
                            typename Own::template type<double, NoCounters>...,
                            typename Own::template type<float, Counters>...,
                            typename Own::template type<double, Counters>...>;
};
}  // namespace detail

// A scene with the acceleration structures the kernels need. The float wide BVH is built with the
// Accel (every Pierce kernel uses it), directly eight wide: no binary tree is built for it. The
// rest is built on first use (thread-safe): the binary float BVH (Embree's exact
// user geometry), the double wide BVH (the double-precision kernels, CSG) and Embree's scenes (embree-*,
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
  // The double-precision wide BVH (the double-precision kernels, CSG's box queries), built on the first call.
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

class HitIterator {
 public:
  HitIterator(const Accel& accel, KernelKind kind, const KernelOptions& opts = {});
  // Out of line: the kernels (and their traversal at every SIMD level) are compiled once, in
  // kernel.cpp, not in every file that traces rays.
  void begin(const Ray& ray, std::size_t max_hits = 0);
  bool next(Hit& out);
  // begin(ray, max_hits), then every next() hit (up to max_hits, 0 = all) appended to `out`.
  void collect(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out);
  // collect() for each ray in turn, ray i's hit count into counts[i]: one dispatch for them all.
  void collect_each(std::span<const Ray> rays, std::size_t max_hits, std::vector<Hit>& out, std::size_t* counts);
  KernelKind kind() const { return kind_; }
  // The work done since construction; all zero unless constructed with KernelOptions::count.
  Counters counters() const;

  using Impl = detail::KernelVariant<OwnBvhKernelTypes, EmbreeKernelTypes>::type;

 private:
  KernelKind kind_;
  Impl impl_;
};

// All hits of one ray (up to max_hits, 0 = all) appended to `out`.
void collect_hits(HitIterator& it, const Ray& ray, std::size_t max_hits, std::vector<Hit>& out);

// Runs many rays on all cores; every ray's hits (up to max_hits, 0 = all) go into one HitBatch,
// identical whatever the thread count. The rays are read from their columns where the caller
// keeps them: each thread builds the rays of a chunk in its own fixed buffer and traces them with
// one collect_each. Each thread appends to its own hit buffer, and the buffers are merged once:
// nothing is allocated per ray. `progress(done, total)` is called from worker threads with the
// number of rays finished so far; returning false cancels (the rays not traced get no hits) and
// the function returns false.
bool trace_batch(const Accel& accel, KernelKind kind, const RayColumns& rays, std::size_t max_hits,
                 HitBatch& out, const KernelOptions& opts = {}, const Progress& progress = {});
// trace_batch on columns_of(rays): the same HitBatch.
bool trace_batch(const Accel& accel, KernelKind kind, std::span<const Ray> rays, std::size_t max_hits,
                 HitBatch& out, const KernelOptions& opts = {}, const Progress& progress = {});

}  // namespace pierce
