#include "pierce/bvh_builder.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace pierce {

namespace {

// SAH bin of a centroid coordinate. Near the float range the centroid or the extent overflow to
// infinity and the position becomes NaN or infinite: clamp without converting those to int
// (undefined behaviour; found by the kernel fuzzer).
inline int bin_index(double c, double lo, double scale, int nb) {
  const double x = (c - lo) * scale;
  if (!(x > 0.0)) return 0;  // also NaN
  return x < double(nb - 1) ? int(x) : nb - 1;
}

template <typename T>
struct Builder {
  const BvhBuildOptions& opts;
  std::vector<Triangle<T>> tris;
  std::vector<BBox<T>> tri_box;
  std::vector<Vec3<T>> centroid;
  std::vector<std::uint32_t> order;
  std::vector<BvhNode<T>> nodes;

  BBox<T> bounds_of(std::uint32_t begin, std::uint32_t end, BBox<T>* cbox) const {
    BBox<T> b;
    for (std::uint32_t i = begin; i < end; ++i) {
      b.extend(tri_box[order[i]]);
      cbox->extend(centroid[order[i]]);
    }
    return b;
  }

  // Builds the subtree for order[begin, end) into node `index`.
  void build(std::uint32_t index, std::uint32_t begin, std::uint32_t end) {
    BBox<T> cbox;
    nodes[index].box = bounds_of(begin, end, &cbox);
    const std::uint32_t n = end - begin;
    auto make_leaf = [&] {
      nodes[index].first = begin;
      nodes[index].count = n;
    };
    if (n <= 1) return make_leaf();

    // Best binned SAH split over the three axes.
    const int nb = opts.bins;
    float best_cost = std::numeric_limits<float>::infinity();
    int best_axis = -1, best_bin = 0;
    const Vec3<T> ext = cbox.extent();
    for (int axis = 0; axis < 3; ++axis) {
      if (!(ext[axis] > T(0))) continue;
      std::vector<BBox<T>> bb(nb);
      std::vector<std::uint32_t> cnt(nb, 0);
      const double scale = double(nb) / double(ext[axis]);
      auto bin_of = [&](std::uint32_t tri) { return bin_index(centroid[tri][axis], cbox.lo[axis], scale, nb); };
      for (std::uint32_t i = begin; i < end; ++i) {
        const int k = bin_of(order[i]);
        bb[k].extend(tri_box[order[i]]);
        ++cnt[k];
      }
      std::vector<float> right_area(nb);
      std::vector<std::uint32_t> right_cnt(nb);
      BBox<T> acc;
      std::uint32_t c = 0;
      for (int k = nb - 1; k > 0; --k) {
        acc.extend(bb[k]);
        c += cnt[k];
        right_area[k] = float(acc.half_area());
        right_cnt[k] = c;
      }
      acc = BBox<T>{};
      c = 0;
      for (int k = 0; k < nb - 1; ++k) {
        acc.extend(bb[k]);
        c += cnt[k];
        if (c == 0 || right_cnt[k + 1] == 0) continue;
        const float cost = float(acc.half_area()) * float(c) + right_area[k + 1] * float(right_cnt[k + 1]);
        if (cost < best_cost) best_cost = cost, best_axis = axis, best_bin = k;
      }
    }
    const float parent_area = float(nodes[index].box.half_area());
    const float leaf_cost = float(n);
    const float split_cost = opts.traversal_cost + (parent_area > 0 ? best_cost / parent_area : 0.f);
    if (best_axis < 0) {
      // All centroids coincide: split by index so huge stacks of coincident triangles still form a tree.
      if (n <= std::uint32_t(opts.max_leaf_size)) return make_leaf();
      return split(index, begin, begin + n / 2, end);
    }
    if (n <= std::uint32_t(opts.max_leaf_size) && leaf_cost <= split_cost) return make_leaf();

    const double scale = double(nb) / double(ext[best_axis]);
    auto* mid = std::partition(order.data() + begin, order.data() + end, [&](std::uint32_t tri) {
      return bin_index(centroid[tri][best_axis], cbox.lo[best_axis], scale, nb) <= best_bin;
    });
    split(index, begin, std::uint32_t(mid - order.data()), end);
  }

  void split(std::uint32_t index, std::uint32_t begin, std::uint32_t mid, std::uint32_t end) {
    const auto left = std::uint32_t(nodes.size());
    nodes.emplace_back();
    nodes.emplace_back();
    nodes[index].first = left;
    nodes[index].count = 0;
    build(left, begin, mid);
    build(left + 1, mid, end);
  }
};

}  // namespace

template <typename T>
Bvh<T> build_bvh(const Scene& scene, const BvhBuildOptions& opts) {
  Builder<T> b{opts, {}, {}, {}, {}, {}};
  for (std::uint32_t g = 0; g < scene.geometries().size(); ++g) {
    const Geometry& geo = scene.geometry(g);
    for (std::uint32_t p = 0; p < geo.triangles.size(); ++p) {
      const Tri& t = geo.triangles[p];
      const Vec3<T> v0(geo.vertices[t[0]]), v1(geo.vertices[t[1]]), v2(geo.vertices[t[2]]);
      if (is_degenerate(v0, v1, v2)) continue;
      b.tris.push_back({v0, v1, v2, g, p});
      BBox<T> box;
      box.extend(v0), box.extend(v1), box.extend(v2);
      b.tri_box.push_back(box);
      b.centroid.push_back(box.center());
    }
  }
  Bvh<T> bvh;
  bvh.scene_max_abs = scene.bounds().max_abs_coord();
  if (b.tris.empty()) return bvh;
  b.order.resize(b.tris.size());
  std::iota(b.order.begin(), b.order.end(), 0u);
  b.nodes.reserve(2 * b.tris.size());
  b.nodes.emplace_back();
  b.build(0, 0, std::uint32_t(b.tris.size()));
  bvh.nodes = std::move(b.nodes);
  bvh.tris.reserve(b.tris.size());
  for (std::uint32_t i : b.order) bvh.tris.push_back(b.tris[i]);
  return bvh;
}

template Bvh<float> build_bvh<float>(const Scene&, const BvhBuildOptions&);
template Bvh<double> build_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
