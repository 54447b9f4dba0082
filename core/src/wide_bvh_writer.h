#pragma once
// Writing the wide BVH's nodes and leaf blocks: shared by the direct 8-wide build
// (wide_bvh_builder.cpp) and the collapse of a binary BVH (wide_bvh_collapse.cpp), so both
// produce the same layout from the same boxes.
#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

#include "pierce/wide_bvh.h"

namespace pierce::detail {

// Sets the `n` child boxes of `w` (slots 0..n-1; the rest empty, so they can never pass) and its
// near-to-far order for each direction octant, ranked by the child box centres along
// (+-1, +-1, +-1). The child references are left to the caller.
template <typename T>
void set_wide_boxes(WideNode<T>& w, const BBox<T>* boxes, int n) {
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < kWideArity; ++s) {
      w.lo[a][s] = std::numeric_limits<T>::infinity();
      w.hi[a][s] = -std::numeric_limits<T>::infinity();
    }
  for (int s = 0; s < kWideArity; ++s) w.child[s] = 0;
  for (int s = 0; s < n; ++s)
    for (int a = 0; a < 3; ++a) w.lo[a][s] = boxes[s].lo[a], w.hi[a][s] = boxes[s].hi[a];
  // Per octant, each child's rank by key (its centre along (+-1, +-1, +-1); ties by slot, empty
  // slots last): a stable sort of eight, without branches on the keys.
  std::array<std::array<double, 3>, kWideArity> centre{};
  for (int s = 0; s < n; ++s)
    for (int a = 0; a < 3; ++a) centre[s][a] = 0.5 * (double(boxes[s].lo[a]) + double(boxes[s].hi[a]));
  const std::uint32_t valid = (1u << n) - 1;
  for (int oct = 0; oct < 8; ++oct) {
    std::array<double, kWideArity> key{};
    for (int s = 0; s < kWideArity; ++s) {
      key[s] = std::numeric_limits<double>::infinity();
      if (s >= n) continue;
      key[s] = 0;
      for (int a = 0; a < 3; ++a) key[s] += (oct >> a & 1) ? -centre[s][a] : centre[s][a];
    }
    std::uint32_t packed = valid << 24;
    for (int s = 0; s < kWideArity; ++s) {
      int rank = 0;
      for (int t = 0; t < kWideArity; ++t) rank += int(key[t] < key[s] || (key[t] == key[s] && t < s));
      packed |= std::uint32_t(s) << (3 * rank);
    }
    w.order[oct] = packed;
  }
}

// Fills leaf blocks out.blocks[first, first + ceil(count / 8)) with the triangles tri(0..count-1)
// (a Triangle<T> each, in that order), padding the last block with masked lanes, and returns the
// leaf's reference and its exact box. The blocks must exist already (several leaves can then be
// written in parallel).
template <typename T, class TriangleAt>
NodeRef write_leaf(WideBvh<T>& out, std::uint32_t first, std::size_t count, const TriangleAt& tri, BBox<T>& box) {
  const auto nblocks = std::uint32_t((count + kBlockLanes - 1) / kBlockLanes);
  for (std::uint32_t b = 0; b < nblocks; ++b) {
    TriBlock<T>& blk = out.blocks[first + b];
    blk = TriBlock<T>{};  // padding lanes: zero corners, never tested (valid)
    for (int l = 0; l < kBlockLanes; ++l) {
      blk.geom[l] = blk.prim[l] = kInvalidId;
      const std::size_t k = std::size_t(b) * kBlockLanes + std::size_t(l);
      if (k >= count) continue;
      const Triangle<T> t = tri(k);
      const Vec3<T> p[3] = {t.v0, t.v1, t.v2};
      const SumOrder so = sum_order(t.v0, t.v1, t.v2);
      for (int c = 0; c < 3; ++c) {
        box.extend(p[c]);
        for (int a = 0; a < 3; ++a) blk.v[c][a][l] = p[so.o[c]][a];
      }
      blk.geom[l] = t.geom;
      blk.prim[l] = t.prim;
      blk.sum[l] = so;
      blk.valid |= 1u << l;
    }
  }
  return make_leaf_ref(first, nblocks);
}

// Blocks a leaf of `count` triangles takes; throws where the reference cannot hold them.
inline std::uint32_t leaf_blocks_for(std::size_t count) {
  const auto nblocks = std::uint32_t((count + kBlockLanes - 1) / kBlockLanes);
  if (nblocks > kMaxLeafBlocks)
    throw std::length_error("wide BVH: a leaf of more than 512 triangles (build with a smaller max_leaf_size)");
  return nblocks;
}

inline void check_block_count(std::size_t blocks) {
  if (blocks > kMaxBlocks) throw std::length_error("wide BVH: more than 2^28 triangles");
}

}  // namespace pierce::detail
