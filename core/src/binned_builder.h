#pragma once
// Pierce's BVH builder, for the binary BVH (bvh_builder.cpp) and the 8-wide one
// (wide_bvh_builder.cpp) alike: one binned SAH builder (sah_binning.h) whose branching is a
// template parameter. It chooses the tree in build records on float boxes rounded outward; each
// BVH's writer then lays the records out in its own node format, with every box recomputed exactly
// from the triangles in the BVH's precision.
//
// The tree is the one Embree's binned SAH builder makes (Wald 2007, as in Embree's
// BVHBuilderBinnedSAH): a node takes the range's best plane, then splits its largest child (by
// area) until it has `Arity`; a range becomes a leaf at up to min_leaf triangles, or at up to
// max_leaf where the SAH says a leaf is cheaper.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include <tbb/blocked_range.h>
#include <tbb/concurrent_vector.h>
#include <tbb/parallel_for.h>

#include "pierce/bvh_builder.h"
#include "pierce/huge_page_allocator.h"
#include "pierce/scene.h"
#include "sah_binning.h"
#include "wide_bvh_writer.h"

namespace pierce::detail {

// A child in the build tree: a leaf (count > 0: prims[first, first + count)) or an inner node
// (count 0: nodes[first]).
struct BuildChild {
  std::uint32_t first = 0, count = 0;
  bool is_leaf() const { return count > 0; }
};

// An inner node with its subtree's sizes (itself included): inner nodes, leaf blocks (kBlockLanes
// triangles each), triangles and inner levels. The wide writer gives every subtree its preorder
// range of nodes and blocks from them before writing any of it.
template <int Arity>
struct BuildNode {
  std::array<BuildChild, Arity> child{};
  std::uint32_t child_count = 0;
  std::uint32_t nodes_below = 0, blocks_below = 0, triangles_below = 0, depth_below = 0;
};

// A range with the plane it would be split at (found only where it may be split).
struct Record {
  PrimRange range;
  SahSplit split;
};

template <typename Area, int Arity>
struct Builder {
  PrimRef* prims;
  std::uint32_t min_leaf, max_leaf;
  float traversal_cost;
  tbb::concurrent_vector<BuildNode<Arity>> nodes;  // grows without moving: tasks fill their own nodes

  Record record(const PrimRange& r) const {
    Record rec{r, {}};
    if (r.size() > min_leaf) rec.split = find_split<Area>(prims, r);
    return rec;
  }

  BuildChild build(const Record& cur) {
    const PrimRange& r = cur.range;
    const std::uint32_t n = r.size();
    const double area = r.geom.half_area<Area>();
    if (n <= min_leaf || (n <= max_leaf && area * blocks_of(n) <= double(traversal_cost) * area + cur.split.cost)) {
      // Lanes in scene order, whatever order the partitions left them in (as Embree's leaves).
      std::sort(prims + r.begin, prims + r.end, [](const PrimRef& a, const PrimRef& b) {
        return a.geom() != b.geom() ? a.geom() < b.geom() : a.prim() < b.prim();
      });
      return {r.begin, n};
    }

    std::array<Record, Arity> children;
    children[0] = cur;
    std::uint32_t count = 1;
    while (count < Arity) {
      int largest = -1;
      Area largest_area = Area(-1);
      for (std::uint32_t i = 0; i < count; ++i) {
        if (children[i].range.size() <= min_leaf) continue;
        const Area a = children[i].range.geom.template half_area<Area>();
        if (a > largest_area) largest = int(i), largest_area = a;
      }
      if (largest < 0) break;
      PrimRange left, right;
      partition(prims, children[largest].range, children[largest].split, left, right);
      children[largest] = record(left);
      children[count++] = record(right);
    }

    // Largest first, as Embree orders a node's children (visit order comes from the per-octant
    // ranks; only order-free traversal, `filter`, follows the slots).
    std::stable_sort(children.begin(), children.begin() + count,
                     [](const Record& a, const Record& b) { return a.range.size() > b.range.size(); });
    const auto it = nodes.grow_by(1);
    const auto index = std::uint32_t(it - nodes.begin());
    std::array<BuildChild, Arity> built{};
    auto child = [&](std::uint32_t s) { built[s] = build(children[s]); };
    if (n >= kParallelBuild) {
      tbb::parallel_for(std::uint32_t(0), count, child);
    } else {
      for (std::uint32_t s = 0; s < count; ++s) child(s);
    }

    BuildNode<Arity>& node = nodes[index];
    node.child = built;
    node.child_count = count;
    node.nodes_below = 1, node.depth_below = 1;
    for (std::uint32_t s = 0; s < count; ++s) {
      const BuildChild c = built[s];
      if (c.is_leaf()) {
        node.blocks_below += leaf_blocks_for(c.count);
        node.triangles_below += c.count;
      } else {
        const BuildNode<Arity>& below = nodes[c.first];
        node.nodes_below += below.nodes_below, node.blocks_below += below.blocks_below;
        node.triangles_below += below.triangles_below;
        node.depth_below = std::max(node.depth_below, below.depth_below + 1);
      }
    }
    return {index, 0};
  }
};

// Float bounds containing x (exact for float input).
inline float round_down(double x) {
  const auto f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
inline float round_up(double x) {
  const auto f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// The scene's non-degenerate triangles (in T) as build references, in scene order.
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
                          PrimRef& r = out[p];
                          if (degenerate) {  // removed below; an empty box marks it
                            r.lo = Float4{} + 1.0f, r.hi = Float4{} - 1.0f;
                            continue;
                          }
                          BBox<T> b;
                          for (const Vec3<T>& x : v) b.extend(x);
                          r.lo = Float4{round_down(double(b.lo.x)), round_down(double(b.lo.y)),
                                        round_down(double(b.lo.z)), PrimRef::id_lane(g)};
                          r.hi = Float4{round_up(double(b.hi.x)), round_up(double(b.hi.y)),
                                        round_up(double(b.hi.z)), PrimRef::id_lane(p)};
                        }
                      });
    first += geo.triangles.size();
  }
  auto is_marked = [](const PrimRef& r) { return r.lo[0] > r.hi[0]; };
  prims.erase(std::remove_if(prims.begin(), prims.end(), is_marked), prims.end());
  return prims;
}

// A built tree: the references in leaf-range order, the inner nodes, and the root.
template <int Arity>
struct BuiltTree {
  HugePageVector<PrimRef> prims;
  tbb::concurrent_vector<BuildNode<Arity>> nodes;
  BuildChild root;
  bool empty() const { return prims.empty(); }
};

// The tree over the scene's non-degenerate triangles, with leaves of up to `max_leaf` (clamped to
// 1..32) and of exactly the range where it holds at most min(kBlockLanes, max_leaf).
template <int Arity, typename T>
BuiltTree<Arity> build_tree(const Scene& scene, const BvhBuildOptions& opts, int max_leaf_size) {
  BuiltTree<Arity> out;
  out.prims = prim_refs<T>(scene);
  if (out.prims.empty()) return out;
  check_block_count((out.prims.size() + kBlockLanes - 1) / kBlockLanes);  // before 32-bit ranges could wrap
  PrimRange all{0, std::uint32_t(out.prims.size()), {}, {}};
  for (const PrimRef& p : out.prims) all.geom.extend(p.lo, p.hi), all.cent.extend(p.centroid2());
  const auto max_leaf = std::uint32_t(std::clamp(max_leaf_size, 1, 32));
  const std::uint32_t min_leaf = std::min<std::uint32_t>(kBlockLanes, max_leaf);
  auto build = [&](auto builder) {
    out.root = builder.build(builder.record(all));
    out.nodes = std::move(builder.nodes);
  };
  if (opts.float_areas && scene.bounds().max_abs_coord() < kMaxFloatAreaCoord) {
    build(Builder<float, Arity>{out.prims.data(), min_leaf, max_leaf, opts.traversal_cost, {}});
  } else {
    build(Builder<double, Arity>{out.prims.data(), min_leaf, max_leaf, opts.traversal_cost, {}});
  }
  const std::uint32_t placed = out.root.is_leaf() ? out.root.count : out.nodes[out.root.first].triangles_below;
  if (placed != out.prims.size()) throw std::logic_error("BVH build: the leaves do not hold every triangle once");
  return out;
}

}  // namespace pierce::detail
