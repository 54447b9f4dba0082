#pragma once
// Binary BVH over a scene's non-degenerate triangles, in precision T. Triangles are stored
// in leaf order next to the nodes (no indirection in the hot loop).
#include <cstdint>
#include <vector>

#include "pierce/bbox.h"
#include "pierce/huge_page_allocator.h"
#include "pierce/triangle.h"

namespace pierce {

template <typename T>
struct BvhNode {
  BBox<T> box;
  std::uint32_t first = 0;  // inner: index of the left child (right = first + 1); leaf: first triangle
  std::uint32_t count = 0;  // 0 for inner nodes
  bool is_leaf() const { return count != 0; }
};

template <typename T>
struct Bvh {
  HugePageVector<BvhNode<T>> nodes;  // nodes[0] is the root when !empty()
  HugePageVector<Triangle<T>> tris;
  double scene_max_abs = 0;       // for TraversalRay::make

  bool empty() const { return tris.empty(); }
  std::size_t memory_bytes() const {
    return nodes.size() * sizeof(BvhNode<T>) + tris.size() * sizeof(Triangle<T>);
  }
};

using Bvhf = Bvh<float>;
using Bvhd = Bvh<double>;

}  // namespace pierce
