// The wide BVH: the binned builder (binned_builder.h) chooses the tree eight wide, and the
// writer here lays it out once in the WideNode / TriBlock layout, every box recomputed exactly
// from the triangles in precision T. No binary tree is built and nothing is collapsed.
#include <array>
#include <cstdint>

#include <tbb/concurrent_vector.h>
#include <tbb/parallel_for.h>

#include "binned_builder.h"
#include "pierce/bvh_builder.h"
#include "pierce/wide_bvh.h"
#include "wide_bvh_writer.h"

namespace pierce {

namespace {

using detail::BuildChild;
using WideBuildNode = detail::BuildNode<kWideArity>;

// Subtrees of at least this many triangles are written in parallel, child by child.
constexpr std::uint32_t kParallelWrite = 8192;

// Writes the build tree: each subtree into its preorder range of nodes and blocks, big subtrees in
// parallel, so the layout does not depend on the schedule and the fresh pages are faulted in by
// the threads that fill them.
template <typename T>
struct Writer {
  const Scene& scene;
  const detail::PrimRef* prims;
  const tbb::concurrent_vector<WideBuildNode>& nodes;
  WideBvh<T>& out;

  Triangle<T> triangle(const detail::PrimRef& p) const {
    const Geometry& geo = scene.geometry(p.geom());
    const Tri& t = geo.triangles[p.prim()];
    return {Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]), Vec3<T>(geo.vertices[t[2]]), p.geom(), p.prim()};
  }

  // Writes the subtree `c`: an inner node at out.nodes[node] with its descendants after it, its
  // leaves' blocks from out.blocks[block] on. Returns its reference; `box` gets its exact bounds.
  NodeRef write(BuildChild c, std::uint32_t node, std::uint32_t block, BBox<T>& box) {
    if (c.is_leaf()) {
      const detail::PrimRef* leaf = prims + c.first;
      return detail::write_leaf(out, block, c.count, [&](std::size_t k) { return triangle(leaf[k]); }, box);
    }
    const WideBuildNode& inner = nodes[c.first];
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
      const WideBuildNode& r = nodes[root.first];
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

}  // namespace

template <typename T>
WideBvh<T> build_wide_bvh(const Scene& scene, const BvhBuildOptions& opts) {
  WideBvh<T> out;
  out.scene_max_abs = scene.bounds().max_abs_coord();
  const detail::BuiltTree<kWideArity> tree = detail::build_tree<kWideArity, T>(scene, opts, opts.wide_max_leaf_size);
  if (!tree.empty()) Writer<T>{scene, tree.prims.data(), tree.nodes, out}.write_all(tree.root);
  return out;
}

template WideBvh<float> build_wide_bvh<float>(const Scene&, const BvhBuildOptions&);
template WideBvh<double> build_wide_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
