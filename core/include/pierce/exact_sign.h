#pragma once
// Exact sign of a*b - c*d in double precision, for the double triangle test's edge functions.
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

// Sign of x[0] + ... + x[3], exactly.
inline int sum4_sign(const double (&x)[4]) {
  double h[4];
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
  return sum4_sign(x);
}

}  // namespace pierce::exact
