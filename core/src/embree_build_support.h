#pragma once
// Float boxes for the builders that partition on them (Embree's rtcBuildBVH for the binary BVH,
// Pierce's binned builder for the wide one), and what the rtcBuildBVH call needs: the device and
// its arguments. The float boxes only choose the partition; both builders recompute every box
// exactly in precision T afterwards.
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "pierce/bbox.h"
#include "pierce/huge_page_allocator.h"

namespace pierce::detail {

// Stateless for rtcBuildBVH, so one device is shared by every build.
inline RTCDevice builder_device() {
  static const RTCDevice device = rtcNewDevice("threads=0");
  return device;
}

// Float bounds containing x (exact for float input).
inline float round_down(double x) {
  const auto f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
inline float round_up(double x) {
  const auto f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// `b` rounded outward to float, with two ids in the fourth lanes (Embree's layout: geomID, primID).
template <typename T>
RTCBuildPrimitive build_primitive(const BBox<T>& b, std::uint32_t geom, std::uint32_t prim) {
  return {round_down(double(b.lo.x)), round_down(double(b.lo.y)), round_down(double(b.lo.z)), geom,
          round_up(double(b.hi.x)),   round_up(double(b.hi.y)),   round_up(double(b.hi.z)),   prim};
}

// Arguments for a build over `prims` (ids = their indices) into `bvh` with Pierce's callbacks, at
// medium quality; the caller sets branching factor and leaf sizes.
inline RTCBuildArguments build_arguments(RTCBVH bvh, HugePageVector<RTCBuildPrimitive>& prims, float traversal_cost,
                                         RTCCreateNodeFunction create_node, RTCSetNodeChildrenFunction set_children,
                                         RTCSetNodeBoundsFunction set_bounds, RTCCreateLeafFunction create_leaf) {
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.traversalCost = traversal_cost;
  args.intersectionCost = 1.0f;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_node;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  return args;
}

}  // namespace pierce::detail
