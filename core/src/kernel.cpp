#include "pierce/kernel.h"


#include <algorithm>
#include <array>
#include <cstdio>
#include <mutex>
#include <optional>
#include <type_traits>

#include "pierce/bvh_builder.h"
#include "pierce/error.h"
#include "pierce/parallel_for_items.h"

namespace pierce {

namespace {
using Impl = HitIterator::Impl;

template <class T>
const WideBvh<T>& wide_bvh_of(const Accel& a) {
  if constexpr (std::is_same_v<T, double>)
    return a.wide_double();
  else
    return a.wide();
}

template <class T, class C, class... Own>
Impl make_own(KernelTypeList<Own...>, const Accel& a, KernelId id, const HitOrder& order) {
  std::optional<Impl> out;
  ((Own::id == id && (out.emplace(std::in_place_type<typename Own::template type<T, C>>, wide_bvh_of<T>(a), order),
                      true)) ||
   ...);
  return std::move(*out);
}

template <class... Embree>
Impl make_embree(KernelTypeList<Embree...>, const Accel& a, KernelId id, const KernelOptions& o) {
  std::optional<Impl> out;
  ((Embree::id == id && (out.emplace(std::in_place_type<typename Embree::type>, a.embree(), o), true)) || ...);
  return std::move(*out);
}

Impl make_impl(const Accel& a, KernelKind kind, const KernelOptions& o) {
  if (uses_embree(kind)) return make_embree(EmbreeKernelTypes{}, a, kind.id, o);
  const bool dbl = kind.precision == Precision::float64;
  if (o.count)
    return dbl ? make_own<double, Counters>(OwnBvhKernelTypes{}, a, kind.id, o.order)
               : make_own<float, Counters>(OwnBvhKernelTypes{}, a, kind.id, o.order);
  return dbl ? make_own<double, NoCounters>(OwnBvhKernelTypes{}, a, kind.id, o.order)
             : make_own<float, NoCounters>(OwnBvhKernelTypes{}, a, kind.id, o.order);
}

// "<name>-d" for every kernel on Pierce's BVH, in table order.
const std::array<std::string, std::size(kKernelTable)>& double_names() {
  static const auto names = [] {
    std::array<std::string, std::size(kKernelTable)> out;
    for (std::size_t i = 0; i < out.size(); ++i)
      if (kKernelTable[i].structure == KernelStructure::own_bvh) out[i] = std::string(kKernelTable[i].name) + "-d";
    return out;
  }();
  return names;
}

std::string own_bvh_kernel_list() {
  std::string s;
  for (const KernelInfo& row : kKernelTable)
    if (row.structure == KernelStructure::own_bvh) s += (s.empty() ? "" : ", ") + std::string(row.name);
  return s;
}
}  // namespace

std::string_view kernel_name(KernelKind k) {
  if (k.precision == Precision::float64) return double_names()[std::size_t(k.id)];
  return kernel_info(k.id).name;
}

std::optional<KernelKind> parse_kernel(std::string_view name) {
  for (const KernelInfo& row : kKernelTable) {
    if (row.name == name) return KernelKind(row.id);
    if (double_names()[std::size_t(row.id)] == name) return KernelKind(row.id, Precision::float64);
  }
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
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "kernel %s: the scene has coordinates up to %.3g, beyond what Embree's BVH holds (%.3g); "
                "use a Pierce kernel (%s) for this model",
                std::string(kernel_name(kind)).c_str(), m, kEmbreeMaxCoord, own_bvh_kernel_list().c_str());
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

namespace {

// All hits of `ray` (up to max_hits, 0 = all) appended to `out`, the kernel's begin() and next()
// inlined into one loop.
template <class Kernel>
void collect_with(Kernel& k, const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
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
}

}  // namespace

void HitIterator::collect(const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
  std::visit([&](auto& k) { collect_with(k, ray, max_hits, out); }, impl_);
}

void HitIterator::collect_each(std::span<const Ray> rays, std::size_t max_hits, std::vector<Hit>& out,
                               std::size_t* counts) {
  std::visit(
      [&](auto& k) {
        for (std::size_t i = 0; i < rays.size(); ++i) {
          const std::size_t before = out.size();
          collect_with(k, rays[i], max_hits, out);
          counts[i] = out.size() - before;
        }
      },
      impl_);
}

void collect_hits(HitIterator& it, const Ray& ray, std::size_t max_hits, std::vector<Hit>& out) {
  it.collect(ray, max_hits, out);
}

bool trace_batch(const Accel& accel, KernelKind kind, std::span<const Ray> rays, std::size_t max_hits,
                 HitBatch& out, const KernelOptions& opts, const Progress& progress) {
  return trace_batch(accel, kind, columns_of(rays), max_hits, out, opts, progress);
}

bool trace_batch(const Accel& accel, KernelKind kind, const RayColumns& rays, std::size_t max_hits,
                 HitBatch& out, const KernelOptions& opts, const Progress& progress) {
  const std::size_t n = rays.size();
  out.offsets.assign(n + 1, 0);
  out.hits.clear();
  // Pass 1: each thread appends the hits of its chunks of rays to its own buffer and notes where
  // each chunk starts there; ray i's hit count goes to offsets[i + 1].
  struct Chunk {
    std::size_t first_ray, end_ray, first_hit;
  };
  // A chunk of rays is traced with one collect_each: in place when the columns are an array of
  // Rays, else built from the columns into the worker's fixed buffer, kGrain at a time (TBB's
  // chunks are about kGrain rays, sometimes more).
  constexpr std::size_t kGrain = 256;
  struct Worker {
    HitIterator it;
    std::vector<Hit> hits;
    std::vector<Chunk> chunks;
    std::array<Ray, kGrain> rays{};
  };
  tbb::enumerable_thread_specific<Worker> workers([&] { return Worker{HitIterator(accel, kind, opts), {}, {}, {}}; });
  ProgressTracker tracker(n, progress);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain), [&](const tbb::blocked_range<std::size_t>& r) {
    if (tracker.stopped()) return;
    Worker& w = workers.local();
    w.chunks.push_back({r.begin(), r.end(), w.hits.size()});
    if (rays.as_rays) {
      w.it.collect_each({rays.as_rays + r.begin(), r.size()}, max_hits, w.hits, out.offsets.data() + r.begin() + 1);
    } else {
      for (std::size_t first = r.begin(); first < r.end(); first += kGrain) {
        const std::size_t count = std::min(kGrain, r.end() - first);
        for (std::size_t i = 0; i < count; ++i) w.rays[i] = rays[first + i];
        w.it.collect_each({w.rays.data(), count}, max_hits, w.hits, out.offsets.data() + first + 1);
      }
    }
    tracker.add(r.size());
  });
  for (std::size_t i = 0; i < n; ++i) out.offsets[i + 1] += out.offsets[i];
  // Pass 2: the chunks are appended in ray order (no zero-fill of the result). When one thread
  // traced every ray in order, as on one core, its buffer is the result and is moved.
  std::vector<std::pair<Worker*, Chunk>> chunks;
  for (Worker& w : workers)
    for (const Chunk& c : w.chunks) chunks.emplace_back(&w, c);
  std::sort(chunks.begin(), chunks.end(),
            [](const auto& a, const auto& b) { return a.second.first_ray < b.second.first_ray; });
  const bool one_buffer_in_order =
      !chunks.empty() && std::all_of(chunks.begin(), chunks.end(), [&](const auto& c) {
        return c.first == chunks.front().first && c.second.first_hit == out.offsets[c.second.first_ray];
      });
  if (one_buffer_in_order && chunks.front().first->hits.size() == out.offsets[n]) {
    out.hits = std::move(chunks.front().first->hits);
  } else {
    out.hits.reserve(out.offsets[n]);
    for (const auto& [w, c] : chunks) {
      const auto from = w->hits.begin() + std::ptrdiff_t(c.first_hit);
      out.hits.insert(out.hits.end(), from, from + std::ptrdiff_t(out.offsets[c.end_ray] - out.offsets[c.first_ray]));
    }
  }
  return !tracker.stopped();
}

}  // namespace pierce
