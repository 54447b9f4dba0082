// The wide BVH built directly: Embree's rtcBuildBVH (binned SAH, parallel) with branching factor
// eight chooses the tree, which is then written once into Pierce's WideNode / TriBlock layout with
// every box recomputed exactly from the triangles in precision T. No binary tree is built and
// nothing is collapsed. Where Embree's builder cannot be used (coordinates beyond
// kEmbreeBuildMaxCoord, or it failed), Pierce's own binned SAH builder and the collapse take over.
#include <algorithm>
#include <array>
#include <atomic>
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
// the leaf's triangle count (0 for an inner node). An inner node also gets its subtree's sizes in
// the writer's first pass.
struct BuildInner {
  std::uint32_t leaf_count;
  std::uint32_t child_count;
  void* child[kWideArity];
  std::uint32_t nodes_below, blocks_below, triangles_below, depth_below;  // the subtree's, itself included
};
struct BuildLeaf {
  std::uint32_t leaf_count;
  std::uint32_t id[1];  // leaf_count primitive ids (allocated to size)
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int children, void* /*user*/) {
  return new (rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16)) BuildInner{0, children, {}, 0, 0, 0, 0};
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

// Subtrees of at least this many triangles are written in parallel, child by child.
constexpr std::uint32_t kParallelTriangles = 8192;

// A triangle the build takes: where it is in the scene.
struct TriRef {
  std::uint32_t geom, prim;
};

// Writes Embree's tree in two passes: the first (serial, over the inner nodes only) sizes every
// subtree and checks the tree's shape; the second writes each subtree into its preorder range of
// nodes and blocks, big subtrees in parallel, so the layout does not depend on the schedule and the
// fresh pages are faulted in by the threads that fill them.
template <typename T>
struct Writer {
  const Scene& scene;
  const HugePageVector<TriRef>& refs;
  WideBvh<T>& out;
  HugePageVector<std::uint8_t> seen;  // each primitive must be in exactly one leaf

  // False where the tree is not one Pierce can take (a null child, an inner node without children).
  bool size(void* p) {
    if (leaf_count(p) > 0) return true;
    auto* n = static_cast<BuildInner*>(p);
    if (n->child_count < 1) return false;
    n->nodes_below = 1, n->blocks_below = 0, n->triangles_below = 0, n->depth_below = 1;
    for (std::uint32_t s = 0; s < n->child_count; ++s) {
      void* c = n->child[s];
      if (c == nullptr || !size(c)) return false;
      if (const std::uint32_t k = leaf_count(c); k > 0) {
        n->blocks_below += detail::leaf_blocks_for(k);
        n->triangles_below += k;
      } else {
        const auto* ci = static_cast<const BuildInner*>(c);
        n->nodes_below += ci->nodes_below, n->blocks_below += ci->blocks_below;
        n->triangles_below += ci->triangles_below;
        n->depth_below = std::max(n->depth_below, ci->depth_below + 1);
      }
    }
    return true;
  }

  Triangle<T> triangle(std::uint32_t id) const {
    const TriRef r = refs[id];
    const Geometry& geo = scene.geometry(r.geom);
    const Tri& t = geo.triangles[r.prim];
    return {Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]), Vec3<T>(geo.vertices[t[2]]), r.geom, r.prim};
  }

  // Every id in range and seen once (atomically: leaves are written concurrently).
  bool claim(const BuildLeaf& leaf) {
    for (std::uint32_t i = 0; i < leaf.leaf_count; ++i) {
      const std::uint32_t id = leaf.id[i];
      if (id >= refs.size() || std::atomic_ref<std::uint8_t>(seen[id]).exchange(1) != 0) return false;
    }
    return true;
  }

  // Writes the subtree at `p`: an inner node at out.nodes[node] with its descendants after it, its
  // leaves' blocks from out.blocks[block] on. Returns its reference; `box` gets its exact bounds.
  NodeRef write(const void* p, std::uint32_t node, std::uint32_t block, BBox<T>& box, std::atomic<bool>& ok) {
    if (const std::uint32_t n = leaf_count(p); n > 0) {
      const auto* leaf = static_cast<const BuildLeaf*>(p);
      if (!claim(*leaf)) ok = false;
      return detail::write_leaf(out, block, n, [&](std::size_t k) { return triangle(leaf->id[k]); }, box);
    }
    const auto* inner = static_cast<const BuildInner*>(p);
    const int nk = int(inner->child_count);
    std::array<BBox<T>, kWideArity> boxes{};
    std::array<NodeRef, kWideArity> refs_out{};
    std::array<std::uint32_t, kWideArity> child_node{}, child_block{};
    std::uint32_t next_node = node + 1, next_block = block;
    for (int s = 0; s < nk; ++s) {
      child_node[s] = next_node, child_block[s] = next_block;
      const void* c = inner->child[s];
      if (const std::uint32_t k = leaf_count(c); k > 0) {
        next_block += detail::leaf_blocks_for(k);
      } else {
        next_node += static_cast<const BuildInner*>(c)->nodes_below;
        next_block += static_cast<const BuildInner*>(c)->blocks_below;
      }
    }
    auto child = [&](int s) { refs_out[s] = write(inner->child[s], child_node[s], child_block[s], boxes[s], ok); };
    if (inner->triangles_below >= kParallelTriangles) {
      tbb::parallel_for(0, nk, child);
    } else {
      for (int s = 0; s < nk; ++s) child(s);
    }
    WideNode<T>& w = out.nodes[node];
    detail::set_wide_boxes(w, boxes.data(), nk);
    for (int s = 0; s < nk; ++s) {
      w.child[s] = refs_out[s];
      box.extend(boxes[s]);
    }
    return node;
  }

  // The whole tree from Embree's root; false if Embree's tree cannot be taken as it is.
  bool write_all(void* root) {
    if (!size(root)) return false;
    std::uint32_t nodes = 0, blocks = 0, triangles = 0;
    if (const std::uint32_t k = leaf_count(root); k > 0) {
      blocks = detail::leaf_blocks_for(k), triangles = k;
    } else {
      const auto* r = static_cast<const BuildInner*>(root);
      nodes = r->nodes_below, blocks = r->blocks_below, triangles = r->triangles_below, out.depth = r->depth_below;
    }
    if (triangles != refs.size()) return false;
    detail::check_block_count(blocks);
    out.nodes.resize(nodes);  // untouched until written (HugePageAllocator::construct)
    out.blocks.resize(blocks);
    std::atomic<bool> ok{true};
    BBox<T> box;
    out.root = write(root, 0, 0, box, ok);
    out.bounds = box;
    out.triangles = triangles;
    return ok;
  }
};

// Embree's tree written as the wide BVH; false (and `out` unusable) if Embree failed, or lost or
// repeated a primitive.
template <typename T>
bool build_with_embree(const Scene& scene, const BvhBuildOptions& opts, WideBvh<T>& out) {
  const RTCDevice device = detail::builder_device();
  if (device == nullptr) return false;
  // The build's arrays are in huge pages (huge_page_allocator.h): each is filled once, at once.
  HugePageVector<TriRef> refs;
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
  HugePageVector<RTCBuildPrimitive> prims(refs.size());
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
  RTCBuildArguments args =
      detail::build_arguments(bvh, prims, opts.traversal_cost, create_node, set_children, set_bounds, create_leaf);
  args.maxBranchingFactor = kWideArity;
  // A leaf block tests its eight lanes at once: the SAH counts leaf cost per block of eight.
  args.sahBlockSize = kBlockLanes;
  // Embree fills a node's eight slots by splitting its children down to minLeafSize regardless of
  // the SAH: a subtree of one block's worth of triangles becomes one leaf block (as the collapse).
  // Up to wide_max_leaf_size (two blocks by default) the SAH may keep a subtree as one leaf.
  args.maxLeafSize = std::uint32_t(std::clamp(opts.wide_max_leaf_size, 1, 32));
  args.minLeafSize = std::min<std::uint32_t>(kBlockLanes, args.maxLeafSize);
  void* root = rtcBuildBVH(&args);
  bool ok = root != nullptr && rtcGetDeviceError(device) == RTC_ERROR_NONE;
  if (ok) {
    HugePageVector<RTCBuildPrimitive>().swap(prims);  // Embree is done with them
    Writer<T> w{scene, refs, out, HugePageVector<std::uint8_t>(refs.size(), 0)};
    ok = w.write_all(root);
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
