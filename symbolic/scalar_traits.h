#pragma once
//! \file scalar_traits.h
//! The arithmetic a straight-line program needs, per scalar type: ScalarTraits<T> for
//! T ∈ {double, Interval, MpfrReal, MpfiInterval, Complex} (scalar_types.h).  Every operation
//! writes its result into `out`; `out` may alias an operand.
//!
//! Operations: set_rational (an exact rational constant), set_pi, assign, add, sub, mul, div, neg,
//! inv (1/a), square, pow (integer exponent), exp, log, sqrt, sin, cos.
//!
//! ## What each type guarantees
//! - double, Complex: round-to-nearest floating point; no guarantee beyond the libm's accuracy.
//!   Constants are the nearest double (real part) to the exact rational, and π is the nearest
//!   double.  pow uses binary powering (squaring).
//! - MpfrReal: every operation is one correctly rounded MPFR call (round to nearest) at the
//!   precision of `out`; rational constants are correctly rounded (mpfr_set_q), pow is
//!   mpfr_pow_si (one rounding).
//! - Interval (CGAL::Interval_nt<false>): **requires a live RoundingGuard** (upward rounding).
//!   For every real value of the operands inside the operand intervals, the exact real result lies
//!   in `out` (an enclosure), with the following domain conventions:
//!   * rational constants and π are enclosed by the two directed roundings of the exact value
//!     (MPFR at 53 bits, rounding down and up);
//!   * +, −, ×, ÷, sqrt, square: CGAL's interval arithmetic (IEEE-754 correctly rounded basic
//!     operations with directed rounding); division by an interval containing 0 gives [−∞, +∞];
//!   * pow(a, n): exact range of x ↦ xⁿ over a (even n ≥ 0 uses the mignitude and magnitude, odd
//!     n is monotone), so square([−1, 2]) = pow([−1, 2], 2) = [0, 4]; the endpoint powers are
//!     enclosed by CGAL interval products of nonnegative point intervals; n < 0 is 1/(a^|n|);
//!   * exp, log: monotone, so the range is [f(lo), f(hi)]; sin, cos: the endpoint values, plus
//!     ±1 whenever a maximum (resp. minimum) of the function may lie in the interval, decided with
//!     a generous margin (an extremum closer than about 1e-10·(1+|x|/2π)·2π to the interval counts
//!     as inside, which costs nothing since the function is flat there), and [−1, 1] when the
//!     interval is at least 2π wide or unbounded.  The endpoint values come from glibc's exp, log,
//!     sin, cos and are widened outward by tolerances::libm_ulp_margin = 10 ulps.  **This rests on
//!     glibc's accuracy:** the glibc manual ("Errors in Math Functions") states that its math test
//!     suite flags as an error any result more than 9 ulp from the correctly rounded value, and the
//!     test suite exercises every rounding mode (the libm-test-ulps tables record exp, log, sin
//!     and cos at ≤ 1–2 ulp on x86_64 in all four modes; Gladman–Innocente–Mather–Zimmermann,
//!     "Accuracy of mathematical functions", hal-03141101, measured < 0.52 ulp for glibc 2.33 in
//!     round-to-nearest).  Results are finally clamped to the function's range ([0, ∞) for exp,
//!     [−1, 1] for sin and cos);
//!   * domain errors: log(a) with inf(a) ≤ 0 and sqrt(a) with inf(a) < 0 give the whole line
//!     [−∞, +∞] — never a partial enclosure that would let a caller exclude a box wrongly.  Such
//!     infinite bounds can turn into NaN bounds in later CGAL products (0 · ∞).  An interval with a
//!     NaN or infinite bound carries no information: test exclusion with certainly_nonzero(),
//!     which is false for it.
//! - MpfiInterval: MPFI's rigorous interval operations at the precision of `out`, with the same
//!   pow and domain conventions as Interval (log with left ≤ 0, sqrt with left < 0 → [−∞, +∞]).

#include <cmath>
#include <cstdint>
#include <limits>

#include <boost/multiprecision/gmp.hpp>

#include "symbolic/scalar_types.h"

namespace delmesh {

//! An exact rational constant of a compiled program.
using Rational = boost::multiprecision::mpq_rational;

template <class T>
struct ScalarTraits;

//! True iff the interval certainly excludes 0 (false for NaN bounds): the one exclusion test
//! a caller should use on an interval result.
inline bool certainly_nonzero(const Interval& a) { return a.inf() > 0 || a.sup() < 0; }
//! MPFI version of certainly_nonzero (false for NaN bounds).
bool certainly_nonzero(const MpfiInterval& a);

namespace detail {
//! out = a^n for n ≥ 1 by binary powering, with the operations of Traits (any T).
template <class Traits, class T>
void power_by_squaring(T& out, const T& a, unsigned long n) {
  T base = a;
  bool have = false;
  T result = a;
  while (n > 0) {
    if (n & 1UL) {
      if (have) {
        Traits::mul(result, result, base);
      } else {
        Traits::assign(result, base);
        have = true;
      }
    }
    n >>= 1;
    if (n > 0) Traits::square(base, base);
  }
  Traits::assign(out, result);
}
}  // namespace detail

template <>
struct ScalarTraits<double> {
  //! No run-time precision: 0.
  static long precision() { return 0; }
  static void set_precision(double&, long) {}
  static void set_rational(double& out, const Rational& q);
  static void set_pi(double& out);
  static void assign(double& out, const double& a) { out = a; }
  static void add(double& out, const double& a, const double& b) { out = a + b; }
  static void sub(double& out, const double& a, const double& b) { out = a - b; }
  static void mul(double& out, const double& a, const double& b) { out = a * b; }
  static void div(double& out, const double& a, const double& b) { out = a / b; }
  static void neg(double& out, const double& a) { out = -a; }
  static void inv(double& out, const double& a) { out = 1.0 / a; }
  static void square(double& out, const double& a) { out = a * a; }
  static void pow(double& out, const double& a, int n) {
    double p = 1.0;
    if (n != 0) detail::power_by_squaring<ScalarTraits<double>>(p, a, n < 0 ? -static_cast<long>(n) : n);
    out = n < 0 ? 1.0 / p : p;
  }
  static void exp(double& out, const double& a) { out = std::exp(a); }
  static void log(double& out, const double& a) { out = std::log(a); }
  static void sqrt(double& out, const double& a) { out = std::sqrt(a); }
  static void sin(double& out, const double& a) { out = std::sin(a); }
  static void cos(double& out, const double& a) { out = std::cos(a); }
};

template <>
struct ScalarTraits<Complex> {
  static long precision() { return 0; }
  static void set_precision(Complex&, long) {}
  static void set_rational(Complex& out, const Rational& q);
  static void set_pi(Complex& out);
  static void assign(Complex& out, const Complex& a) { out = a; }
  static void add(Complex& out, const Complex& a, const Complex& b) { out = a + b; }
  static void sub(Complex& out, const Complex& a, const Complex& b) { out = a - b; }
  //! The textbook (a + bi)(c + di): std::complex's operator* goes through libgcc's __muldc3
  //! (C99 Annex G recovery of infinite results from NaN parts), several times slower; the two
  //! differ only when a part overflows or is not finite.
  static void mul(Complex& out, const Complex& a, const Complex& b) {
    out = Complex(a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real());
  }
  static void div(Complex& out, const Complex& a, const Complex& b) { out = a / b; }
  static void neg(Complex& out, const Complex& a) { out = -a; }
  static void inv(Complex& out, const Complex& a) { out = 1.0 / a; }
  static void square(Complex& out, const Complex& a) {
    out = Complex((a.real() - a.imag()) * (a.real() + a.imag()), 2 * a.real() * a.imag());
  }
  static void pow(Complex& out, const Complex& a, int n) {
    Complex p = 1.0;
    if (n != 0) detail::power_by_squaring<ScalarTraits<Complex>>(p, a, n < 0 ? -static_cast<long>(n) : n);
    out = n < 0 ? 1.0 / p : p;
  }
  static void exp(Complex& out, const Complex& a) { out = std::exp(a); }
  static void log(Complex& out, const Complex& a) { out = std::log(a); }
  static void sqrt(Complex& out, const Complex& a) { out = std::sqrt(a); }
  static void sin(Complex& out, const Complex& a) { out = std::sin(a); }
  static void cos(Complex& out, const Complex& a) { out = std::cos(a); }
};

//! Interval operations; every one requires a live RoundingGuard (see the file comment).
template <>
struct ScalarTraits<Interval> {
  static long precision() { return 0; }
  static void set_precision(Interval&, long) {}
  //! The tightest double interval containing q.
  static void set_rational(Interval& out, const Rational& q);
  //! The tightest double interval containing π.
  static void set_pi(Interval& out);
  static void assign(Interval& out, const Interval& a) { out = a; }
  static void add(Interval& out, const Interval& a, const Interval& b) { out = a + b; }
  static void sub(Interval& out, const Interval& a, const Interval& b) { out = a - b; }
  static void mul(Interval& out, const Interval& a, const Interval& b) { out = a * b; }
  static void div(Interval& out, const Interval& a, const Interval& b) { out = a / b; }
  static void neg(Interval& out, const Interval& a) { out = -a; }
  static void inv(Interval& out, const Interval& a) { out = 1.0 / a; }
  //! The exact range {x² : x ∈ a}, rounded outward.
  static void square(Interval& out, const Interval& a) { out = CGAL::square(a); }
  //! The exact range {xⁿ : x ∈ a}, rounded outward (n < 0: 1 / a^|n|).
  static void pow(Interval& out, const Interval& a, int n);
  static void exp(Interval& out, const Interval& a);
  //! inf(a) ≤ 0 → [−∞, +∞].
  static void log(Interval& out, const Interval& a);
  //! inf(a) < 0 → [−∞, +∞].
  static void sqrt(Interval& out, const Interval& a);
  static void sin(Interval& out, const Interval& a);
  static void cos(Interval& out, const Interval& a);
  //! [−∞, +∞].
  static Interval whole_line() { return Interval::largest(); }
};

//! MPFR operations, each correctly rounded to nearest at the precision of `out`.
template <>
struct ScalarTraits<MpfrReal> {
  //! The precision in bits of a default-constructed MpfrReal (Boost's default_precision()).
  static long precision();
  static void set_precision(MpfrReal& out, long bits);
  static void set_rational(MpfrReal& out, const Rational& q);
  static void set_pi(MpfrReal& out);
  //! Rounds a to the precision of out (unlike operator=, which copies a's precision).
  static void assign(MpfrReal& out, const MpfrReal& a);
  static void add(MpfrReal& out, const MpfrReal& a, const MpfrReal& b);
  static void sub(MpfrReal& out, const MpfrReal& a, const MpfrReal& b);
  static void mul(MpfrReal& out, const MpfrReal& a, const MpfrReal& b);
  static void div(MpfrReal& out, const MpfrReal& a, const MpfrReal& b);
  static void neg(MpfrReal& out, const MpfrReal& a);
  static void inv(MpfrReal& out, const MpfrReal& a);
  static void square(MpfrReal& out, const MpfrReal& a);
  static void pow(MpfrReal& out, const MpfrReal& a, int n);
  static void exp(MpfrReal& out, const MpfrReal& a);
  static void log(MpfrReal& out, const MpfrReal& a);
  static void sqrt(MpfrReal& out, const MpfrReal& a);
  static void sin(MpfrReal& out, const MpfrReal& a);
  static void cos(MpfrReal& out, const MpfrReal& a);
};

//! MPFI operations: rigorous enclosures at the precision of `out` (see the file comment for pow
//! and the domain conventions).
template <>
struct ScalarTraits<MpfiInterval> {
  //! The precision in bits of a default-constructed MpfiInterval (Boost's default_precision()).
  static long precision();
  static void set_precision(MpfiInterval& out, long bits);
  static void set_rational(MpfiInterval& out, const Rational& q);
  static void set_pi(MpfiInterval& out);
  //! Encloses a at the precision of out.
  static void assign(MpfiInterval& out, const MpfiInterval& a);
  static void add(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b);
  static void sub(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b);
  static void mul(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b);
  static void div(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b);
  static void neg(MpfiInterval& out, const MpfiInterval& a);
  static void inv(MpfiInterval& out, const MpfiInterval& a);
  static void square(MpfiInterval& out, const MpfiInterval& a);
  static void pow(MpfiInterval& out, const MpfiInterval& a, int n);
  static void exp(MpfiInterval& out, const MpfiInterval& a);
  static void log(MpfiInterval& out, const MpfiInterval& a);
  static void sqrt(MpfiInterval& out, const MpfiInterval& a);
  static void sin(MpfiInterval& out, const MpfiInterval& a);
  static void cos(MpfiInterval& out, const MpfiInterval& a);
  static void set_whole_line(MpfiInterval& out);
};

}  // namespace delmesh
