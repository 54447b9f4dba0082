#pragma once
// Exact signs in double precision: a*b - c*d for the double triangle test's edge functions, and
// 2D orientations for the exact zero-area test of triangles.
// The rounded result decides when it is clearly away from zero; otherwise the rounding errors
// of both products are recovered exactly with fma (error-free products) and the four-term sum
// is added up as a non-overlapping expansion (Shewchuk 1997), whose largest term has the sign
// of the exact value. Exact while no product underflows (|a*b|, |c*d| above ~1e-292 or zero)
// and nothing overflows.
#include <cmath>

namespace pierce::exact {

// s + e == a + b exactly, s = fl(a + b) (Knuth's TwoSum, no ordering precondition).
inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

// Sign of x[0] + ... + x[N-1], exactly.
template <int N>
inline int sum_sign(const double (&x)[N]) {
  double h[N];
  int m = 0;
  for (double q : x) {  // Grow-Expansion: h stays non-overlapping, increasing in magnitude
    for (int j = 0; j < m; ++j) {
      double s, e;
      two_sum(q, h[j], s, e);
      h[j] = e;
      q = s;
    }
    h[m++] = q;
  }
  for (int j = m - 1; j >= 0; --j)
    if (h[j] != 0.0) return h[j] > 0.0 ? 1 : -1;
  return 0;
}

inline int diff_of_products_sign(double a, double b, double c, double d) {
  const double p = a * b, q = c * d, r = p - q;
  // |a*b - c*d - (p - q)| <= 2^-53 (|p| + |q|), and r has the sign of p - q: past 2^-52 (|p| + |q|)
  // the rounding cannot have changed the sign.
  if (std::abs(r) > 0x1p-52 * (std::abs(p) + std::abs(q))) return r > 0.0 ? 1 : -1;
  const double x[4] = {p, -q, std::fma(a, b, -p), -std::fma(c, d, -q)};
  return sum_sign(x);
}

// Sign of the 2D orientation (b - a) x (c - a), exactly: expanded into six products of the raw
// coordinates (the differences themselves would round), each split into its rounded value and
// its exact error.
inline int orient2d_sign(double ax, double ay, double bx, double by, double cx, double cy) {
  // Fast path with Shewchuk's error bound for the rounded evaluation (ccwerrboundA).
  const double left = (ax - cx) * (by - cy), right = (ay - cy) * (bx - cx), det = left - right;
  const double bound = (3.0 + 16.0 * 0x1p-53) * 0x1p-53 * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return det > 0.0 ? 1 : -1;
  const double p[6][2] = {{bx, cy}, {ax, by}, {cx, ay}, {by, cx}, {ay, bx}, {cy, ax}};  // + + + - - -
  double x[12];
  for (int i = 0; i < 6; ++i) {
    const double v = p[i][0] * p[i][1], e = std::fma(p[i][0], p[i][1], -v);
    x[2 * i] = i < 3 ? v : -v;
    x[2 * i + 1] = i < 3 ? e : -e;
  }
  return sum_sign(x);
}

}  // namespace pierce::exact
