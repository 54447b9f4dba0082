#pragma once
// The hits of a batch of rays in one array (compressed rows): no allocation per ray, and one
// contiguous block a front end can hand on as it is (NumPy, VTK arrays).
#include <cstddef>
#include <span>
#include <vector>

#include "pierce/hit.h"

namespace pierce {

struct HitBatch {
  std::vector<Hit> hits;             // every ray's hits, ray by ray, each ray's in hit order
  std::vector<std::size_t> offsets;  // ray i's hits are hits[offsets[i], offsets[i + 1])

  std::size_t rays() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::span<const Hit> of(std::size_t ray) const {
    return {hits.data() + offsets[ray], hits.data() + offsets[ray + 1]};
  }
};

}  // namespace pierce
