#pragma once
// Axis-aligned bounding box; empty() boxes have lo > hi.
#include <limits>

#include "pierce/vec3.h"

namespace pierce {

template <typename T>
struct BBox {
  Vec3<T> lo{std::numeric_limits<T>::infinity(), std::numeric_limits<T>::infinity(),
             std::numeric_limits<T>::infinity()};
  Vec3<T> hi{-std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity(),
             -std::numeric_limits<T>::infinity()};

  void extend(Vec3<T> p) { lo = vmin(lo, p); hi = vmax(hi, p); }
  void extend(const BBox& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  Vec3<T> extent() const { return hi - lo; }
  Vec3<T> center() const { return (lo + hi) * T(0.5); }
  T half_area() const {
    if (empty()) return T(0);
    const Vec3<T> e = extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
  T max_abs_coord() const { return empty() ? T(0) : std::max(max_abs(lo), max_abs(hi)); }
};

using BBoxf = BBox<float>;
using BBoxd = BBox<double>;

}  // namespace pierce
