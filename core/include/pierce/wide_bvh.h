#pragma once
// 8-wide BVH in precision T. Child boxes are stored structure-of-arrays so one SIMD slab test
// covers all eight children; leaves are blocks of up to eight triangles, also structure-of-arrays,
// with raw vertices (shared vertices stay bit-identical to the input) stored in each triangle's
// SumOrder, so the fixed summation order needs no per-ray work and a whole block can be finished
// in SIMD.
//
// Every box is the exact union (min and max in T, no rounding) of the triangles below it, so a
// child's box lies inside its parent's and "triangle hit => every enclosing box hit" holds.
// The layout only: the builders are declared in bvh_builder.h.
#include <cstdint>
#include <limits>
#include <vector>

#include "pierce/bbox.h"
#include "pierce/hit.h"
#include "pierce/huge_page_allocator.h"
#include "pierce/triangle.h"

namespace pierce {

inline constexpr int kWideArity = 8;
inline constexpr int kBlockLanes = 8;

// A child reference: an inner node's index, or a leaf: `kLeafFlag | first_block << 6 | (blocks-1)`.
using NodeRef = std::uint32_t;
inline constexpr NodeRef kLeafFlag = 0x80000000u;
inline constexpr std::uint32_t kMaxLeafBlocks = 64;
inline constexpr std::uint32_t kMaxBlocks = 1u << 25;
constexpr bool is_leaf(NodeRef r) { return (r & kLeafFlag) != 0; }
constexpr std::uint32_t leaf_first_block(NodeRef r) { return (r & ~kLeafFlag) >> 6; }
constexpr std::uint32_t leaf_block_count(NodeRef r) { return (r & 63u) + 1; }
constexpr NodeRef make_leaf_ref(std::uint32_t first_block, std::uint32_t blocks) {
  return kLeafFlag | first_block << 6 | (blocks - 1);
}

// A node to visit and the distance at which the ray enters it (the traversal's stack and queue).
template <typename T>
struct NodeEntry {
  T tn;
  NodeRef ref;
};

template <typename T>
struct alignas(64) WideNode {
  // Child boxes by axis and slot; unused slots hold the empty box (lo = +inf, hi = -inf) and are
  // also masked out by valid(), so they can never pass.
  T lo[3][kWideArity];
  T hi[3][kWideArity];
  NodeRef child[kWideArity];
  // Near-to-far child order for each direction octant (bit a set: direction component a < 0),
  // computed at build time from the child box centres: bits 3k..3k+2 hold the slot ranked k-th.
  // Bits 24..31 of every entry hold the mask of used slots (a 256-byte node for float).
  std::uint32_t order[8];

  std::uint32_t valid() const { return order[0] >> 24; }
  static constexpr int slot_at_rank(std::uint32_t order_word, int rank) { return int(order_word >> (3 * rank) & 7u); }
};

template <typename T>
struct alignas(64) TriBlock {
  // What the SIMD test reads comes first and together (the lane mask, then the corners); the ids
  // are read only for the few lanes that hit.
  // Trivial (no member initialisers), so blocks can be allocated untouched and first written by
  // the thread that fills them; TriBlock<T>{} is all zeros.
  std::uint32_t valid;  // bit l: lane l holds a triangle (padding lanes are masked, never repeated)
  SumOrder sum[kBlockLanes];  // the stored corner k of lane l is the input's corner sum[l].o[k]
  alignas(32) T v[3][3][kBlockLanes];  // v[k][axis][lane]: the input corners in SumOrder
  std::uint32_t geom[kBlockLanes];
  std::uint32_t prim[kBlockLanes];

  // Stored corner k (in SumOrder).
  Vec3<T> corner(int k, int lane) const { return {v[k][0][lane], v[k][1][lane], v[k][2][lane]}; }
  // The input's corner i.
  Vec3<T> input_corner(int i, int lane) const {
    const SumOrder& so = sum[lane];
    return corner(so.o[0] == i ? 0 : (so.o[1] == i ? 1 : 2), lane);
  }
  // Lane `lane`'s triangle: the input's corners in the input's order, and its ids.
  Triangle<T> triangle(int lane) const {
    return {input_corner(0, lane), input_corner(1, lane), input_corner(2, lane), geom[lane], prim[lane]};
  }
};

template <typename T>
struct WideBvh {
  // In huge pages where the system gives them (huge_page_allocator.h): a ray reads a few nodes and
  // blocks spread over both arrays.
  HugePageVector<WideNode<T>> nodes;  // nodes[0] is the root when root is not a leaf
  HugePageVector<TriBlock<T>> blocks;
  BBox<T> bounds;                  // of every triangle: the root's box
  NodeRef root = make_leaf_ref(0, 1);
  std::uint32_t depth = 0;         // inner levels on the longest root-to-leaf path
  std::size_t triangles = 0;
  double scene_max_abs = 0;        // for TraversalRay::make

  bool empty() const { return triangles == 0; }
  // Entries a depth-first stack can hold at most: seven siblings left behind per level, plus one.
  std::size_t stack_capacity() const { return std::size_t(depth) * (kWideArity - 1) + 1; }
  std::size_t memory_bytes() const {
    return nodes.size() * sizeof(WideNode<T>) + blocks.size() * sizeof(TriBlock<T>);
  }
};

using WideBvhf = WideBvh<float>;
using WideBvhd = WideBvh<double>;

}  // namespace pierce
