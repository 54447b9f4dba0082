// core/include/pierce/exact_sign.h against GMP rationals, on inputs built to sit at or within one
// rounding of zero (where the rounded evaluation gets the sign wrong).
#include <gtest/gtest.h>
#include <gmpxx.h>

#include <cmath>
#include <random>

#include "pierce/exact_sign.h"

namespace {

mpq_class q(double x) { return mpq_class(x); }

TEST(ExactSign, DiffOfProductsNearZero) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.5, 1.0);
  int rounded_wrong = 0;
  for (int i = 0; i < 200000; ++i) {
    // The edge function of (x, y) and (-l x, -l y) (an edge through the origin, up to rounding):
    // a*b - c*d = (-l x) y - (-l y) x.
    const double x = U(rng), y = -U(rng), l = U(rng);
    double a = -l * x, b = y, c = -l * y, d = x;
    if (i % 3 == 1) a = std::nextafter(a, 2.0);
    if (i % 3 == 2) a = -2 * x, c = -2 * y;  // exactly zero
    const int exact = sgn(q(a) * q(b) - q(c) * q(d));
    ASSERT_EQ(pierce::exact::diff_of_products_sign(a, b, c, d), exact) << a << " " << b << " " << c << " " << d;
    const double r = a * b - c * d;
    rounded_wrong += (r > 0) - (r < 0) != exact;
  }
  EXPECT_GT(rounded_wrong, 0) << "the inputs should defeat plain double arithmetic";
}

TEST(ExactSign, Orient2dNearCollinear) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int i = 0; i < 200000; ++i) {
    const double ax = U(rng), ay = U(rng), bx = U(rng), by = U(rng), l = 0.5 + 0.5 * U(rng);
    double cx = ax + (bx - ax) * l, cy = ay + (by - ay) * l;  // collinear up to rounding
    if (i % 4 == 0) cx = ax, cy = ay;                         // a repeated corner: exactly zero
    if (i % 4 == 1) cx = 2 * bx - ax, cy = 2 * by - ay;       // often exactly collinear
    const int exact = sgn((q(bx) - q(ax)) * (q(cy) - q(ay)) - (q(by) - q(ay)) * (q(cx) - q(ax)));
    ASSERT_EQ(pierce::exact::orient2d_sign(ax, ay, bx, by, cx, cy), exact);
  }
}

}  // namespace
