#pragma once
//! \file complex_interval.h
//! Rectangular complex intervals: ComplexInterval = Re × Im, two CGAL double intervals, and the
//! straight-line-program arithmetic over them (ScalarTraits<ComplexInterval>), for the complex
//! Krawczyk test of certified homotopy continuation (solvers/homotopy_certificate.h).
//!
//! Enclosure.  **Every operation requires a live RoundingGuard** (the operations are those of
//! Interval, scalar_traits.h).  For all complex values a ∈ A, b ∈ B of the operand rectangles the
//! exact result lies in the output rectangle:
//!  - A ± B = (Re A ± Re B, Im A ± Im B);
//!  - A · B = (Re A Re B − Im A Im B, Re A Im B + Im A Re B), each part an interval expression in
//!    which every real factor ranges over its own interval, so the exact product of any a ∈ A,
//!    b ∈ B is enclosed (interval arithmetic's inclusion property);
//!  - A² = (Re A² − Im A², 2 Re A Im A) with Re A² the exact range of x² (tighter than A · A);
//!  - 1/A = (Re A, −Im A) / d, d = Re A² + Im A² (= |a|² ∈ d for a ∈ A); when inf d ≤ 0 the
//!    result is the whole plane [−∞, ∞]²;  A / B = A · (1/B);
//!  - A^n (integer n ≥ 1) by binary powering with the products above; A^0 = 1; n < 0 is 1/A^|n|;
//!  - constants: the Interval enclosure of the exact rational (or π) as real part, imaginary 0.
//! Written as a real computation on (Re, Im) these are exactly the real interval operations on the
//! 2×2 real form of complex multiplication, so a complex Krawczyk operator evaluated with them is
//! the real Krawczyk operator of the same map on R^{2n} (krawczyk.h's theorem applies).
//! exp, log, sqrt, sin and cos are not provided (homotopy continuation is for polynomial
//! systems): they throw PreconditionViolation.

#include "common/errors.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

struct ComplexInterval {
  Interval re{0.0};
  Interval im{0.0};
  ComplexInterval() = default;
  ComplexInterval(Interval real, Interval imaginary) : re(real), im(imaginary) {}
  //! The degenerate rectangle at z.
  explicit ComplexInterval(Complex z) : re(z.real()), im(z.imag()) {}
};

//! True iff no point of the rectangle is 0 (one of its parts certainly excludes 0).
inline bool certainly_nonzero(const ComplexInterval& a) { return certainly_nonzero(a.re) || certainly_nonzero(a.im); }

template <>
struct ScalarTraits<ComplexInterval> {
  static long precision() { return 0; }
  static void set_precision(ComplexInterval&, long) {}
  static void set_rational(ComplexInterval& out, const Rational& q) {
    ScalarTraits<Interval>::set_rational(out.re, q);
    out.im = Interval(0.0);
  }
  static void set_pi(ComplexInterval& out) {
    ScalarTraits<Interval>::set_pi(out.re);
    out.im = Interval(0.0);
  }
  static void assign(ComplexInterval& out, const ComplexInterval& a) { out = a; }
  static void add(ComplexInterval& out, const ComplexInterval& a, const ComplexInterval& b) {
    out = ComplexInterval(a.re + b.re, a.im + b.im);
  }
  static void sub(ComplexInterval& out, const ComplexInterval& a, const ComplexInterval& b) {
    out = ComplexInterval(a.re - b.re, a.im - b.im);
  }
  static void mul(ComplexInterval& out, const ComplexInterval& a, const ComplexInterval& b) {
    out = ComplexInterval(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re);
  }
  static void neg(ComplexInterval& out, const ComplexInterval& a) { out = ComplexInterval(-a.re, -a.im); }
  static void square(ComplexInterval& out, const ComplexInterval& a) {
    out = ComplexInterval(CGAL::square(a.re) - CGAL::square(a.im), 2.0 * (a.re * a.im));
  }
  static void inv(ComplexInterval& out, const ComplexInterval& a) {
    const Interval d = CGAL::square(a.re) + CGAL::square(a.im);
    if (!(d.inf() > 0)) {
      out = ComplexInterval(Interval::largest(), Interval::largest());
      return;
    }
    out = ComplexInterval(a.re / d, -a.im / d);
  }
  static void div(ComplexInterval& out, const ComplexInterval& a, const ComplexInterval& b) {
    ComplexInterval r;
    inv(r, b);
    mul(out, a, r);
  }
  static void pow(ComplexInterval& out, const ComplexInterval& a, int n) {
    if (n == 0) {
      out = ComplexInterval(Interval(1.0), Interval(0.0));
      return;
    }
    ComplexInterval p;
    detail::power_by_squaring<ScalarTraits<ComplexInterval>>(p, a, n < 0 ? -static_cast<long>(n) : n);
    if (n < 0)
      inv(out, p);
    else
      out = p;
  }
  [[noreturn]] static void not_polynomial() {
    throw PreconditionViolation("ComplexInterval: exp, log, sqrt, sin and cos are not provided");
  }
  static void exp(ComplexInterval&, const ComplexInterval&) { not_polynomial(); }
  static void log(ComplexInterval&, const ComplexInterval&) { not_polynomial(); }
  static void sqrt(ComplexInterval&, const ComplexInterval&) { not_polynomial(); }
  static void sin(ComplexInterval&, const ComplexInterval&) { not_polynomial(); }
  static void cos(ComplexInterval&, const ComplexInterval&) { not_polynomial(); }
};

// Explicitly instantiated in compiled_system.cpp.
extern template void CompiledSystem::values<ComplexInterval>(const ComplexInterval*, const ComplexInterval*,
                                                             ComplexInterval*) const;
extern template void CompiledSystem::values_and_jacobian<ComplexInterval>(const ComplexInterval*,
                                                                          const ComplexInterval*, ComplexInterval*,
                                                                          ComplexInterval*) const;

}  // namespace delmesh
