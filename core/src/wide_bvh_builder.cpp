// The wide BVH built directly: Embree's rtcBuildBVH (binned SAH, parallel) with branching factor
// eight chooses the tree, which is then written once into Pierce's WideNode / TriBlock layout with
// every box recomputed exactly from the triangles in precision T. No binary tree is built and
// nothing is collapsed. Where Embree's builder cannot be used (coordinates beyond
// kEmbreeBuildMaxCoord, or it failed), Pierce's own binned SAH builder and the collapse take over.
#include <algorithm>
#include <array>
#include <cstdint>
#include <new>
#include <vector>

#include <tbb/parallel_for.h>

#include "embree_build_support.h"
#include "pierce/bvh_builder.h"
#include "pierce/wide_bvh.h"
#include "wide_bvh_writer.h"

namespace pierce {

namespace {

// The tree as Embree's builder makes it, in its thread-local allocators. Both kinds start with
// the leaf's triangle count (0 for an inner node).
struct BuildInner {
  std::uint32_t leaf_count;
  std::uint32_t child_count;
  void* child[kWideArity];
};
struct BuildLeaf {
  std::uint32_t leaf_count;
  std::uint32_t id[1];  // leaf_count primitive ids (allocated to size)
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int children, void* /*user*/) {
  return new (rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16)) BuildInner{0, children, {}};
}
void set_children(void* node, void** children, unsigned int count, void* /*user*/) {
  auto* n = static_cast<BuildInner*>(node);
  n->child_count = std::min<unsigned int>(count, kWideArity);
  for (unsigned int i = 0; i < n->child_count; ++i) n->child[i] = children[i];
}
void set_bounds(void*, const RTCBounds**, unsigned int, void*) {}  // recomputed exactly when written
void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void* /*user*/) {
  const std::size_t bytes = offsetof(BuildLeaf, id) + sizeof(std::uint32_t) * std::max<size_t>(count, 1);
  auto* leaf = static_cast<BuildLeaf*>(rtcThreadLocalAlloc(alloc, bytes, 16));
  leaf->leaf_count = std::uint32_t(count);
  for (size_t i = 0; i < count; ++i) leaf->id[i] = prims[i].primID;
  return leaf;
}
std::uint32_t leaf_count(const void* p) { return *static_cast<const std::uint32_t*>(p); }

// A triangle the build takes: where it is in the scene.
struct TriRef {
  std::uint32_t geom, prim;
};

template <typename T>
struct Writer {
  const Scene& scene;
  const std::vector<TriRef>& refs;
  WideBvh<T>& out;
  std::vector<std::uint8_t> seen;  // each primitive must be in exactly one leaf
  bool ok = true;

  Triangle<T> triangle(std::uint32_t id) const {
    const TriRef r = refs[id];
    const Geometry& geo = scene.geometry(r.geom);
    const Tri& t = geo.triangles[r.prim];
    return {Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]), Vec3<T>(geo.vertices[t[2]]), r.geom, r.prim};
  }

  // Writes the subtree at `p` (the node before its children, preorder) and returns its reference;
  // `box` gets its exact bounds.
  NodeRef write(const void* p, std::uint32_t level, BBox<T>& box) {
    if (const std::uint32_t n = leaf_count(p); n > 0) {
      const auto* leaf = static_cast<const BuildLeaf*>(p);
      for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t id = leaf->id[i];
        if (id >= refs.size() || seen[id]) {
          ok = false;
          return make_leaf_ref(0, 1);
        }
        seen[id] = 1;
      }
      const std::uint32_t nblocks = detail::leaf_blocks_for(n);
      const auto first = std::uint32_t(out.blocks.size());
      detail::check_block_count(std::size_t(first) + nblocks);
      out.blocks.resize(first + nblocks);
      out.triangles += n;
      return detail::write_leaf(out, first, n, [&](std::size_t k) { return triangle(leaf->id[k]); }, box);
    }
    const auto* inner = static_cast<const BuildInner*>(p);
    const int nk = int(inner->child_count);
    if (nk < 1) {
      ok = false;
      return make_leaf_ref(0, 1);
    }
    out.depth = std::max(out.depth, level + 1);
    const auto index = std::uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    std::array<BBox<T>, kWideArity> boxes{};
    std::array<NodeRef, kWideArity> refs_out{};
    for (int s = 0; s < nk && ok; ++s) {
      if (inner->child[s] == nullptr) {
        ok = false;
        break;
      }
      refs_out[s] = write(inner->child[s], level + 1, boxes[s]);
      box.extend(boxes[s]);
    }
    if (!ok) return make_leaf_ref(0, 1);
    WideNode<T>& w = out.nodes[index];  // the vector may have grown: looked up again
    detail::set_wide_boxes(w, boxes.data(), nk);
    for (int s = 0; s < nk; ++s) w.child[s] = refs_out[s];
    return index;
  }
};

// Embree's tree written as the wide BVH; false (and `out` unusable) if Embree failed, or lost or
// repeated a primitive.
template <typename T>
bool build_with_embree(const Scene& scene, const BvhBuildOptions& opts, WideBvh<T>& out) {
  const RTCDevice device = detail::builder_device();
  if (device == nullptr) return false;
  std::vector<TriRef> refs;
  refs.reserve(scene.triangle_count());
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      // The scene flags triangles degenerate in float; a double BVH asks in double.
      if constexpr (std::is_same_v<T, float>) {
        if (geo.degenerate[p]) continue;
      } else {
        const Tri& t = geo.triangles[p];
        if (is_degenerate(geo.vertices[t[0]], geo.vertices[t[1]], geo.vertices[t[2]])) continue;
      }
      refs.push_back({g, p});
    }
  }
  if (refs.empty()) return true;
  std::vector<RTCBuildPrimitive> prims(refs.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, refs.size(), 4096), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      const Geometry& geo = scene.geometry(refs[i].geom);
      const Tri& t = geo.triangles[refs[i].prim];
      BBox<T> b;
      for (int k = 0; k < 3; ++k) b.extend(Vec3<T>(geo.vertices[t[k]]));
      prims[i] = detail::build_primitive(b, std::uint32_t(i));
    }
  });

  RTCBVH bvh = rtcNewBVH(device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = kWideArity;
  // A leaf block tests its eight lanes at once: the SAH counts leaf cost per block of eight.
  args.sahBlockSize = kBlockLanes;
  // Embree fills a node's eight slots by splitting its children down to minLeafSize regardless of
  // the SAH: a subtree of one block's worth of triangles becomes one leaf block (as the collapse).
  args.maxLeafSize = std::uint32_t(std::clamp(opts.max_leaf_size, 1, 32));
  args.minLeafSize = std::min<std::uint32_t>(kBlockLanes, args.maxLeafSize);
  args.traversalCost = opts.traversal_cost;
  args.intersectionCost = 1.0f;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  const void* root = rtcBuildBVH(&args);
  bool ok = root != nullptr && rtcGetDeviceError(device) == RTC_ERROR_NONE;
  if (ok) {
    std::vector<RTCBuildPrimitive>().swap(prims);  // Embree is done with them
    out.nodes.reserve(refs.size() / 16 + 1);
    out.blocks.reserve(refs.size() / 4 + 1);
    Writer<T> w{scene, refs, out, std::vector<std::uint8_t>(refs.size(), 0)};
    BBox<T> box;
    out.root = w.write(root, 0, box);
    out.bounds = box;
    ok = w.ok && out.triangles == refs.size();
  }
  rtcReleaseBVH(bvh);
  return ok;
}

}  // namespace

template <typename T>
WideBvh<T> build_wide_bvh(const Scene& scene, const BvhBuildOptions& opts) {
  const double max_coord = scene.bounds().max_abs_coord();
  if (opts.embree_builder && max_coord < kEmbreeBuildMaxCoord) {
    WideBvh<T> out;
    out.scene_max_abs = max_coord;
    if (build_with_embree(scene, opts, out)) return out;
  }
  BvhBuildOptions own = opts;
  own.embree_builder = false;
  return build_wide_bvh(build_bvh<T>(scene, own));
}

template WideBvh<float> build_wide_bvh<float>(const Scene&, const BvhBuildOptions&);
template WideBvh<double> build_wide_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
