#pragma once
// Exact dyadic numbers m * 2^e (m a GMP integer) for the oracle. Every finite double is one,
// and sums, differences and products of them stay exact, so signs and comparisons of the
// oracle's polynomials in the input coordinates are exact, without range limits.
#include <gmpxx.h>

#include <cmath>

namespace pierce::oracle {

class Exact {
 public:
  Exact() = default;
  // Exact value of a finite double.
  explicit Exact(double x) {
    if (x == 0.0) return;
    int ex = 0;
    const double f = std::frexp(x, &ex);  // x = f * 2^ex, 0.5 <= |f| < 1: ldexp(f, 53) is an integer
    m_ = mpz_class(std::ldexp(f, 53));
    e_ = long(ex) - 53;
    const mp_bitcnt_t tz = mpz_scan1(m_.get_mpz_t(), 0);  // keep mantissas short
    mpz_fdiv_q_2exp(m_.get_mpz_t(), m_.get_mpz_t(), tz);
    e_ += long(tz);
  }

  int sign() const { return sgn(m_); }
  bool is_zero() const { return sgn(m_) == 0; }

  friend Exact operator*(const Exact& a, const Exact& b) {
    Exact r;
    if (a.is_zero() || b.is_zero()) return r;
    r.m_ = a.m_ * b.m_;
    r.e_ = a.e_ + b.e_;
    return r;
  }
  friend Exact operator+(const Exact& a, const Exact& b) { return add(a, b, false); }
  friend Exact operator-(const Exact& a, const Exact& b) { return add(a, b, true); }
  Exact operator-() const {
    Exact r = *this;
    r.m_ = -r.m_;
    return r;
  }
  // Multiplication by 2^k: exact.
  Exact scaled_pow2(long k) const {
    Exact r = *this;
    if (!r.is_zero()) r.e_ += k;
    return r;
  }

  // Sign of a - b.
  friend int compare(const Exact& a, const Exact& b) { return (a - b).sign(); }
  friend bool operator==(const Exact& a, const Exact& b) { return compare(a, b) == 0; }

  mpq_class to_mpq() const {
    mpq_class q(m_);
    if (e_ >= 0) mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(e_));
    else mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-e_));
    return q;
  }

  // Nearest double (for display and tolerances only; never for decisions).
  double to_double() const {
    if (is_zero()) return 0.0;
    long ex = 0;
    const double d = mpz_get_d_2exp(&ex, m_.get_mpz_t());
    return std::ldexp(d, int(ex + e_));
  }

 private:
  static Exact add(const Exact& a, const Exact& b, bool negate_b) {
    if (b.is_zero()) return a;
    if (a.is_zero()) return negate_b ? -b : b;
    Exact r;
    // Align to the smaller exponent: shifting left is exact.
    if (a.e_ >= b.e_) {
      mpz_mul_2exp(r.m_.get_mpz_t(), a.m_.get_mpz_t(), mp_bitcnt_t(a.e_ - b.e_));
      if (negate_b) r.m_ -= b.m_; else r.m_ += b.m_;
      r.e_ = b.e_;
    } else {
      mpz_mul_2exp(r.m_.get_mpz_t(), b.m_.get_mpz_t(), mp_bitcnt_t(b.e_ - a.e_));
      if (negate_b) r.m_ = a.m_ - r.m_; else r.m_ += a.m_;
      r.e_ = a.e_;
    }
    return r;
  }

  mpz_class m_{0};
  long e_ = 0;
};

// An exact rational num / den with den != 0, for hit distances.
struct ExactRatio {
  Exact num, den;
  // Sign of this - o.
  friend int compare(const ExactRatio& a, const ExactRatio& b) {
    const int s = (a.num * b.den - b.num * a.den).sign();
    return a.den.sign() * b.den.sign() > 0 ? s : -s;
  }
  // Sign of this - x for an exact x.
  int compare_to(const Exact& x) const {
    const int s = (num - x * den).sign();
    return den.sign() > 0 ? s : -s;
  }
  // Approximate value (GMP truncates toward zero): for display and tolerances only.
  double to_double() const { return mpq_class(num.to_mpq() / den.to_mpq()).get_d(); }
};

}  // namespace pierce::oracle
