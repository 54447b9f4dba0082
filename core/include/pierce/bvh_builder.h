#pragma once
// Binary SAH BVH for Bvh<T>: Embree's parallel builder (rtcBuildBVH, binned SAH) into Pierce's
// nodes where the scene's coordinates are within what Embree's builder keeps (kEmbreeMaxCoord),
// else Pierce's own binned SAH builder (Wald 2007). Either way every node's box is then recomputed
// from its triangles in precision T, exactly (min and max), so the tree's boxes are the exact
// unions the kernels' conservative box test relies on; Embree only chooses the partition.
#include "pierce/bvh.h"
#include "pierce/embree_limits.h"
#include "pierce/scene.h"

namespace pierce {

struct BvhBuildOptions {
  int bins = 16;                   // Pierce's binary builder only
  int max_leaf_size = 8;
  // The wide BVH's leaves (its binned SAH builder): up to two 8-lane blocks. Against one block,
  // the 1.64 M-triangle shell has 50 104 nodes instead of 84 689 (docs/BENCHMARKS.md).
  int wide_max_leaf_size = 16;
  float traversal_cost = 1.0f;     // relative to one triangle test
  // false: always Pierce's binary builder in precision T (for the wide BVH: then collapsed),
  // instead of Embree's rtcBuildBVH (binary) or the float binned builder (wide).
  bool embree_builder = true;
};


template <typename T>
Bvh<T> build_bvh(const Scene& scene, const BvhBuildOptions& opts = {});

extern template Bvh<float> build_bvh<float>(const Scene&, const BvhBuildOptions&);
extern template Bvh<double> build_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
