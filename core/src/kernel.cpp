#include "pierce/kernel.h"

#include <cstdio>
#include <mutex>

#include "pierce/bvh_builder.h"
#include "pierce/error.h"
#include "pierce/parallel_for_items.h"

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

using Impl = HitIterator::Impl;

template <class C>
HitIterator::OwnBvhKernels<C> make_own(const Accel& a, KernelKind kind, const HitOrder& o) {
  switch (kind) {
    case KernelKind::queue: return QueueKernel<float, C>(a.wide(), o);
    case KernelKind::nodecull: return NodeCullKernel<float, C>(a.wide(), o);
    case KernelKind::filter: return AllHitsKernel<float, C>(a.wide(), o);
    case KernelKind::buffered: return BufferedKernel<float, C>(a.wide(), o);
    case KernelKind::restart_d: return RestartKernel<double, C>(a.wide_double(), o);
    case KernelKind::queue_d: return QueueKernel<double, C>(a.wide_double(), o);
    case KernelKind::nodecull_d: return NodeCullKernel<double, C>(a.wide_double(), o);
    case KernelKind::filter_d: return AllHitsKernel<double, C>(a.wide_double(), o);
    case KernelKind::buffered_d: return BufferedKernel<double, C>(a.wide_double(), o);
    case KernelKind::restart:
    default: return RestartKernel<float, C>(a.wide(), o);  // the Embree kinds never get here
  }
}

Impl make_impl(const Accel& a, KernelKind kind, const KernelOptions& o) {
  switch (kind) {
    case KernelKind::epsilon: return EpsilonKernel(a.embree(), o.epsilon_rel, o.count);
    case KernelKind::embree_restart: return EmbreeRestartKernel(a.embree(), o.order, o.count);
    case KernelKind::embree_filter: return EmbreeFilterKernel(a.embree(), o.order, o.count);
    case KernelKind::embree_nodecull: return EmbreeNodeCullKernel(a.embree(), o.order, o.count);
    default: {
      auto to_impl = [](auto&& k) -> Impl { return std::move(k); };
      if (o.count) return std::visit(to_impl, make_own<Counters>(a, kind, o.order));
      return std::visit(to_impl, make_own<NoCounters>(a, kind, o.order));
    }
  }
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

struct Accel::Lazy {
  std::once_flag bvh_once, embree_once, wide_double_once;
  Bvhf bvh;
  std::unique_ptr<EmbreeAccel> embree;
  WideBvhd wide_double;
};

Accel::Accel(const Scene& scene)
    : scene_(&scene), wide_(build_wide_bvh<float>(scene)), lazy_(std::make_unique<Lazy>()) {}

Accel::~Accel() = default;

const Bvhf& Accel::bvh() const {
  std::call_once(lazy_->bvh_once, [this] { lazy_->bvh = build_bvh<float>(*scene_); });
  return lazy_->bvh;
}

const EmbreeAccel& Accel::embree() const {
  std::call_once(lazy_->embree_once, [this] {
    // The float BVH is built only if an exact Embree kernel asks for the exact scene.
    lazy_->embree = std::make_unique<EmbreeAccel>(
        *scene_, [this]() -> const HugePageVector<Triangle<float>>& { return bvh().tris; });
  });
  return *lazy_->embree;
}

const WideBvhd& Accel::wide_double() const {
  std::call_once(lazy_->wide_double_once, [this] { lazy_->wide_double = build_wide_bvh<double>(*scene_); });
  return lazy_->wide_double;
}

std::size_t Accel::memory_bytes() const {
  return wide_.memory_bytes() + lazy_->bvh.memory_bytes() + lazy_->wide_double.memory_bytes();
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

void HitIterator::begin(const Ray& ray, std::size_t max_hits) {
  std::visit([&](auto& k) { k.begin(ray, max_hits); }, impl_);
}

bool HitIterator::next(Hit& out) {
  return std::visit([&](auto& k) { return k.next(out); }, impl_);
}

Counters HitIterator::counters() const {
  return std::visit([](const auto& k) { return k.counters.totals(); }, impl_);
}

void HitIterator::collect(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
  // One dispatch per ray, with the kernel's begin() and next() inlined into one loop.
  std::visit(
      [&](auto& k) {
        // A kernel that gathers its hits (`filter`, `queue`'s gathering pass) puts them in `out`
        // itself, sorted; only the cut to max_hits is left.
        if constexpr (requires { k.begin_into(ray, max_hits, out); }) {
          const std::size_t first = out.size();
          if (k.begin_into(ray, max_hits, out)) {
            if (max_hits != 0 && out.size() - first > max_hits) out.resize(first + max_hits);
            return;
          }
        } else {
          k.begin(ray, max_hits);
        }
        Hit h;
        std::size_t n = 0;
        while ((max_hits == 0 || n < max_hits) && k.next(h)) {
          out.push_back(h);
          ++n;
        }
      },
      impl_);
}

void collect_hits(HitIterator& it, const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
  it.collect(ray, max_hits, out);
}

bool trace_batch(const Accel& accel, KernelKind kind, const std::vector<Ray>& rays, std::size_t max_hits,
                 std::vector<std::vector<Hit>>& result, const KernelOptions& opts,
                 const Progress& progress) {
  result.assign(rays.size(), {});
  tbb::enumerable_thread_specific<HitIterator> iters([&] { return HitIterator(accel, kind, opts); });
  return parallel_for_items(rays.size(), 256, iters, progress,
                            [&](HitIterator& it, std::size_t i) { collect_hits(it, rays[i], max_hits, result[i]); });
}

}  // namespace pierce
