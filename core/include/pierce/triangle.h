#pragma once
// Watertight ray/triangle test (Woop, Benthin, Wald 2013) with a symbolic tie rule:
// edge functions that are exactly zero are decided as if the ray passed through the
// point (eps, eps^2) of the sheared plane. That point lies on no edge line, so a ray
// through a shared edge or vertex of a consistently meshed surface crosses exactly one
// of the triangles around it, whatever their winding.
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "pierce/exact_sign.h"
#include "pierce/slab.h"
#include "pierce/traversal_ray.h"

namespace pierce {

template <typename T>
struct Triangle {
  Vec3<T> v0, v1, v2;
  std::uint32_t geom, prim;
};

template <typename T>
struct TriangleHit {
  T t;
  T u, v;      // barycentric weights of v1 and v2
  bool enter;  // direction against (v1-v0)x(v2-v0)
};

namespace detail {

// Sign of the edge function E = p.x*q.y - p.y*q.x at the perturbed point; e is E at the origin.
template <typename W, typename T>
inline int perturbed_sign(W e, T px, T py, T qx, T qy) {
  if (e > W(0)) return 1;
  if (e < W(0)) return -1;
  // E(eps, eps^2) = eps*(p.y - q.y) + eps^2*(q.x - p.x); float differences have exact signs.
  if (py != qy) return py > qy ? 1 : -1;
  if (qx != px) return qx > px ? 1 : -1;
  return 0;
}

template <typename T>
inline bool lex_less(const Vec3<T>& a, const Vec3<T>& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

}  // namespace detail

// The order in which a triangle's three per-vertex terms are summed: its corners sorted by
// position (lexicographically), independent of their order in the triangle. Two triangles over
// the same three points (a face shared by touching solids, a duplicated face, either winding)
// then get bit-identical det and t, since reordering or reversing the corners only permutes the
// terms and negates them exactly. A property of the triangle, not of the ray: BVH leaves store it.
// (Trivial, so the wide BVH's leaf blocks can be allocated without being written; sum_order()
// makes every value.)
struct SumOrder {
  std::uint8_t o[3];
};

template <typename T>
inline SumOrder sum_order(const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2) {
  const Vec3<T>* p[3] = {&p0, &p1, &p2};
  SumOrder s{{0, 1, 2}};
  std::uint8_t* o = s.o;
  if (detail::lex_less(*p[o[1]], *p[o[0]])) std::swap(o[0], o[1]);
  if (detail::lex_less(*p[o[2]], *p[o[1]])) std::swap(o[1], o[2]);
  if (detail::lex_less(*p[o[1]], *p[o[0]])) std::swap(o[0], o[1]);
  return s;
}

// True if the corners in SumOrder are an odd permutation of the input's: the sorted triangle then
// has the opposite winding.
constexpr bool is_odd(SumOrder so) {
  return ((so.o[0] > so.o[1]) + (so.o[0] > so.o[2]) + (so.o[1] > so.o[2])) % 2 != 0;
}

// Where input corners 1 and 2 are among the sorted ones: their barycentric weights are the hit's
// u and v.
struct InputWeights {
  std::uint8_t u, v;
};
constexpr InputWeights input_weights(SumOrder so) {
  InputWeights w{0, 0};
  for (std::uint8_t k = 0; k < 3; ++k) {
    if (so.o[k] == 1) w.u = k;
    if (so.o[k] == 2) w.v = k;
  }
  return w;
}

// The hit in the input's terms, from det and the edge functions U, V, W of the sorted corners:
// u and v are the weights of input corners 1 and 2, and the facing flips with the parity of the
// sort. Shared by the scalar test and the lanes finished in SIMD.
template <typename T>
inline TriangleHit<T> input_frame_hit(T t, T det, T U, T V, T W, SumOrder so) {
  const T inv_det = T(1) / det;
  const T w[3] = {U, V, W};
  const InputWeights in = input_weights(so);
  return {t, w[in.u] * inv_det, w[in.v] * inv_det, (det > T(0)) != is_odd(so)};
}

namespace detail {

// The test is computed on the corners in SumOrder (q0, q1, q2 below). Reordering the corners only
// permutes the three edge functions and, for an odd permutation, negates them all exactly (each
// is a difference of two rounded products, and fl(x - y) = -fl(y - x)); det and the numerator of t
// then change sign together, so t, the barycentric weights and the decision are bit for bit those
// of any other corner order, and only the facing flips with the permutation's parity.

// The rest of the test once the edge functions U, V, W of the sorted corners and their exact signs
// su, sv, sw are known (the signs already agree): det, t, the clamp into the triangle's slab
// interval, the range. za, zb, zc: the sorted corners' kz coordinates relative to the origin.
// kSignsOfValues: the signs are those of U, V, W themselves (no exact path was taken), so nothing
// needs fixing. The hit is reported in the input's terms (so).
template <bool kSignsOfValues, typename T>
inline bool finish_intersect(const TraversalRay<T>& r, const Vec3<T>& q0, const Vec3<T>& q1, const Vec3<T>& q2,
                             SumOrder so, T U, T V, T W, int su, int sv, int sw, T za, T zb, T zc, T tlo,
                             T thi, TriangleHit<T>& out) {
  // Values that disagree with their exact sign (a double's false zero or wrong sign, a value that
  // underflowed, an exact zero decided by the tie rule) would spoil det: replace them by the
  // smallest normal value of the exact sign (normal: immune to flush-to-zero modes), so det is
  // never zero and has the exact facing. Only t of an almost edge-on triangle is affected, and t
  // is clamped into the triangle's box below.
  auto fix = [](T& e, int s) {
    if ((e > T(0) ? 1 : (e < T(0) ? -1 : 0)) != s) e = T(s) * std::numeric_limits<T>::min();
  };
  // t keeps the unfixed values: a tie-decided zero must add nothing to t, or a ray starting on a
  // vertex or edge would see that surface at a tiny t of either sign instead of exactly at 0.
  const T eU = U, eV = V, eW = W;
  if constexpr (!kSignsOfValues) fix(U, su), fix(V, sv), fix(W, sw);

  const T az = r.sz * za, bz = r.sz * zb, cz = r.sz * zc;
  // Summed in the sorted corners' order (see SumOrder).
  const T det = (U + V) + W;
  if (det == T(0)) return false;  // ray lies in the triangle's plane
  const T inv_det = T(1) / det;
  const T tnum = (eU * az + eV * bz) + eW * cz;
  T t = tnum / det;  // one rounding of exact terms where the coordinates are small dyadics
  if (!std::isfinite(t)) {
    // tnum is cubic in the coordinates and overflowed: use the corners' barycentric weights,
    // which lie in [0, 1], so t cannot overflow where the corners' z do not.
    t = ((U * inv_det) * az + (V * inv_det) * bz) + (W * inv_det) * cz;
  }

  const Span<T> box = slab(r, vmin(vmin(q0, q1), q2), vmax(vmax(q0, q1), q2));
  const T wf = r.widen(box.tf);
  if (box.tn > wf) return false;  // keeps "triangle hit" implying "every enclosing box hit"
  // Clamp into [tn, max(tn, tf)], not up to the widened wf: a triangle perpendicular to an axis
  // the ray is not parallel to has tn == tf, so every triangle in that plane (touching faces
  // meshed differently) gets the same t, the slab value, and ties are then decided by the ids.
  // max(tn, tf) <= wf, so every enclosing box still contains t.
  const T t_hi = box.tf > box.tn ? box.tf : box.tn;
  t = t < box.tn ? box.tn : (t > t_hi ? t_hi : t);
  // Not finite: a distance beyond T's range (a tiny direction), never reported.
  if (!(t >= tlo && t <= thi) || !std::isfinite(t)) return false;

  out = input_frame_hit(t, det, U, V, W, so);
  return true;
}

}  // namespace detail

// Returns true and fills `out` on a hit with t in [tlo, thi]. The reported t is clamped into
// the triangle's own slab interval so that every box containing the triangle contains t.
// q0, q1, q2: the triangle's corners in SumOrder (q[k] = input corner so.o[k]), as the wide BVH's
// leaves store them; the hit is reported in the input's terms.
template <typename T>
inline bool intersect_sorted(const TraversalRay<T>& r, const Vec3<T>& q0, const Vec3<T>& q1, const Vec3<T>& q2,
                             SumOrder so, T tlo, T thi, TriangleHit<T>& out) {
  const Vec3<T> a = q0 - r.org, b = q1 - r.org, c = q2 - r.org;
  const T ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const T bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const T cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];

  T U = cx * by - cy * bx;
  T V = ax * cy - ay * cx;
  T W = bx * ay - by * ax;
  int su, sv, sw;
  if constexpr (sizeof(T) < sizeof(double)) {
    if (U == T(0) || V == T(0) || W == T(0) || !std::isfinite(U + V + W)) {
      // Products of floats are exact in double: the sign of each edge function becomes exact
      // (also where a float product overflowed: inf - inf has no sign).
      const double Ud = double(cx) * double(by) - double(cy) * double(bx);
      const double Vd = double(ax) * double(cy) - double(ay) * double(cx);
      const double Wd = double(bx) * double(ay) - double(by) * double(ax);
      su = detail::perturbed_sign(Ud, cx, cy, bx, by);
      sv = detail::perturbed_sign(Vd, ax, ay, cx, cy);
      sw = detail::perturbed_sign(Wd, bx, by, ax, ay);
      U = T(Ud), V = T(Vd), W = T(Wd);
    } else {
      su = U > T(0) ? 1 : -1, sv = V > T(0) ? 1 : -1, sw = W > T(0) ? 1 : -1;
    }
  } else {
    // Double products are rounded: near zero an edge function can round to a false zero or the
    // wrong sign, so its sign is taken exactly (error-free products, exact_sign.h).
    su = detail::perturbed_sign(exact::diff_of_products_sign(cx, by, cy, bx), cx, cy, bx, by);
    sv = detail::perturbed_sign(exact::diff_of_products_sign(ax, cy, ay, cx), ax, ay, cx, cy);
    sw = detail::perturbed_sign(exact::diff_of_products_sign(bx, ay, by, ax), bx, by, ax, ay);
  }
  if (su == 0 || su != sv || su != sw) return false;
  return detail::finish_intersect<false>(r, q0, q1, q2, so, U, V, W, su, sv, sw, a[r.kz], b[r.kz], c[r.kz], tlo,
                                         thi, out);
}

// The test for corners in any order; `so` must be sum_order(p0, p1, p2).
template <typename T>
inline bool intersect(const TraversalRay<T>& r, const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2,
                      SumOrder so, T tlo, T thi, TriangleHit<T>& out) {
  const Vec3<T> p[3] = {p0, p1, p2};
  return intersect_sorted(r, p[so.o[0]], p[so.o[1]], p[so.o[2]], so, tlo, thi, out);
}

template <typename T>
inline bool intersect(const TraversalRay<T>& r, const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2, T tlo,
                      T thi, TriangleHit<T>& out) {
  return intersect(r, p0, p1, p2, sum_order(p0, p1, p2), tlo, thi, out);
}

}  // namespace pierce
