#include "pierce/exact_predicates.h"

#include <cmath>
#include <vector>

namespace pierce {

namespace {

// Expansions: sums of non-overlapping doubles in increasing magnitude (Shewchuk 1997). The
// sign of an expansion is the sign of its last (largest) component.
using Expansion = std::vector<double>;

constexpr double kEps = 0x1p-53;  // half an ulp of 1

inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a, av = x - bv;
  y = (a - av) + (b - bv);
}

inline void two_diff(double a, double b, double& x, double& y) {
  x = a - b;
  const double bv = a - x, av = x + bv;
  y = (a - av) + (bv - b);
}

inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);  // exact error term, whatever the contraction flags
}

// e + b (grow_expansion_zeroelim).
Expansion grow(const Expansion& e, double b) {
  Expansion h;
  h.reserve(e.size() + 1);
  double q = b;
  for (double ei : e) {
    double qn, hh;
    two_sum(q, ei, qn, hh);
    q = qn;
    if (hh != 0.0) h.push_back(hh);
  }
  if (q != 0.0 || h.empty()) h.push_back(q);
  return h;
}

Expansion add(Expansion e, const Expansion& f) {
  for (double fi : f) e = grow(e, fi);
  return e;
}

// e * b (scale_expansion_zeroelim).
Expansion scale(const Expansion& e, double b) {
  Expansion h;
  if (e.empty()) return h;
  h.reserve(2 * e.size());
  double q, hh;
  two_product(e[0], b, q, hh);
  if (hh != 0.0) h.push_back(hh);
  for (std::size_t i = 1; i < e.size(); ++i) {
    double p1, p0, sum;
    two_product(e[i], b, p1, p0);
    two_sum(q, p0, sum, hh);
    if (hh != 0.0) h.push_back(hh);
    two_sum(p1, sum, q, hh);
    if (hh != 0.0) h.push_back(hh);
  }
  if (q != 0.0 || h.empty()) h.push_back(q);
  return h;
}

Expansion mul(const Expansion& e, const Expansion& f) {
  Expansion r{0.0};
  for (double fi : f) r = add(r, scale(e, fi));
  return r;
}

Expansion negate(Expansion e) {
  for (double& x : e) x = -x;
  return e;
}

Expansion diff(double a, double b) {
  double x, y;
  two_diff(a, b, x, y);
  if (y == 0.0) return {x};
  return {y, x};
}

int sign(const Expansion& e) {
  for (auto it = e.rbegin(); it != e.rend(); ++it)
    if (*it != 0.0) return *it > 0 ? 1 : -1;
  return 0;
}

}  // namespace

int orient2d(Vec2d a, Vec2d b, Vec2d c) {
  const double detleft = (b.x - a.x) * (c.y - a.y);
  const double detright = (b.y - a.y) * (c.x - a.x);
  const double det = detleft - detright;
  const double bound = (3.0 + 16.0 * kEps) * kEps * (std::abs(detleft) + std::abs(detright));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  const Expansion e = add(mul(diff(b.x, a.x), diff(c.y, a.y)), negate(mul(diff(b.y, a.y), diff(c.x, a.x))));
  return sign(e);
}

int orient3d(Vec3d a, Vec3d b, Vec3d c, Vec3d d) {
  const Vec3d u = b - a, v = c - a, w = d - a;
  const double m0 = v.y * w.z - v.z * w.y, m1 = v.z * w.x - v.x * w.z, m2 = v.x * w.y - v.y * w.x;
  const double det = u.x * m0 + u.y * m1 + u.z * m2;
  const double permanent = std::abs(u.x) * (std::abs(v.y * w.z) + std::abs(v.z * w.y)) +
                           std::abs(u.y) * (std::abs(v.z * w.x) + std::abs(v.x * w.z)) +
                           std::abs(u.z) * (std::abs(v.x * w.y) + std::abs(v.y * w.x));
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  const Expansion ux = diff(b.x, a.x), uy = diff(b.y, a.y), uz = diff(b.z, a.z);
  const Expansion vx = diff(c.x, a.x), vy = diff(c.y, a.y), vz = diff(c.z, a.z);
  const Expansion wx = diff(d.x, a.x), wy = diff(d.y, a.y), wz = diff(d.z, a.z);
  const Expansion e0 = add(mul(vy, wz), negate(mul(vz, wy)));
  const Expansion e1 = add(mul(vz, wx), negate(mul(vx, wz)));
  const Expansion e2 = add(mul(vx, wy), negate(mul(vy, wx)));
  return sign(add(add(mul(ux, e0), mul(uy, e1)), mul(uz, e2)));
}

}  // namespace pierce
