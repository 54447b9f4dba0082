#pragma once
// Per-ray state handed to Embree through an extended RTCIntersectContext. The user-geometry
// intersect callback runs Pierce's exact triangle test and then the kernel's filter:
// restart keeps the closest hit after `last`, all-hits keeps everything, N-closest keeps a
// bounded heap. Embree's own tnear/tfar are only ever used for culling, with slack and in a
// rebased frame, so Embree's rounding can cost work but never a hit.
#include <embree3/rtcore.h>

#include <vector>

#include "pierce/counters.h"
#include "pierce/hit.h"
#include "pierce/huge_page_allocator.h"
#include "pierce/triangle.h"

namespace pierce {

struct EmbreeQuery {
  RTCIntersectContext ctx;  // must stay first: Embree hands back a pointer to it
  enum class Mode { restart, all, closest_n } mode = Mode::restart;
  const HugePageVector<Triangle<float>>* tris = nullptr;
  TraversalRay<float> ray;
  HitOrder order;
  double t_base = 0;   // Embree's t = (Pierce's t - t_base) * t_scale
  double t_scale = 1;  // power of two: Embree's direction is Pierce's / t_scale, of magnitude ~1
  float lo = 0, hi = 0;  // current range (Pierce's t)
  Hit last;
  bool have_last = false;
  Hit best;                       // restart
  std::vector<Hit>* hits = nullptr;  // all: unsorted; closest_n: max-heap in hit order
  std::size_t n = 0;
  Counters* counters = nullptr;  // null: the kernel does not count

  // Embree-frame bounds around a Pierce-frame t, widened to absorb both sides' rounding.
  double slack(double t) const { return std::ldexp(std::abs(t), -18) + 4.0 * double(ray.pad); }
  float embree_far(double t) const { return float((t + slack(t) - t_base) * t_scale); }
  float embree_near(double t) const { return float(std::max(0.0, (t - slack(t) - t_base) * t_scale)); }
};

namespace detail {
void embree_exact_intersect(const RTCIntersectFunctionNArguments* args);
}

}  // namespace pierce
