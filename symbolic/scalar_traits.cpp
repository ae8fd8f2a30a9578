#include "symbolic/scalar_traits.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <mpfi.h>
#include <mpfr.h>

#include "common/tolerances.h"

namespace delmesh {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

//! q rounded to a double in the given MPFR rounding mode (53-bit MPFR, then an exact get_d for
//! normal numbers; both roundings go the same direction, so the result stays on q's side).
double rational_to_double(const Rational& q, mpfr_rnd_t rounding) {
  mpfr_t t;
  mpfr_init2(t, 53);
  mpfr_set_q(t, q.backend().data(), rounding);
  const double d = mpfr_get_d(t, rounding);
  mpfr_clear(t);
  return d;
}

double pi_to_double(mpfr_rnd_t rounding) {
  mpfr_t t;
  mpfr_init2(t, 53);
  mpfr_const_pi(t, rounding);
  const double d = mpfr_get_d(t, rounding);
  mpfr_clear(t);
  return d;
}

double widen_down(double x) {
  for (int i = 0; i < tolerances::libm_ulp_margin; ++i) x = std::nextafter(x, -kInfinity);
  return x;
}
double widen_up(double x) {
  for (int i = 0; i < tolerances::libm_ulp_margin; ++i) x = std::nextafter(x, kInfinity);
  return x;
}

//! vⁿ for v ≥ 0 and n ≥ 1 rounded up (Up) or down, by binary powering under the guard's upward
//! rounding: plain products round up, and −((−a)·b) is the product a·b rounded down (a, b ≥ 0).
//! These are the products CGAL's interval arithmetic makes for the bounds of nonnegative point
//! intervals, without its case analysis, and only those of the bound asked for.  The exponents
//! up to 4 (the common ones in surface equations and their derivatives) are written out: the
//! same products in the same order as the loop, whose factors 1 are exact.
template <bool Up>
inline double nonnegative_power(double v, unsigned long n) {
  const auto times = [](double a, double b) {
    if constexpr (Up) {
      return a * b;
    } else {
      return -((-a) * b);
    }
  };
  switch (n) {
    case 1: return v;
    case 2: return times(v, v);
    case 3: return times(v, times(v, v));
    case 4: {
      const double square = times(v, v);
      return times(square, square);
    }
    default: break;
  }
  double base = v, result = 1;
  while (true) {
    if (n & 1UL) result = times(result, base);
    n >>= 1;
    if (n == 0) return result;
    base = times(base, base);
  }
}

constexpr double kTwoPi = 6.283185307179586;   // nearest double to 2π
constexpr double kHalfPi = 1.5707963267948966;  // nearest double to π/2
constexpr double kPi = 3.141592653589793;       // nearest double to π

//! True if some c + 2πk (k ∈ ℤ) may lie in [lo, hi] (finite bounds); false only when certainly
//! none does (see tolerances::trig_extremum_margin).
bool may_contain_lattice_point(double lo, double hi, double c) {
  const double tl = (lo - c) / kTwoPi;
  const double th = (hi - c) / kTwoPi;
  const double big = std::max(std::fabs(tl), std::fabs(th));
  if (!(big < 1e15)) return true;  // beyond this, a double cannot resolve the period
  const double margin = tolerances::trig_extremum_margin * (1.0 + big);
  return std::ceil(tl - margin) <= std::floor(th + margin);
}

//! sin or cos over [lo, hi] given where its maxima and minima lie (mod 2π).
Interval periodic_enclosure(const Interval& a, double (*f)(double), double maximum_at, double minimum_at) {
  const double lo = a.inf(), hi = a.sup();
  if (!(std::isfinite(lo) && std::isfinite(hi)) || !(hi - lo < kTwoPi)) return Interval(-1.0, 1.0);
  const double f_lo = f(lo), f_hi = f(hi);
  double l = widen_down(std::min(f_lo, f_hi));
  double h = widen_up(std::max(f_lo, f_hi));
  if (may_contain_lattice_point(lo, hi, maximum_at)) h = 1.0;
  if (may_contain_lattice_point(lo, hi, minimum_at)) l = -1.0;
  return Interval(std::max(l, -1.0), std::min(h, 1.0));
}

double sin_fn(double x) { return std::sin(x); }
double cos_fn(double x) { return std::cos(x); }

mpfr_ptr left(MpfiInterval& a) { return &a.backend().data()[0].left; }
mpfr_ptr right(MpfiInterval& a) { return &a.backend().data()[0].right; }
mpfr_srcptr left(const MpfiInterval& a) { return &a.backend().data()[0].left; }
mpfr_srcptr right(const MpfiInterval& a) { return &a.backend().data()[0].right; }

}  // namespace

bool certainly_nonzero(const MpfiInterval& a) {
  if (mpfi_nan_p(a.backend().data())) return false;
  return mpfr_sgn(left(a)) > 0 || mpfr_sgn(right(a)) < 0;
}

// ---------------------------------------------------------------------------------------------
// double, Complex
// ---------------------------------------------------------------------------------------------
void ScalarTraits<double>::set_rational(double& out, const Rational& q) {
  out = rational_to_double(q, MPFR_RNDN);
}
void ScalarTraits<double>::set_pi(double& out) { out = pi_to_double(MPFR_RNDN); }

void ScalarTraits<Complex>::set_rational(Complex& out, const Rational& q) {
  out = Complex(rational_to_double(q, MPFR_RNDN), 0.0);
}
void ScalarTraits<Complex>::set_pi(Complex& out) { out = Complex(pi_to_double(MPFR_RNDN), 0.0); }

// ---------------------------------------------------------------------------------------------
// Interval
// ---------------------------------------------------------------------------------------------
void ScalarTraits<Interval>::set_rational(Interval& out, const Rational& q) {
  out = Interval(rational_to_double(q, MPFR_RNDD), rational_to_double(q, MPFR_RNDU));
}
void ScalarTraits<Interval>::set_pi(Interval& out) {
  out = Interval(pi_to_double(MPFR_RNDD), pi_to_double(MPFR_RNDU));
}

void ScalarTraits<Interval>::pow(Interval& out, const Interval& a, int n) {
  if (n == 0) {
    out = Interval(1.0);
    return;
  }
  const unsigned long m = n < 0 ? -static_cast<long>(n) : n;
  const double lo = a.inf(), hi = a.sup();
  Interval r;
  if (m == 2) {
    r = CGAL::square(a);  // the exact range of x², rounded outward
  } else if (m % 2 == 1) {
    // x^m is increasing, and (−v)^m = −(v^m).
    r = Interval(lo >= 0 ? nonnegative_power<false>(lo, m) : -nonnegative_power<true>(-lo, m),
                 hi >= 0 ? nonnegative_power<true>(hi, m) : -nonnegative_power<false>(-hi, m));
  } else {
    double mig, mag;
    if (lo >= 0) {
      mig = lo;
      mag = hi;
    } else if (hi <= 0) {
      mig = -hi;
      mag = -lo;
    } else {
      mig = 0.0;
      mag = std::max(-lo, hi);
    }
    r = Interval(nonnegative_power<false>(mig, m), nonnegative_power<true>(mag, m));
  }
  out = n < 0 ? 1.0 / r : r;
}

void ScalarTraits<Interval>::exp(Interval& out, const Interval& a) {
  const double l = widen_down(std::exp(a.inf()));
  const double h = widen_up(std::exp(a.sup()));
  out = Interval(std::max(l, 0.0), h);
}

void ScalarTraits<Interval>::log(Interval& out, const Interval& a) {
  if (!(a.inf() > 0)) {
    out = whole_line();
    return;
  }
  out = Interval(widen_down(std::log(a.inf())), widen_up(std::log(a.sup())));
}

void ScalarTraits<Interval>::sqrt(Interval& out, const Interval& a) {
  if (!(a.inf() >= 0)) {
    out = whole_line();
    return;
  }
  out = CGAL::sqrt(a);
}

void ScalarTraits<Interval>::sin(Interval& out, const Interval& a) {
  out = periodic_enclosure(a, &sin_fn, kHalfPi, -kHalfPi);
}
void ScalarTraits<Interval>::cos(Interval& out, const Interval& a) {
  out = periodic_enclosure(a, &cos_fn, 0.0, kPi);
}

// ---------------------------------------------------------------------------------------------
// MpfrReal
// ---------------------------------------------------------------------------------------------
long ScalarTraits<MpfrReal>::precision() {
  return static_cast<long>(boost::multiprecision::detail::digits10_2_2(MpfrReal::default_precision()));
}
void ScalarTraits<MpfrReal>::set_precision(MpfrReal& out, long bits) {
  if (mpfr_get_prec(out.backend().data()) != bits) mpfr_set_prec(out.backend().data(), bits);
}
void ScalarTraits<MpfrReal>::set_rational(MpfrReal& out, const Rational& q) {
  mpfr_set_q(out.backend().data(), q.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::set_pi(MpfrReal& out) { mpfr_const_pi(out.backend().data(), MPFR_RNDN); }
void ScalarTraits<MpfrReal>::assign(MpfrReal& out, const MpfrReal& a) {
  mpfr_set(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::add(MpfrReal& out, const MpfrReal& a, const MpfrReal& b) {
  mpfr_add(out.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::sub(MpfrReal& out, const MpfrReal& a, const MpfrReal& b) {
  mpfr_sub(out.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::mul(MpfrReal& out, const MpfrReal& a, const MpfrReal& b) {
  mpfr_mul(out.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::div(MpfrReal& out, const MpfrReal& a, const MpfrReal& b) {
  mpfr_div(out.backend().data(), a.backend().data(), b.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::neg(MpfrReal& out, const MpfrReal& a) {
  mpfr_neg(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::inv(MpfrReal& out, const MpfrReal& a) {
  mpfr_ui_div(out.backend().data(), 1UL, a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::square(MpfrReal& out, const MpfrReal& a) {
  mpfr_sqr(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::pow(MpfrReal& out, const MpfrReal& a, int n) {
  mpfr_pow_si(out.backend().data(), a.backend().data(), n, MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::exp(MpfrReal& out, const MpfrReal& a) {
  mpfr_exp(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::log(MpfrReal& out, const MpfrReal& a) {
  mpfr_log(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::sqrt(MpfrReal& out, const MpfrReal& a) {
  mpfr_sqrt(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::sin(MpfrReal& out, const MpfrReal& a) {
  mpfr_sin(out.backend().data(), a.backend().data(), MPFR_RNDN);
}
void ScalarTraits<MpfrReal>::cos(MpfrReal& out, const MpfrReal& a) {
  mpfr_cos(out.backend().data(), a.backend().data(), MPFR_RNDN);
}

// ---------------------------------------------------------------------------------------------
// MpfiInterval
// ---------------------------------------------------------------------------------------------
long ScalarTraits<MpfiInterval>::precision() {
  return static_cast<long>(
      boost::multiprecision::detail::digits10_2_2(MpfiInterval::default_precision()));
}
void ScalarTraits<MpfiInterval>::set_precision(MpfiInterval& out, long bits) {
  if (mpfi_get_prec(out.backend().data()) != bits) mpfi_set_prec(out.backend().data(), bits);
}
void ScalarTraits<MpfiInterval>::set_rational(MpfiInterval& out, const Rational& q) {
  mpfi_set_q(out.backend().data(), q.backend().data());
}
void ScalarTraits<MpfiInterval>::set_pi(MpfiInterval& out) { mpfi_const_pi(out.backend().data()); }
void ScalarTraits<MpfiInterval>::assign(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_set(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::add(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b) {
  mpfi_add(out.backend().data(), a.backend().data(), b.backend().data());
}
void ScalarTraits<MpfiInterval>::sub(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b) {
  mpfi_sub(out.backend().data(), a.backend().data(), b.backend().data());
}
void ScalarTraits<MpfiInterval>::mul(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b) {
  mpfi_mul(out.backend().data(), a.backend().data(), b.backend().data());
}
void ScalarTraits<MpfiInterval>::div(MpfiInterval& out, const MpfiInterval& a, const MpfiInterval& b) {
  mpfi_div(out.backend().data(), a.backend().data(), b.backend().data());
}
void ScalarTraits<MpfiInterval>::neg(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_neg(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::inv(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_inv(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::square(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_sqr(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::pow(MpfiInterval& out, const MpfiInterval& a, int n) {
  if (n == 0) {
    mpfi_set_ui(out.backend().data(), 1UL);
    return;
  }
  const unsigned long m = n < 0 ? -static_cast<long>(n) : n;
  // Per-thread endpoint temporaries at the precision of out (no allocation per call).
  struct Endpoints {
    mpfr_t lo, hi;
    Endpoints() {
      mpfr_init2(lo, MPFR_PREC_MIN);
      mpfr_init2(hi, MPFR_PREC_MIN);
    }
    ~Endpoints() {
      mpfr_clear(lo);
      mpfr_clear(hi);
    }
  };
  thread_local Endpoints t;
  mpfr_ptr lo = t.lo, hi = t.hi;
  const mpfr_prec_t prec = mpfi_get_prec(out.backend().data());
  if (mpfr_get_prec(lo) != prec) {
    mpfr_set_prec(lo, prec);
    mpfr_set_prec(hi, prec);
  }
  if (m % 2 == 1) {  // x ↦ xᵐ is increasing
    mpfr_pow_ui(lo, left(a), m, MPFR_RNDD);
    mpfr_pow_ui(hi, right(a), m, MPFR_RNDU);
  } else {  // range of |x| is [mig, mag], rounded outward by MPFI
    mpfi_mig(lo, a.backend().data());
    mpfi_mag(hi, a.backend().data());
    mpfr_pow_ui(lo, lo, m, MPFR_RNDD);
    mpfr_pow_ui(hi, hi, m, MPFR_RNDU);
  }
  mpfi_interv_fr(out.backend().data(), lo, hi);
  if (n < 0) mpfi_inv(out.backend().data(), out.backend().data());
}
void ScalarTraits<MpfiInterval>::exp(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_exp(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::log(MpfiInterval& out, const MpfiInterval& a) {
  if (mpfi_nan_p(a.backend().data()) || mpfr_sgn(left(a)) <= 0) {
    set_whole_line(out);
    return;
  }
  mpfi_log(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::sqrt(MpfiInterval& out, const MpfiInterval& a) {
  if (mpfi_nan_p(a.backend().data()) || mpfr_sgn(left(a)) < 0) {
    set_whole_line(out);
    return;
  }
  mpfi_sqrt(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::sin(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_sin(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::cos(MpfiInterval& out, const MpfiInterval& a) {
  mpfi_cos(out.backend().data(), a.backend().data());
}
void ScalarTraits<MpfiInterval>::set_whole_line(MpfiInterval& out) {
  mpfr_set_inf(left(out), -1);
  mpfr_set_inf(right(out), 1);
}

}  // namespace delmesh
