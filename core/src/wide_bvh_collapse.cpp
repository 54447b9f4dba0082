#include <algorithm>
#include <array>

#include "pierce/bvh_builder.h"
#include "pierce/wide_bvh.h"
#include "wide_bvh_writer.h"

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
    const std::uint32_t nblocks = detail::leaf_blocks_for(scratch.size());
    const auto first = std::uint32_t(out.blocks.size());
    detail::check_block_count(std::size_t(first) + nblocks);
    out.blocks.resize(first + nblocks);
    out.triangles += scratch.size();
    BBox<T> box;  // the binary node's box already: the same exact union
    return detail::write_leaf(out, first, scratch.size(), [&](std::size_t k) { return bin.tris[scratch[k]]; }, box);
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
    std::array<BBox<T>, kWideArity> boxes{};
    for (int s = 0; s < nk; ++s) boxes[s] = bin.nodes[kids[s]].box;
    detail::set_wide_boxes(out.nodes[index], boxes.data(), nk);
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
