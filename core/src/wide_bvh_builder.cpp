// The wide BVH built directly, eight wide: a binned SAH builder on float boxes (sah_binning.h)
// chooses the tree in Pierce's own build records, which are then written once into the WideNode /
// TriBlock layout with every box recomputed exactly from the triangles in precision T. No binary
// tree is built and nothing is collapsed. Where float boxes cannot be used (coordinates beyond
// kEmbreeMaxCoord), Pierce's precision-T binary builder and the collapse take over.
//
// The tree is the one Embree's binned SAH builder makes (Wald 2007, as in Embree's
// BVHBuilderBinnedSAH): a node takes the range's best plane, then splits its largest child (by
// area) until it has eight; a range becomes a leaf at up to minLeafSize triangles, or at up to
// wide_max_leaf_size where the SAH says a leaf is cheaper. Embree's generic rtcBuildBVH, used here
// before, builds the same tree but was slower than Embree's own scene build by more than the issue
// allows (docs/BENCHMARKS-HISTORY.md, fourteenth session).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include <tbb/concurrent_vector.h>
#include <tbb/parallel_for.h>

#include "embree_build_support.h"
#include "pierce/bvh_builder.h"
#include "pierce/wide_bvh.h"
#include "sah_binning.h"
#include "wide_bvh_writer.h"

namespace pierce {

namespace {

using detail::PrimRange;
using detail::PrimRef;
using detail::SahSplit;

// A child in the build tree: a leaf (count > 0: prims[first, first + count)) or an inner node
// (count 0: nodes[first]).
struct BuildChild {
  std::uint32_t first = 0, count = 0;
  bool is_leaf() const { return count > 0; }
};

// An inner node with its subtree's sizes (itself included), so the writer can give every subtree
// its preorder range of nodes and blocks before writing any of it.
struct BuildNode {
  std::array<BuildChild, kWideArity> child{};
  std::uint32_t child_count = 0;
  std::uint32_t nodes_below = 0, blocks_below = 0, triangles_below = 0, depth_below = 0;
};

// Ranges of at least this many triangles build their children in parallel (Embree: 1024).
constexpr std::uint32_t kParallelBuild = 1024;
// Subtrees of at least this many triangles are written in parallel, child by child.
constexpr std::uint32_t kParallelWrite = 8192;

// A range with the plane it would be split at (found only where it may be split).
struct Record {
  PrimRange range;
  SahSplit split;
};

struct Builder {
  PrimRef* prims;
  std::uint32_t min_leaf, max_leaf;
  float traversal_cost;
  tbb::concurrent_vector<BuildNode> nodes;  // grows without moving: tasks fill their own nodes

  Record record(const PrimRange& r) const {
    Record rec{r, {}};
    if (r.size() > min_leaf) rec.split = detail::find_split(prims, r);
    return rec;
  }

  BuildChild build(const Record& cur) {
    const PrimRange& r = cur.range;
    const std::uint32_t n = r.size();
    const double area = r.geom.half_area();
    if (n <= min_leaf || (n <= max_leaf && area * detail::blocks_of(n) <= double(traversal_cost) * area + cur.split.cost)) {
      // Lanes in scene order, whatever order the partitions left them in (as Embree's leaves).
      std::sort(prims + r.begin, prims + r.end, [](const PrimRef& a, const PrimRef& b) {
        return a.geom() != b.geom() ? a.geom() < b.geom() : a.prim() < b.prim();
      });
      return {r.begin, n};
    }

    std::array<Record, kWideArity> children;
    children[0] = cur;
    std::uint32_t count = 1;
    while (count < kWideArity) {
      int largest = -1;
      float largest_area = -1.0f;
      for (std::uint32_t i = 0; i < count; ++i) {
        if (children[i].range.size() <= min_leaf) continue;
        if (const float a = children[i].range.geom.half_area(); a > largest_area) largest = int(i), largest_area = a;
      }
      if (largest < 0) break;
      PrimRange left, right;
      detail::partition(prims, children[largest].range, children[largest].split, left, right);
      children[largest] = record(left);
      children[count++] = record(right);
    }

    // Largest first, as Embree orders a node's children (visit order comes from the per-octant
    // ranks; only order-free traversal, `filter`, follows the slots).
    std::stable_sort(children.begin(), children.begin() + count,
                     [](const Record& a, const Record& b) { return a.range.size() > b.range.size(); });
    const auto it = nodes.grow_by(1);
    const auto index = std::uint32_t(it - nodes.begin());
    std::array<BuildChild, kWideArity> built{};
    auto child = [&](std::uint32_t s) { built[s] = build(children[s]); };
    if (n >= kParallelBuild) {
      tbb::parallel_for(std::uint32_t(0), count, child);
    } else {
      for (std::uint32_t s = 0; s < count; ++s) child(s);
    }

    BuildNode& node = nodes[index];
    node.child = built;
    node.child_count = count;
    node.nodes_below = 1, node.depth_below = 1;
    for (std::uint32_t s = 0; s < count; ++s) {
      const BuildChild c = built[s];
      if (c.is_leaf()) {
        node.blocks_below += detail::leaf_blocks_for(c.count);
        node.triangles_below += c.count;
      } else {
        const BuildNode& below = nodes[c.first];
        node.nodes_below += below.nodes_below, node.blocks_below += below.blocks_below;
        node.triangles_below += below.triangles_below;
        node.depth_below = std::max(node.depth_below, below.depth_below + 1);
      }
    }
    return {index, 0};
  }
};

// Writes the build tree: each subtree into its preorder range of nodes and blocks, big subtrees in
// parallel, so the layout does not depend on the schedule and the fresh pages are faulted in by
// the threads that fill them.
template <typename T>
struct Writer {
  const Scene& scene;
  const PrimRef* prims;
  const tbb::concurrent_vector<BuildNode>& nodes;
  WideBvh<T>& out;

  Triangle<T> triangle(const PrimRef& p) const {
    const Geometry& geo = scene.geometry(p.geom());
    const Tri& t = geo.triangles[p.prim()];
    return {Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]), Vec3<T>(geo.vertices[t[2]]), p.geom(), p.prim()};
  }

  // Writes the subtree `c`: an inner node at out.nodes[node] with its descendants after it, its
  // leaves' blocks from out.blocks[block] on. Returns its reference; `box` gets its exact bounds.
  NodeRef write(BuildChild c, std::uint32_t node, std::uint32_t block, BBox<T>& box) {
    if (c.is_leaf()) {
      const PrimRef* leaf = prims + c.first;
      return detail::write_leaf(out, block, c.count, [&](std::size_t k) { return triangle(leaf[k]); }, box);
    }
    const BuildNode& inner = nodes[c.first];
    const int nk = int(inner.child_count);
    std::array<BBox<T>, kWideArity> boxes{};
    std::array<NodeRef, kWideArity> refs{};
    std::array<std::uint32_t, kWideArity> child_node{}, child_block{};
    std::uint32_t next_node = node + 1, next_block = block;
    for (int s = 0; s < nk; ++s) {
      child_node[s] = next_node, child_block[s] = next_block;
      const BuildChild k = inner.child[s];
      if (k.is_leaf()) {
        next_block += detail::leaf_blocks_for(k.count);
      } else {
        next_node += nodes[k.first].nodes_below;
        next_block += nodes[k.first].blocks_below;
      }
    }
    auto child = [&](int s) { refs[s] = write(inner.child[s], child_node[s], child_block[s], boxes[s]); };
    if (inner.triangles_below >= kParallelWrite) {
      tbb::parallel_for(0, nk, child);
    } else {
      for (int s = 0; s < nk; ++s) child(s);
    }
    WideNode<T>& w = out.nodes[node];
    detail::set_wide_boxes(w, boxes.data(), nk);
    for (int s = 0; s < nk; ++s) {
      w.child[s] = refs[s];
      box.extend(boxes[s]);
    }
    return node;
  }

  void write_all(BuildChild root) {
    std::uint32_t node_count = 0, block_count = 0;
    if (root.is_leaf()) {
      block_count = detail::leaf_blocks_for(root.count), out.triangles = root.count;
    } else {
      const BuildNode& r = nodes[root.first];
      node_count = r.nodes_below, block_count = r.blocks_below, out.triangles = r.triangles_below;
      out.depth = r.depth_below;
    }
    detail::check_block_count(block_count);
    out.nodes.resize(node_count);  // untouched until written (HugePageAllocator::construct)
    out.blocks.resize(block_count);
    BBox<T> box;
    out.root = write(root, 0, 0, box);
    out.bounds = box;
  }
};

// PrimRef has Embree's build-primitive layout (box corners with geomID and primID in the fourth
// lanes), so the one outward rounding of embree_build_support.h fills it.
static_assert(sizeof(PrimRef) == sizeof(RTCBuildPrimitive) && offsetof(RTCBuildPrimitive, geomID) == 12 &&
              offsetof(RTCBuildPrimitive, upper_x) == 16 && offsetof(RTCBuildPrimitive, primID) == 28);

// The scene's non-degenerate triangles (in T) as build references, boxes rounded outward to float.
template <typename T>
HugePageVector<PrimRef> prim_refs(const Scene& scene) {
  HugePageVector<PrimRef> prims(scene.triangle_count());
  std::size_t first = 0;
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    PrimRef* out = prims.data() + first;
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, std::uint32_t(geo.triangles.size()), 4096),
                      [&](const auto& range) {
                        for (std::uint32_t p = range.begin(); p != range.end(); ++p) {
                          const Tri& t = geo.triangles[p];
                          const Vec3<T> v[3] = {Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]),
                                                Vec3<T>(geo.vertices[t[2]])};
                          // The scene flags triangles degenerate in float; a double BVH asks in double.
                          bool degenerate;
                          if constexpr (std::is_same_v<T, float>) {
                            degenerate = geo.degenerate[p] != 0;
                          } else {
                            degenerate = is_degenerate(v[0], v[1], v[2]);
                          }
                          BBox<T> b;
                          for (const Vec3<T>& x : v) b.extend(x);
                          PrimRef& r = out[p];
                          if (degenerate) {  // removed below; an empty box marks it
                            r.lo = detail::Float4{} + 1.0f, r.hi = detail::Float4{} - 1.0f;
                            continue;
                          }
                          const RTCBuildPrimitive rounded = detail::build_primitive(b, g, p);
                          std::memcpy(&r, &rounded, sizeof r);
                        }
                      });
    first += geo.triangles.size();
  }
  auto is_marked = [](const PrimRef& r) { return r.lo[0] > r.hi[0]; };
  prims.erase(std::remove_if(prims.begin(), prims.end(), is_marked), prims.end());
  return prims;
}

template <typename T>
void build_binned(const Scene& scene, const BvhBuildOptions& opts, WideBvh<T>& out) {
  HugePageVector<PrimRef> prims = prim_refs<T>(scene);
  if (prims.empty()) return;
  detail::check_block_count((prims.size() + kBlockLanes - 1) / kBlockLanes);  // before 32-bit ranges could wrap
  PrimRange all{0, std::uint32_t(prims.size()), {}, {}};
  for (const PrimRef& p : prims) all.geom.extend(p.lo, p.hi), all.cent.extend(p.centroid2());
  const auto max_leaf = std::uint32_t(std::clamp(opts.wide_max_leaf_size, 1, 32));
  Builder builder{prims.data(), std::min<std::uint32_t>(kBlockLanes, max_leaf), max_leaf, opts.traversal_cost, {}};
  const BuildChild root = builder.build(builder.record(all));
  const std::uint32_t placed = root.is_leaf() ? root.count : builder.nodes[root.first].triangles_below;
  if (placed != prims.size()) throw std::logic_error("wide BVH build: the leaves do not hold every triangle once");
  Writer<T>{scene, prims.data(), builder.nodes, out}.write_all(root);
}

}  // namespace

template <typename T>
WideBvh<T> build_wide_bvh(const Scene& scene, const BvhBuildOptions& opts) {
  const double max_coord = scene.bounds().max_abs_coord();
  if (opts.embree_builder && max_coord < kEmbreeMaxCoord) {
    WideBvh<T> out;
    out.scene_max_abs = max_coord;
    build_binned(scene, opts, out);
    return out;
  }
  BvhBuildOptions own = opts;
  own.embree_builder = false;
  return build_wide_bvh(build_bvh<T>(scene, own));
}

template WideBvh<float> build_wide_bvh<float>(const Scene&, const BvhBuildOptions&);
template WideBvh<double> build_wide_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
