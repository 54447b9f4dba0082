#include "pierce/wide_bvh.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace pierce {

namespace {

template <typename T>
struct Collapser {
  const Bvh<T>& bin;
  WideBvh<T>& out;
  std::vector<std::uint32_t> tri_count;  // triangles under each binary node
  std::vector<std::uint32_t> scratch;

  std::uint32_t count(std::uint32_t i) {
    const BvhNode<T>& n = bin.nodes[i];
    if (n.is_leaf()) return tri_count[i] = n.count;
    return tri_count[i] = count(n.first) + count(n.first + 1);
  }

  void gather(std::uint32_t i, std::vector<std::uint32_t>& tris) const {
    const BvhNode<T>& n = bin.nodes[i];
    if (n.is_leaf()) {
      for (std::uint32_t t = n.first; t < n.first + n.count; ++t) tris.push_back(t);
      return;
    }
    gather(n.first, tris);
    gather(n.first + 1, tris);
  }

  // The triangles of binary subtree i as one leaf of consecutive blocks.
  NodeRef make_leaf(std::uint32_t i) {
    scratch.clear();
    gather(i, scratch);
    const auto nblocks = std::uint32_t((scratch.size() + kBlockLanes - 1) / kBlockLanes);
    if (nblocks > kMaxLeafBlocks)
      throw std::length_error("wide BVH: a leaf of more than 512 triangles (build with a smaller max_leaf_size)");
    const auto first = std::uint32_t(out.blocks.size());
    if (std::size_t(first) + nblocks > kMaxBlocks)
      throw std::length_error("wide BVH: more than 2^28 triangles");
    for (std::uint32_t b = 0; b < nblocks; ++b) {
      TriBlock<T>& blk = out.blocks.emplace_back();
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a)
          for (int l = 0; l < kBlockLanes; ++l) blk.v[c][a][l] = T(0);
      for (int l = 0; l < kBlockLanes; ++l) {
        blk.geom[l] = blk.prim[l] = kInvalidId;
        const std::size_t k = std::size_t(b) * kBlockLanes + std::size_t(l);
        if (k >= scratch.size()) continue;
        const Triangle<T>& t = bin.tris[scratch[k]];
        const Vec3<T> p[3] = {t.v0, t.v1, t.v2};
        for (int c = 0; c < 3; ++c)
          for (int a = 0; a < 3; ++a) blk.v[c][a][l] = p[c][a];
        blk.geom[l] = t.geom;
        blk.prim[l] = t.prim;
        blk.sum[l] = sum_order(t.v0, t.v1, t.v2);
        blk.valid |= 1u << l;
      }
    }
    out.triangles += scratch.size();
    return make_leaf_ref(first, nblocks);
  }

  NodeRef ref_of(std::uint32_t i, std::uint32_t level) {
    const BvhNode<T>& n = bin.nodes[i];
    if (n.is_leaf() || tri_count[i] <= std::uint32_t(kBlockLanes)) return make_leaf(i);
    return make_inner(i, level);
  }

  NodeRef make_inner(std::uint32_t i, std::uint32_t level) {
    out.depth = std::max(out.depth, level + 1);
    // Open the binary subtree: replace the inner child of largest area by its two children
    // until there are eight (or only leaves and small subtrees are left).
    std::array<std::uint32_t, kWideArity> kids{};
    int nk = 0;
    kids[nk++] = bin.nodes[i].first;
    kids[nk++] = bin.nodes[i].first + 1;
    while (nk < kWideArity) {
      int best = -1;
      T best_area = T(-1);
      for (int k = 0; k < nk; ++k) {
        const BvhNode<T>& c = bin.nodes[kids[k]];
        if (c.is_leaf() || tri_count[kids[k]] <= std::uint32_t(kBlockLanes)) continue;
        const T area = c.box.half_area();
        if (area > best_area) best_area = area, best = k;
      }
      if (best < 0) break;
      const std::uint32_t opened = kids[best];
      kids[best] = bin.nodes[opened].first;
      kids[nk++] = bin.nodes[opened].first + 1;
    }
    const auto index = std::uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    {
      WideNode<T>& w = out.nodes[index];
      for (int a = 0; a < 3; ++a)
        for (int s = 0; s < kWideArity; ++s) {
          w.lo[a][s] = std::numeric_limits<T>::infinity();
          w.hi[a][s] = -std::numeric_limits<T>::infinity();
        }
      for (int s = 0; s < kWideArity; ++s) w.child[s] = 0;
      for (int s = 0; s < nk; ++s) {
        const BBox<T>& b = bin.nodes[kids[s]].box;
        for (int a = 0; a < 3; ++a) w.lo[a][s] = b.lo[a], w.hi[a][s] = b.hi[a];
      }
      const std::uint32_t valid = (1u << nk) - 1;
      // Near-to-far per octant: rank the children by their centres along (+-1, +-1, +-1).
      for (int oct = 0; oct < 8; ++oct) {
        std::array<int, kWideArity> slot{};
        std::array<double, kWideArity> key{};
        for (int s = 0; s < kWideArity; ++s) {
          slot[s] = s;
          key[s] = std::numeric_limits<double>::infinity();  // empty slots last
          if (s >= nk) continue;
          const BBox<T>& b = bin.nodes[kids[s]].box;
          key[s] = 0;
          for (int a = 0; a < 3; ++a) {
            const double c = 0.5 * (double(b.lo[a]) + double(b.hi[a]));
            key[s] += (oct >> a & 1) ? -c : c;
          }
        }
        // Insertion sort (stable, no allocation): eight entries.
        for (int i = 1; i < kWideArity; ++i)
          for (int j = i; j > 0 && key[slot[j]] < key[slot[j - 1]]; --j) std::swap(slot[j], slot[j - 1]);
        std::uint32_t packed = valid << 24;
        for (int k = 0; k < kWideArity; ++k) packed |= std::uint32_t(slot[k]) << (3 * k);
        w.order[oct] = packed;
      }
    }
    // Children after the node itself (the vector may grow: no references kept across this).
    for (int s = 0; s < nk; ++s) {
      const NodeRef r = ref_of(kids[s], level + 1);
      out.nodes[index].child[s] = r;
    }
    return index;
  }
};

}  // namespace

template <typename T>
WideBvh<T> build_wide_bvh(const Bvh<T>& binary) {
  WideBvh<T> out;
  out.scene_max_abs = binary.scene_max_abs;
  if (binary.empty() || binary.nodes.empty()) return out;
  out.bounds = binary.nodes[0].box;
  Collapser<T> c{binary, out, std::vector<std::uint32_t>(binary.nodes.size(), 0), {}};
  c.count(0);
  out.nodes.reserve(binary.nodes.size() / 4 + 1);
  out.blocks.reserve(binary.tris.size() / 4 + 1);
  out.root = c.ref_of(0, 0);
  return out;
}

template WideBvh<float> build_wide_bvh<float>(const Bvh<float>&);
template WideBvh<double> build_wide_bvh<double>(const Bvh<double>&);

}  // namespace pierce
