#pragma once
// Ray/box slab test. Only max, min, subtraction and multiplication by a per-ray constant:
// all monotone under rounding, so a child box's [tn, tf] lies inside its parent's.
#include <limits>

#include "pierce/traversal_ray.h"

namespace pierce {

template <typename T>
struct Span {
  T tn, tf;
};

// Raw computed interval; tn > tf (or +inf) means a miss even before widening.
template <typename T>
inline Span<T> slab(const TraversalRay<T>& r, const Vec3<T>& lo, const Vec3<T>& hi) {
  constexpr T inf = std::numeric_limits<T>::infinity();
  T tn = -inf, tf = inf;
  for (int a = 0; a < 3; ++a) {
    if (r.zero[a]) {
      if (r.org[a] < lo[a] || r.org[a] > hi[a]) return {inf, -inf};
      continue;
    }
    T t0 = (lo[a] - r.org[a]) * r.inv[a];
    T t1 = (hi[a] - r.org[a]) * r.inv[a];
    if (r.inv[a] < T(0)) std::swap(t0, t1);
    tn = t0 > tn ? t0 : tn;
    tf = t1 < tf ? t1 : tf;
  }
  return {tn, tf};
}

// The box is entered within [lo_t, hi_t] if it passes the widened test and overlaps the range.
template <typename T>
inline bool box_overlaps(const TraversalRay<T>& r, const Span<T>& s, T lo_t, T hi_t) {
  const T wf = r.widen(s.tf);
  return s.tn <= wf && s.tn <= hi_t && wf >= lo_t;
}

}  // namespace pierce
