#include "pierce/bvh_builder.h"

#include <cstdint>
#include <utility>
#include <vector>

#include "binned_builder.h"

namespace pierce {

namespace {

using detail::BuildChild;
using BinaryBuildNode = detail::BuildNode<2>;

// Lays the build tree out as Bvh<T> nodes: preorder, the two children of a node adjacent (first,
// first + 1), the triangles in the order of the references (each leaf a range of them). Boxes are
// then recomputed exactly in T, children before parents.
template <typename T>
void write_binary(const Scene& scene, const detail::BuiltTree<2>& tree, Bvh<T>& out) {
  out.tris.reserve(tree.prims.size());
  for (const detail::PrimRef& p : tree.prims) {
    const Geometry& geo = scene.geometry(p.geom());
    const Tri& t = geo.triangles[p.prim()];
    out.tris.push_back({Vec3<T>(geo.vertices[t[0]]), Vec3<T>(geo.vertices[t[1]]), Vec3<T>(geo.vertices[t[2]]),
                        p.geom(), p.prim()});
  }
  const std::uint32_t inner = tree.root.is_leaf() ? 0 : tree.nodes[tree.root.first].nodes_below;
  out.nodes.reserve(2 * std::size_t(inner) + 1);  // a binary tree of m inner nodes has m + 1 leaves
  out.nodes.emplace_back();
  std::vector<std::pair<BuildChild, std::uint32_t>> todo{{tree.root, 0}};
  while (!todo.empty()) {
    const auto [c, index] = todo.back();
    todo.pop_back();
    if (c.is_leaf()) {
      out.nodes[index].first = c.first;
      out.nodes[index].count = c.count;
      continue;
    }
    const BinaryBuildNode& n = tree.nodes[c.first];
    const auto first = std::uint32_t(out.nodes.size());
    out.nodes[index].first = first;
    out.nodes[index].count = 0;
    out.nodes.emplace_back();
    out.nodes.emplace_back();
    todo.push_back({n.child[1], first + 1});
    todo.push_back({n.child[0], first});
  }
  for (std::size_t i = out.nodes.size(); i-- > 0;) {
    BvhNode<T>& n = out.nodes[i];
    n.box = BBox<T>{};
    if (n.is_leaf()) {
      for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
        const Triangle<T>& t = out.tris[k];
        n.box.extend(t.v0), n.box.extend(t.v1), n.box.extend(t.v2);
      }
    } else {
      n.box.extend(out.nodes[n.first].box);
      n.box.extend(out.nodes[n.first + 1].box);
    }
  }
}

}  // namespace

template <typename T>
Bvh<T> build_bvh(const Scene& scene, const BvhBuildOptions& opts) {
  Bvh<T> out;
  out.scene_max_abs = scene.bounds().max_abs_coord();
  const detail::BuiltTree<2> tree = detail::build_tree<2, T>(scene, opts, opts.max_leaf_size);
  if (!tree.empty()) write_binary(scene, tree, out);
  return out;
}

template Bvh<float> build_bvh<float>(const Scene&, const BvhBuildOptions&);
template Bvh<double> build_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
