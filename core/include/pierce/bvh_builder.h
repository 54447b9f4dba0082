#pragma once
// Building Pierce's BVHs from a scene: the binary Bvh<T> and the 8-wide WideBvh<T> that the
// kernels traverse. Both come from one binned SAH builder (Wald 2007) with the branching as a
// parameter (core/src/binned_builder.h), over the scene's non-degenerate triangles (degenerate in
// T: never hit). It partitions on float boxes rounded outward; every box of the result is the
// exact union (min and max in T) of the triangles below it, which the kernels' conservative box
// test relies on. Included by what builds a BVH (the Accel, the analyses, tests);
// the kernels include only the BVH layouts (bvh.h, wide_bvh.h).
#include "pierce/bvh.h"
#include "pierce/scene.h"
#include "pierce/wide_bvh.h"

namespace pierce {

struct BvhBuildOptions {
  int max_leaf_size = 8;  // the binary BVH's leaves
  // The wide BVH's leaves: up to two 8-lane blocks. Against one block, the 1.64 M-triangle shell
  // has 50 104 nodes instead of 84 689 (`pierce_bench_kernels --scene shell` prints the count).
  int wide_max_leaf_size = 16;
  float traversal_cost = 1.0f;  // relative to one 8-lane block test
  // The SAH's areas in float where every coordinate is below 2^59 (they stay finite there): the
  // tree the kernels are measured on. false: in double, as scenes beyond 2^59 always are.
  bool float_areas = true;
};

template <typename T>
Bvh<T> build_bvh(const Scene& scene, const BvhBuildOptions& opts = {});

template <typename T>
WideBvh<T> build_wide_bvh(const Scene& scene, const BvhBuildOptions& opts = {});

// Collapses a binary BVH: each wide node takes the binary children with the largest surface area
// apart until it holds eight; a subtree of at most eight triangles becomes one leaf block. For a
// binary BVH built another way (the tests build unusual layouts by hand).
template <typename T>
WideBvh<T> build_wide_bvh(const Bvh<T>& binary);

extern template Bvh<float> build_bvh<float>(const Scene&, const BvhBuildOptions&);
extern template Bvh<double> build_bvh<double>(const Scene&, const BvhBuildOptions&);
extern template WideBvh<float> build_wide_bvh<float>(const Scene&, const BvhBuildOptions&);
extern template WideBvh<double> build_wide_bvh<double>(const Scene&, const BvhBuildOptions&);
extern template WideBvh<float> build_wide_bvh<float>(const Bvh<float>&);
extern template WideBvh<double> build_wide_bvh<double>(const Bvh<double>&);

}  // namespace pierce
