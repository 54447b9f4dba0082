#include "pierce/kernel.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cstdio>
#include <mutex>

#include "pierce/bvh_builder.h"
#include "pierce/error.h"

namespace pierce {

namespace {
constexpr std::pair<KernelKind, std::string_view> kNames[] = {
    {KernelKind::epsilon, "epsilon"},
    {KernelKind::embree_restart, "embree-restart"},
    {KernelKind::embree_filter, "embree-filter"},
    {KernelKind::embree_nodecull, "embree-nodecull"},
    {KernelKind::restart, "restart"},
    {KernelKind::queue, "queue"},
    {KernelKind::nodecull, "nodecull"},
    {KernelKind::filter, "filter"},
    {KernelKind::buffered, "buffered"},
    {KernelKind::restart_d, "restart-d"},
    {KernelKind::queue_d, "queue-d"},
    {KernelKind::nodecull_d, "nodecull-d"},
    {KernelKind::filter_d, "filter-d"},
    {KernelKind::buffered_d, "buffered-d"},
};

using Impl = std::variant<EpsilonKernel, EmbreeRestartKernel, EmbreeFilterKernel, EmbreeNodeCullKernel,
                          RestartKernel<float>, QueueKernel<float>, NodeCullKernel<float>, AllHitsKernel<float>,
                          BufferedKernel<float>, RestartKernel<double>, QueueKernel<double>, NodeCullKernel<double>,
                          AllHitsKernel<double>, BufferedKernel<double>>;

Impl make_impl(const Accel& a, KernelKind kind, const KernelOptions& o) {
  switch (kind) {
    case KernelKind::epsilon: return EpsilonKernel(a.embree(), o.epsilon_rel);
    case KernelKind::embree_restart: return EmbreeRestartKernel(a.embree(), o.order);
    case KernelKind::embree_filter: return EmbreeFilterKernel(a.embree(), o.order);
    case KernelKind::embree_nodecull: return EmbreeNodeCullKernel(a.embree(), o.order);
    case KernelKind::restart: return RestartKernel<float>(a.bvh(), o.order);
    case KernelKind::queue: return QueueKernel<float>(a.bvh(), o.order);
    case KernelKind::nodecull: return NodeCullKernel<float>(a.bvh(), o.order);
    case KernelKind::filter: return AllHitsKernel<float>(a.bvh(), o.order);
    case KernelKind::buffered: return BufferedKernel<float>(a.bvh(), o.order);
    case KernelKind::restart_d: return RestartKernel<double>(a.bvh_double(), o.order);
    case KernelKind::queue_d: return QueueKernel<double>(a.bvh_double(), o.order);
    case KernelKind::nodecull_d: return NodeCullKernel<double>(a.bvh_double(), o.order);
    case KernelKind::filter_d: return AllHitsKernel<double>(a.bvh_double(), o.order);
    case KernelKind::buffered_d: return BufferedKernel<double>(a.bvh_double(), o.order);
  }
  return RestartKernel<float>(a.bvh(), o.order);
}
}  // namespace

std::string_view kernel_name(KernelKind k) {
  for (const auto& [kind, name] : kNames)
    if (kind == k) return name;
  return "?";
}

int kernel_precision_bits(KernelKind k) {
  switch (k) {
    case KernelKind::restart_d:
    case KernelKind::queue_d:
    case KernelKind::nodecull_d:
    case KernelKind::filter_d:
    case KernelKind::buffered_d: return 53;
    default: return 24;
  }
}

std::optional<KernelKind> parse_kernel(std::string_view name) {
  for (const auto& [kind, n] : kNames)
    if (n == name) return kind;
  return std::nullopt;
}

struct Accel::LazyBvhd {
  std::once_flag once;
  Bvhd bvh;
};

Accel::Accel(const Scene& scene)
    : scene_(&scene), bvh_(build_bvh<float>(scene)), bvhd_(std::make_shared<LazyBvhd>()) {
  embree_ = std::make_unique<EmbreeAccel>(scene, bvh_.tris);
}

const Bvhd& Accel::bvh_double() const {
  std::call_once(bvhd_->once, [this] { bvhd_->bvh = build_bvh<double>(*scene_); });
  return bvhd_->bvh;
}

std::string unsupported_reason(const Accel& accel, KernelKind kind) {
  if (!uses_embree(kind)) return {};
  const double m = accel.scene().bounds().max_abs_coord();
  if (!(m > kEmbreeMaxCoord)) return {};
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "kernel %s: the scene has coordinates up to %.3g, beyond what Embree's BVH holds (%.3g); "
                "use a Pierce kernel (restart, queue, nodecull, filter, buffered) for this model",
                std::string(kernel_name(kind)).c_str(), m, kEmbreeMaxCoord);
  return buf;
}

namespace {
KernelKind checked_kind(const Accel& accel, KernelKind kind) {
  if (std::string why = unsupported_reason(accel, kind); !why.empty()) throw InputError(why);
  return kind;
}
}  // namespace

HitIterator::HitIterator(const Accel& accel, KernelKind kind, const KernelOptions& opts)
    : kind_(checked_kind(accel, kind)), impl_(make_impl(accel, kind, opts)) {}

void collect_hits(HitIterator& it, const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
  it.begin(ray, max_hits);
  Hit h;
  std::size_t n = 0;
  while ((max_hits == 0 || n < max_hits) && it.next(h)) {
    out.push_back(h);
    ++n;
  }
}

bool trace_batch(const Accel& accel, KernelKind kind, const std::vector<Ray>& rays, std::size_t max_hits,
                 std::vector<std::vector<Hit>>& result, const KernelOptions& opts,
                 const std::function<bool(std::size_t)>& progress) {
  result.assign(rays.size(), {});
  tbb::enumerable_thread_specific<HitIterator> iters([&] { return HitIterator(accel, kind, opts); });
  std::atomic<std::size_t> done{0};
  std::atomic<bool> cancelled{false};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](const auto& range) {
    if (cancelled.load(std::memory_order_relaxed)) return;
    HitIterator& it = iters.local();
    for (std::size_t i = range.begin(); i != range.end(); ++i) collect_hits(it, rays[i], max_hits, result[i]);
    const std::size_t d = done.fetch_add(range.size()) + range.size();
    if (progress && !progress(d)) cancelled = true;
  });
  return !cancelled;
}

}  // namespace pierce
