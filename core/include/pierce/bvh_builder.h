#pragma once
// Binned SAH builder (Wald 2007) for Bvh<T>.
#include "pierce/bvh.h"
#include "pierce/scene.h"

namespace pierce {

struct BvhBuildOptions {
  int bins = 16;
  int max_leaf_size = 8;
  float traversal_cost = 1.0f;     // relative to one triangle test
};

template <typename T>
Bvh<T> build_bvh(const Scene& scene, const BvhBuildOptions& opts = {});

extern template Bvh<float> build_bvh<float>(const Scene&, const BvhBuildOptions&);
extern template Bvh<double> build_bvh<double>(const Scene&, const BvhBuildOptions&);

}  // namespace pierce
