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

namespace detail {

// The rest of the test once the edge functions U, V, W and their exact signs su, sv, sw are known
// (the signs already agree): det, t, the clamp into the triangle's slab interval, the range.
// za, zb, zc: the corners' kz coordinates relative to the origin. kSignsOfValues: the signs are
// those of U, V, W themselves (no exact path was taken), so nothing needs fixing.
template <bool kSignsOfValues, typename T>
inline bool finish_intersect(const TraversalRay<T>& r, const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2,
                             SumOrder so, T U, T V, T W, int su, int sv, int sw, T za, T zb, T zc, T tlo, T thi,
                             TriangleHit<T>& out) {
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
  const T e[3] = {U, V, W};
  if constexpr (!kSignsOfValues) fix(U, su), fix(V, sv), fix(W, sw);

  const T az = r.sz * za, bz = r.sz * zb, cz = r.sz * zc;
  // Sum the per-vertex terms in the triangle's SumOrder (see there).
  const T w[3] = {U, V, W}, z[3] = {az, bz, cz};
  const std::uint8_t* o = so.o;
  const T det = (w[o[0]] + w[o[1]]) + w[o[2]];
  if (det == T(0)) return false;  // ray lies in the triangle's plane
  const T inv_det = T(1) / det;
  const T tnum = (e[o[0]] * z[o[0]] + e[o[1]] * z[o[1]]) + e[o[2]] * z[o[2]];
  T t = tnum / det;  // one rounding of exact terms where the coordinates are small dyadics
  if (!std::isfinite(t)) {
    // tnum is cubic in the coordinates and overflowed: use the corners' barycentric weights,
    // which lie in [0, 1], so t cannot overflow where the corners' z do not.
    const T g[3] = {U * inv_det, V * inv_det, W * inv_det};
    t = (g[o[0]] * z[o[0]] + g[o[1]] * z[o[1]]) + g[o[2]] * z[o[2]];
  }

  const Span<T> box = slab(r, vmin(vmin(p0, p1), p2), vmax(vmax(p0, p1), p2));
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

  out.t = t;
  out.u = V * inv_det;
  out.v = W * inv_det;
  out.enter = det > T(0);
  return true;
}

}  // namespace detail

// Returns true and fills `out` on a hit with t in [tlo, thi]. The reported t is clamped into
// the triangle's own slab interval so that every box containing the triangle contains t.
// `so` must be sum_order(p0, p1, p2).
template <typename T>
inline bool intersect(const TraversalRay<T>& r, const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2,
                      SumOrder so, T tlo, T thi, TriangleHit<T>& out) {
  const Vec3<T> a = p0 - r.org, b = p1 - r.org, c = p2 - r.org;
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
  return detail::finish_intersect<false>(r, p0, p1, p2, so, U, V, W, su, sv, sw, a[r.kz], b[r.kz], c[r.kz], tlo, thi, out);
}

// intersect() for a float triangle whose edge functions U, V, W were computed as there (the SIMD
// leaf test computes them lane by lane in the same operations): the same answer, bit for bit,
// without computing them again. Zero or non-finite values take intersect()'s exact path.
inline bool intersect_given_edges(const TraversalRay<float>& r, const Vec3f& p0, const Vec3f& p1, const Vec3f& p2,
                                  SumOrder so, float U, float V, float W, float tlo, float thi,
                                  TriangleHit<float>& out) {
  if (U == 0.0f || V == 0.0f || W == 0.0f || !std::isfinite(U + V + W))
    return intersect(r, p0, p1, p2, so, tlo, thi, out);
  const int su = U > 0.0f ? 1 : -1, sv = V > 0.0f ? 1 : -1, sw = W > 0.0f ? 1 : -1;
  if (su != sv || su != sw) return false;
  const float oz = r.org[r.kz];
  return detail::finish_intersect<true>(r, p0, p1, p2, so, U, V, W, su, sv, sw, p0[r.kz] - oz, p1[r.kz] - oz,
                                  p2[r.kz] - oz, tlo, thi, out);
}

template <typename T>
inline bool intersect(const TraversalRay<T>& r, const Vec3<T>& p0, const Vec3<T>& p1, const Vec3<T>& p2, T tlo,
                      T thi, TriangleHit<T>& out) {
  return intersect(r, p0, p1, p2, sum_order(p0, p1, p2), tlo, thi, out);
}

}  // namespace pierce
