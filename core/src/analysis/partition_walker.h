#pragma once
// What a worker thread of the partition analyses (gqa, shotline) keeps from ray to ray: the hit
// iterator, with exits before entries at equal t so that touching solids leave no overlap, and
// the buffers of one ray's hits, partitions and CSG intervals.
#include <vector>

#include "pierce/analysis/csg.h"
#include "pierce/analysis/ray_partitions.h"
#include "pierce/kernel.h"

namespace pierce::analysis {

struct PartitionWalker {
  HitIterator it;
  PartitionBuilder builder;
  std::vector<Hit> hits;
  RayPartitions parts;
  std::vector<CsgInterval> intervals;

  PartitionWalker(const Accel& accel, KernelKind kernel)
      : it(accel, kernel, KernelOptions{HitOrder{TieOrder::leave_before_enter}}),
        builder(accel.scene().geometries().size()) {}
};

}  // namespace pierce::analysis
