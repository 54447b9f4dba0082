#include "pierce/bvh_builder.h"

#include <algorithm>
#include <array>
#include <limits>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <numeric>

#include <embree3/rtcore.h>
#include <tbb/parallel_invoke.h>

#include "embree_build_support.h"

#include <cmath>

namespace pierce {

namespace {

constexpr int kMaxBins = 64;
// Subtrees of at least this many triangles build their two children in parallel.
constexpr std::uint32_t kParallelGrain = 4096;

// SAH bin of a centroid coordinate. Near the float range the centroid or the extent overflow to
// infinity and the position becomes NaN or infinite: clamp without converting those to int
// (undefined behaviour; found by the kernel fuzzer).
inline int bin_index(double c, double lo, double scale, int nb) {
  const double x = (c - lo) * scale;
  if (!(x > 0.0)) return 0;  // also NaN
  return x < double(nb - 1) ? int(x) : nb - 1;
}

// A triangle as the builder moves it: its box, centroid and index, partitioned in place so every
// pass over a node's triangles reads memory in order.
template <typename T>
struct Ref {
  BBox<T> box;
  Vec3<T> centroid;
  std::uint32_t geom, prim;
};

template <typename T>
struct Split {
  int axis = -1, bin = 0;
  float cost = std::numeric_limits<float>::infinity();
  BBox<T> left, left_centroids, right, right_centroids;
};

template <typename T>
struct Builder {
  const BvhBuildOptions& opts;
  std::vector<Ref<T>> refs;
  // 2m - 1 slots for m triangles, most never written: allocated without initialising, so the
  // pages of the gaps are never touched.
  std::unique_ptr<std::byte[]> slots;
  static_assert(std::is_trivially_destructible_v<BvhNode<T>>);
  BvhNode<T>& node(std::uint32_t i) const {
    return *std::launder(reinterpret_cast<BvhNode<T>*>(slots.get() + std::size_t(i) * sizeof(BvhNode<T>)));
  }

  void bounds_of(std::uint32_t begin, std::uint32_t end, BBox<T>& box, BBox<T>& cbox) const {
    for (std::uint32_t i = begin; i < end; ++i) {
      box.extend(refs[i].box);
      cbox.extend(refs[i].centroid);
    }
  }

  // Best binned SAH split over the three axes, all binned in one pass. Out of line, so the bins
  // are not on the stack while the children are built.
  __attribute__((noinline)) Split<T> best_split(std::uint32_t begin, std::uint32_t end, const BBox<T>& cbox,
                                                int nb) const {
    std::array<std::array<BBox<T>, kMaxBins>, 3> bb{};
    std::array<std::array<std::uint32_t, kMaxBins>, 3> cnt{};
    const Vec3<T> ext = cbox.extent();
    bool active[3];
    double scale[3];
    for (int a = 0; a < 3; ++a) {
      active[a] = ext[a] > T(0);
      scale[a] = active[a] ? double(nb) / double(ext[a]) : 0.0;
    }
    for (std::uint32_t i = begin; i < end; ++i) {
      const Ref<T>& r = refs[i];
      for (int a = 0; a < 3; ++a) {
        if (!active[a]) continue;
        const int k = bin_index(r.centroid[a], cbox.lo[a], scale[a], nb);
        bb[a][k].extend(r.box);
        ++cnt[a][k];
      }
    }
    Split<T> best;
    for (int axis = 0; axis < 3; ++axis) {
      if (!active[axis]) continue;
      std::array<float, kMaxBins> right_area{};
      std::array<std::uint32_t, kMaxBins> right_cnt{};
      BBox<T> acc;
      std::uint32_t c = 0;
      for (int k = nb - 1; k > 0; --k) {
        acc.extend(bb[axis][k]);
        c += cnt[axis][k];
        right_area[k] = float(acc.half_area());
        right_cnt[k] = c;
      }
      acc = BBox<T>{};
      c = 0;
      for (int k = 0; k < nb - 1; ++k) {
        acc.extend(bb[axis][k]);
        c += cnt[axis][k];
        if (c == 0 || right_cnt[k + 1] == 0) continue;
        const float cost = float(acc.half_area()) * float(c) + right_area[k + 1] * float(right_cnt[k + 1]);
        if (cost < best.cost) best.cost = cost, best.axis = axis, best.bin = k;
      }
    }
    if (best.axis >= 0)  // the children's boxes, as unions of their bins' (exact: min and max)
      for (int k = 0; k < nb; ++k) (k <= best.bin ? best.left : best.right).extend(bb[best.axis][k]);
    return best;
  }

  // Builds the subtree for refs[begin, end) (bounds `box`, centroid bounds `cbox`) into node
  // `index`; its descendants go into the node slots from `desc` on. A subtree of m triangles has at
  // most 2m - 1 nodes, so each child's descendants get a fixed range and both children build in
  // parallel with a layout that does not depend on the schedule (the gaps are squeezed out after).
  void build(std::uint32_t index, std::uint32_t begin, std::uint32_t end, std::uint32_t desc, const BBox<T>& box,
             const BBox<T>& cbox) {
    new (&node(index)) BvhNode<T>{box, 0, 0};
    const std::uint32_t n = end - begin;
    auto make_leaf = [&] {
      node(index).first = begin;
      node(index).count = n;
    };
    if (n <= 1) return make_leaf();

    const int nb = std::clamp(opts.bins, 2, kMaxBins);
    const Split<T> best = best_split(begin, end, cbox, nb);
    const float parent_area = float(box.half_area());
    const float leaf_cost = float(n);
    const float split_cost = opts.traversal_cost + (parent_area > 0 ? best.cost / parent_area : 0.f);
    if (best.axis < 0) {
      // All centroids coincide: split by index so huge stacks of coincident triangles still form a tree.
      if (n <= std::uint32_t(opts.max_leaf_size)) return make_leaf();
      const std::uint32_t mid = begin + n / 2;
      Split<T> halves;
      bounds_of(begin, mid, halves.left, halves.left_centroids);
      bounds_of(mid, end, halves.right, halves.right_centroids);
      return split(index, begin, mid, end, desc, halves);
    }
    if (n <= std::uint32_t(opts.max_leaf_size) && leaf_cost <= split_cost) return make_leaf();

    // Partition, gathering the children's centroid bounds on the way.
    const double scale = double(nb) / double(cbox.extent()[best.axis]);
    Split<T> s = best;
    std::uint32_t lo = begin, hi = end;
    while (lo < hi) {
      const Ref<T>& r = refs[lo];
      if (bin_index(r.centroid[best.axis], cbox.lo[best.axis], scale, nb) <= best.bin) {
        s.left_centroids.extend(r.centroid);
        ++lo;
      } else {
        s.right_centroids.extend(r.centroid);
        std::swap(refs[lo], refs[--hi]);
      }
    }
    split(index, begin, lo, end, desc, s);
  }

  void split(std::uint32_t index, std::uint32_t begin, std::uint32_t mid, std::uint32_t end, std::uint32_t desc,
             const Split<T>& s) {
    node(index).first = desc;
    node(index).count = 0;
    const std::uint32_t left_desc = desc + 2, right_desc = left_desc + 2 * (mid - begin) - 2;
    auto left = [&] { build(desc, begin, mid, left_desc, s.left, s.left_centroids); };
    auto right = [&] { build(desc + 1, mid, end, right_desc, s.right, s.right_centroids); };
    if (end - begin >= kParallelGrain) {
      tbb::parallel_invoke(left, right);
    } else {
      left();
      right();
    }
  }

  // The tree without the unused slots, in depth-first order (siblings stay adjacent).
  HugePageVector<BvhNode<T>> compacted() const {
    HugePageVector<BvhNode<T>> out;
    out.push_back(node(0));
    struct Todo {
      std::uint32_t old_index, new_index;
    };
    std::vector<Todo> todo{{0, 0}};
    while (!todo.empty()) {
      const Todo t = todo.back();
      todo.pop_back();
      const BvhNode<T>& n = node(t.old_index);
      if (n.is_leaf()) continue;
      const auto first = std::uint32_t(out.size());
      out.push_back(node(n.first));
      out.push_back(node(n.first + 1));
      out[t.new_index].first = first;
      todo.push_back({n.first + 1, first + 1});
      todo.push_back({n.first, first});
    }
    out.shrink_to_fit();
    return out;
  }
};

// ---------------------------------------------------------------- Embree's builder
// rtcBuildBVH builds a binary tree of these in its thread-local allocators; the tree is then
// copied into Pierce's node array (siblings adjacent, preorder) and its boxes recomputed exactly.
struct EmbreeHeader {
  std::uint32_t leaf_count;  // 0 for an inner node
};
struct EmbreeInner {
  EmbreeHeader h;
  void* child[2];
};
std::uint32_t* leaf_refs(void* leaf) { return reinterpret_cast<std::uint32_t*>(static_cast<char*>(leaf) + sizeof(EmbreeHeader)); }

void* embree_create_node(RTCThreadLocalAllocator alloc, unsigned int /*children*/, void* /*user*/) {
  return new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeInner), 16)) EmbreeInner{{0}, {nullptr, nullptr}};
}
void embree_set_children(void* node, void** children, unsigned int count, void* /*user*/) {
  auto* n = static_cast<EmbreeInner*>(node);
  for (unsigned int i = 0; i < count && i < 2; ++i) n->child[i] = children[i];
}
void embree_set_bounds(void*, const RTCBounds**, unsigned int, void*) {}  // recomputed exactly afterwards
void* embree_create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void* /*user*/) {
  void* leaf = rtcThreadLocalAlloc(alloc, sizeof(EmbreeHeader) + sizeof(std::uint32_t) * std::max<size_t>(count, 1), 16);
  new (leaf) EmbreeHeader{std::uint32_t(count)};
  for (size_t i = 0; i < count; ++i) leaf_refs(leaf)[i] = prims[i].primID;
  return leaf;
}

// The tree Embree's builder chooses over `refs`, as Pierce nodes with exact boxes; `order` gets the
// refs in leaf order. False (and nothing written) if Embree failed or lost or repeated a primitive,
// or made a leaf beyond what the wide collapse takes.
template <typename T>
bool build_with_embree(const std::vector<Ref<T>>& refs, const BvhBuildOptions& opts, HugePageVector<BvhNode<T>>& nodes,
                       std::vector<std::uint32_t>& order) {
  const RTCDevice device = detail::builder_device();
  if (device == nullptr) return false;
  HugePageVector<RTCBuildPrimitive> prims(refs.size());
  for (std::size_t i = 0; i < refs.size(); ++i) prims[i] = detail::build_primitive(refs[i].box, 0, std::uint32_t(i));
  RTCBVH bvh = rtcNewBVH(device);
  RTCBuildArguments args = detail::build_arguments(bvh, prims, opts.traversal_cost, embree_create_node,
                                                   embree_set_children, embree_set_bounds, embree_create_leaf);
  args.maxBranchingFactor = 2;
  args.minLeafSize = 1;
  args.maxLeafSize = std::uint32_t(std::clamp(opts.max_leaf_size, 1, 32));
  void* root = rtcBuildBVH(&args);
  bool ok = root != nullptr && rtcGetDeviceError(device) == RTC_ERROR_NONE;

  HugePageVector<BvhNode<T>> out;
  std::vector<std::uint32_t> leaf_order;
  if (ok) {
    out.reserve(refs.size());
    leaf_order.reserve(refs.size());
    out.emplace_back();
    std::vector<std::pair<void*, std::uint32_t>> todo{{root, 0}};
    while (!todo.empty() && ok) {
      const auto [ptr, index] = todo.back();
      todo.pop_back();
      const auto* h = static_cast<const EmbreeHeader*>(ptr);
      if (h->leaf_count > 0) {
        if (h->leaf_count > 256) ok = false;  // beyond the wide collapse's leaves
        out[index].first = std::uint32_t(leaf_order.size());
        out[index].count = h->leaf_count;
        for (std::uint32_t i = 0; i < h->leaf_count; ++i) leaf_order.push_back(leaf_refs(ptr)[i]);
        continue;
      }
      const auto* n = static_cast<const EmbreeInner*>(ptr);
      if (n->child[0] == nullptr || n->child[1] == nullptr) {
        ok = false;
        break;
      }
      const auto first = std::uint32_t(out.size());
      out[index].first = first;
      out[index].count = 0;
      out.emplace_back();
      out.emplace_back();
      todo.push_back({n->child[1], first + 1});
      todo.push_back({n->child[0], first});
    }
  }
  rtcReleaseBVH(bvh);
  if (!ok || leaf_order.size() != refs.size()) return false;
  std::vector<std::uint8_t> seen(refs.size(), 0);
  for (const std::uint32_t r : leaf_order) {
    if (r >= refs.size() || seen[r]) return false;
    seen[r] = 1;
  }
  // Exact boxes, children before parents (children always follow their parent in preorder).
  for (std::size_t i = out.size(); i-- > 0;) {
    BvhNode<T>& n = out[i];
    n.box = BBox<T>{};
    if (n.is_leaf()) {
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k) n.box.extend(refs[leaf_order[k]].box);
    } else {
      n.box.extend(out[n.first].box);
      n.box.extend(out[n.first + 1].box);
    }
  }
  nodes = std::move(out);
  order = std::move(leaf_order);
  return true;
}

}  // namespace

template <typename T>
Bvh<T> build_bvh(const Scene& scene, const BvhBuildOptions& opts) {
  Builder<T> b{opts, {}, {}};
  b.refs.reserve(scene.triangle_count());
  BBox<T> box, cbox;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      const Tri& t = geo.triangles[p];
      const Vec3<T> v0(geo.vertices[t[0]]), v1(geo.vertices[t[1]]), v2(geo.vertices[t[2]]);
      if (is_degenerate(v0, v1, v2)) continue;
      Ref<T> r;
      r.box.extend(v0), r.box.extend(v1), r.box.extend(v2);
      r.centroid = r.box.center();
      r.geom = g, r.prim = p;
      box.extend(r.box);
      cbox.extend(r.centroid);
      b.refs.push_back(r);
    }
  }
  Bvh<T> bvh;
  bvh.scene_max_abs = scene.bounds().max_abs_coord();
  const std::size_t n = b.refs.size();
  if (n == 0) return bvh;
  auto add_triangle = [&](const Ref<T>& r) {
    const Geometry& geo = scene.geometry(r.geom);
    const Tri& t = geo.triangles[r.prim];
    bvh.tris.push_back({Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]), Vec3<T>(geo.vertices[t[2]]), r.geom, r.prim});
  };
  std::vector<std::uint32_t> order;
  if (opts.embree_builder && double(box.max_abs_coord()) < kEmbreeMaxCoord &&
      build_with_embree(b.refs, opts, bvh.nodes, order)) {
    bvh.tris.reserve(n);
    for (const std::uint32_t r : order) add_triangle(b.refs[r]);
    return bvh;
  }
  b.slots = std::make_unique_for_overwrite<std::byte[]>((2 * n - 1) * sizeof(BvhNode<T>));
  b.build(0, 0, std::uint32_t(n), 1, box, cbox);
  bvh.nodes = b.compacted();
  b.slots.reset();
  bvh.tris.reserve(n);
  for (const Ref<T>& r : b.refs) add_triangle(r);
  return bvh;
}

template Bvh<float> build_bvh<float>(const Scene&, const BvhBuildOptions&);
template Bvh<double> build_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
