#include "symbolic/scalar_traits.h"

#include <cmath>
#include <limits>
#include <random>

#include <boost/test/unit_test.hpp>
#include <mpfi.h>
#include <mpfr.h>

using namespace delmesh;

namespace {

using IT = ScalarTraits<Interval>;
using FT = ScalarTraits<MpfiInterval>;

//! A reference value of f at the double x, with 160 bits (far more than any enclosure's width).
struct Reference {
  mpfr_t value;
  Reference(int (*f)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t), double x) {
    mpfr_init2(value, 160);
    mpfr_set_d(value, x, MPFR_RNDN);
    f(value, value, MPFR_RNDN);
  }
  ~Reference() { mpfr_clear(value); }
  bool inside(const Interval& i) const { return mpfr_cmp_d(value, i.inf()) >= 0 && mpfr_cmp_d(value, i.sup()) <= 0; }
};

using UnaryInterval = void (*)(Interval&, const Interval&);

//! Checks that op(I) contains the 160-bit value of f at the endpoints and at random points of I,
//! for random intervals I ⊂ [lo, hi] of random widths (down to a point).
void check_enclosure(UnaryInterval op, int (*f)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t), double lo, double hi,
                     unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> where(lo, hi), fraction(0, 1);
  for (int trial = 0; trial < 300; ++trial) {
    const double a = where(rng);
    const double width = (trial % 3 == 0) ? 0.0 : std::pow(10.0, -6.0 * fraction(rng)) * (hi - lo) * 0.5;
    const double b = std::min(hi, a + width);
    Interval result;
    {
      RoundingGuard guard;
      op(result, Interval(a, b));
    }
    BOOST_REQUIRE(result.inf() <= result.sup());
    for (int k = 0; k < 8; ++k) {
      const double x = k == 0 ? a : k == 1 ? b : a + (b - a) * fraction(rng);
      const Reference ref(f, x);
      BOOST_CHECK_MESSAGE(ref.inside(result), "enclosure [" << result.inf() << ", " << result.sup()
                                                            << "] misses f(" << x << ")");
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(scalar_traits)

BOOST_AUTO_TEST_CASE(interval_square_and_powers_are_exact_ranges) {
  RoundingGuard guard;
  Interval r;
  IT::square(r, Interval(-1, 2));
  BOOST_CHECK_EQUAL(r.inf(), 0.0);
  BOOST_CHECK_EQUAL(r.sup(), 4.0);
  IT::pow(r, Interval(-1, 2), 2);
  BOOST_CHECK_EQUAL(r.inf(), 0.0);
  BOOST_CHECK_EQUAL(r.sup(), 4.0);
  IT::pow(r, Interval(-1, 2), 3);  // x ↦ x³ is increasing: [-1, 8], not [-4, 8]
  BOOST_CHECK_EQUAL(r.inf(), -1.0);
  BOOST_CHECK_EQUAL(r.sup(), 8.0);
  IT::pow(r, Interval(-3, -2), 4);
  BOOST_CHECK_EQUAL(r.inf(), 16.0);
  BOOST_CHECK_EQUAL(r.sup(), 81.0);
  IT::pow(r, Interval(-3, 2), 4);
  BOOST_CHECK_EQUAL(r.inf(), 0.0);
  BOOST_CHECK_EQUAL(r.sup(), 81.0);
  IT::pow(r, Interval(2, 4), -2);
  BOOST_CHECK_EQUAL(r.inf(), 1.0 / 16);
  BOOST_CHECK_EQUAL(r.sup(), 0.25);
  IT::pow(r, Interval(-1, 1), -1);  // 1/x over an interval through 0: no information
  BOOST_CHECK(!certainly_nonzero(r));
  BOOST_CHECK(r.inf() == -std::numeric_limits<double>::infinity());
  // (the double nearest 1.1)^5 is not a double: enclosed by a few-ulp interval around it.
  IT::pow(r, Interval(1.1), 5);
  BOOST_CHECK(r.inf() < r.sup());
  BOOST_CHECK(r.sup() - r.inf() < 8 * std::numeric_limits<double>::epsilon());
  mpfr_t exact;
  mpfr_init2(exact, 300);
  mpfr_set_d(exact, 1.1, MPFR_RNDN);
  mpfr_pow_ui(exact, exact, 5, MPFR_RNDN);  // exact: 5 · 53 bits < 300
  BOOST_CHECK(mpfr_cmp_d(exact, r.inf()) > 0 && mpfr_cmp_d(exact, r.sup()) < 0);
  IT::pow(r, Interval(-1.1), 5);
  BOOST_CHECK(mpfr_cmp_d(exact, -r.sup()) > 0 && mpfr_cmp_d(exact, -r.inf()) < 0);
  mpfr_clear(exact);
}

BOOST_AUTO_TEST_CASE(interval_powers_of_points_enclose_the_exact_power_tightly) {
  // For every exponent (the written-out ones up to 4 and the loop beyond) and points of both
  // signs whose powers are not doubles, the exact power (MPFR, 400 bits: exact up to n = 7)
  // lies in the interval, which is a few ulps wide.
  RoundingGuard guard;
  mpfr_t exact;
  mpfr_init2(exact, 400);
  for (double v : {1.1, -1.1, 0.7, -3.3, 1e-3}) {
    for (int n = 1; n <= 7; ++n) {
      Interval r;
      IT::pow(r, Interval(v), n);
      mpfr_set_d(exact, v, MPFR_RNDN);
      mpfr_pow_ui(exact, exact, static_cast<unsigned long>(n), MPFR_RNDN);
      BOOST_TEST((mpfr_cmp_d(exact, r.inf()) >= 0 && mpfr_cmp_d(exact, r.sup()) <= 0), "v " << v << ", n " << n);
      const double magnitude = std::max(std::abs(r.inf()), std::abs(r.sup()));
      BOOST_TEST(r.sup() - r.inf() <= 2 * n * std::numeric_limits<double>::epsilon() * magnitude,
                 "v " << v << ", n " << n);
    }
  }
  mpfr_clear(exact);
}

BOOST_AUTO_TEST_CASE(interval_rational_constants_are_tight_enclosures) {
  Interval third, pi;
  IT::set_rational(third, Rational(1) / 3);
  IT::set_pi(pi);
  BOOST_CHECK_EQUAL(std::nextafter(third.inf(), 1.0), third.sup());
  BOOST_CHECK_EQUAL(std::nextafter(pi.inf(), 4.0), pi.sup());
  // The mathematical 1/3 and π lie strictly between the two bounds.
  mpfr_t p;
  mpfr_init2(p, 200);
  mpfr_set_ui(p, 1, MPFR_RNDN);
  mpfr_div_ui(p, p, 3, MPFR_RNDN);
  BOOST_CHECK(mpfr_cmp_d(p, third.inf()) > 0 && mpfr_cmp_d(p, third.sup()) < 0);
  mpfr_const_pi(p, MPFR_RNDN);
  BOOST_CHECK(mpfr_cmp_d(p, pi.inf()) > 0 && mpfr_cmp_d(p, pi.sup()) < 0);
  mpfr_clear(p);
  Interval half;
  IT::set_rational(half, Rational(-1) / 2);  // exactly representable: a point
  BOOST_CHECK_EQUAL(half.inf(), -0.5);
  BOOST_CHECK_EQUAL(half.sup(), -0.5);
}

BOOST_AUTO_TEST_CASE(interval_transcendentals_enclose_high_precision_values) {
  check_enclosure(&IT::exp, &mpfr_exp, -30, 30, 1);
  check_enclosure(&IT::log, &mpfr_log, 1e-6, 1e6, 2);
  check_enclosure(&IT::sqrt, &mpfr_sqrt, 0, 100, 3);
  check_enclosure(&IT::sin, &mpfr_sin, -20, 20, 4);
  check_enclosure(&IT::cos, &mpfr_cos, -20, 20, 5);
  check_enclosure(&IT::sin, &mpfr_sin, 1e6, 1e6 + 50, 6);  // large arguments
  check_enclosure(&IT::cos, &mpfr_cos, -1e9 - 50, -1e9, 7);
}

BOOST_AUTO_TEST_CASE(interval_sin_cos_extrema_inside_the_interval) {
  RoundingGuard guard;
  Interval r;
  IT::sin(r, Interval(1.0, 2.0));  // contains π/2
  BOOST_CHECK_EQUAL(r.sup(), 1.0);
  BOOST_CHECK(r.inf() < std::sin(1.0) && r.inf() > std::sin(1.0) - 1e-14);
  IT::sin(r, Interval(4.0, 5.0));  // contains 3π/2
  BOOST_CHECK_EQUAL(r.inf(), -1.0);
  BOOST_CHECK(r.sup() > std::sin(4.0) && r.sup() < std::sin(4.0) + 1e-14);
  IT::sin(r, Interval(1.4, 1.5));  // increasing, below the maximum
  BOOST_CHECK(r.sup() < 1.0);
  BOOST_CHECK(r.sup() >= std::sin(1.5));
  IT::cos(r, Interval(-0.1, 0.2));  // contains 0
  BOOST_CHECK_EQUAL(r.sup(), 1.0);
  IT::cos(r, Interval(3.0, 3.3));  // contains π
  BOOST_CHECK_EQUAL(r.inf(), -1.0);
  BOOST_CHECK(r.sup() < 0.0);
  IT::cos(r, Interval(0.5, 1.0));  // decreasing
  BOOST_CHECK(r.inf() > 0.5 && r.sup() < 0.9);
  IT::cos(r, Interval(2 * 3.141592653589793 + 0.5, 2 * 3.141592653589793 + 1.0));  // one period on
  BOOST_CHECK(r.inf() > 0.5 && r.sup() < 0.9);
  IT::sin(r, Interval(0.0, 7.0));  // wider than 2π
  BOOST_CHECK_EQUAL(r.inf(), -1.0);
  BOOST_CHECK_EQUAL(r.sup(), 1.0);
  IT::sin(r, Interval(0.0, std::numeric_limits<double>::infinity()));
  BOOST_CHECK_EQUAL(r.inf(), -1.0);
  BOOST_CHECK_EQUAL(r.sup(), 1.0);
}

BOOST_AUTO_TEST_CASE(interval_domain_errors_give_the_whole_line) {
  RoundingGuard guard;
  Interval r;
  IT::log(r, Interval(-1.0, 2.0));
  BOOST_CHECK(r.inf() == -std::numeric_limits<double>::infinity());
  BOOST_CHECK(r.sup() == std::numeric_limits<double>::infinity());
  IT::log(r, Interval(0.0, 2.0));
  BOOST_CHECK(!certainly_nonzero(r));
  IT::sqrt(r, Interval(-4.0, -1.0));
  BOOST_CHECK(r.inf() == -std::numeric_limits<double>::infinity());
  BOOST_CHECK(!certainly_nonzero(r));
  IT::sqrt(r, Interval(4.0, 9.0));
  BOOST_CHECK_EQUAL(r.inf(), 2.0);
  BOOST_CHECK_EQUAL(r.sup(), 3.0);
  IT::exp(r, Interval(-1000.0, 0.0));
  BOOST_CHECK(r.inf() >= 0.0);
  BOOST_CHECK(r.sup() >= 1.0 && r.sup() < 1.0 + 1e-14);
  // A NaN bound never counts as excluding zero.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  BOOST_CHECK(!certainly_nonzero(Interval(nan, nan)));
  BOOST_CHECK(certainly_nonzero(Interval(1e-300, 1.0)));
}

BOOST_AUTO_TEST_CASE(mpfi_operations_enclose_and_follow_the_same_conventions) {
  const unsigned saved = MpfiInterval::default_precision();
  MpfiInterval::default_precision(60);
  MpfiInterval x(-1, 2), r, q;
  FT::pow(r, x, 2);
  BOOST_CHECK_EQUAL(lower(r), 0);
  BOOST_CHECK_EQUAL(upper(r), 4);
  FT::pow(r, x, 3);
  BOOST_CHECK_EQUAL(lower(r), -1);
  BOOST_CHECK_EQUAL(upper(r), 8);
  FT::log(r, x);
  BOOST_CHECK(!certainly_nonzero(r));
  BOOST_CHECK(boost::multiprecision::isinf(lower(r)) && boost::multiprecision::isinf(upper(r)));
  FT::set_rational(q, Rational(1) / 3);
  BOOST_CHECK(lower(q) < upper(q));
  BOOST_CHECK(upper(q) - lower(q) < 1e-55);
  BOOST_CHECK(certainly_nonzero(q));
  // exp([1/3]) encloses e^{1/3} (computed with MPFR at 400 bits) and is about 2^-200 wide.
  FT::exp(r, q);
  mpfr_t e;
  mpfr_init2(e, 400);
  mpfr_set_ui(e, 1, MPFR_RNDN);
  mpfr_div_ui(e, e, 3, MPFR_RNDN);
  mpfr_exp(e, e, MPFR_RNDN);
  BOOST_CHECK(mpfi_is_inside_fr(e, r.backend().data()));
  BOOST_CHECK(upper(r) - lower(r) < 1e-55);
  mpfr_clear(e);
  MpfiInterval::default_precision(saved);
}

BOOST_AUTO_TEST_CASE(mpfr_operations_round_at_the_output_precision) {
  MpfrReal r;
  ScalarTraits<MpfrReal>::set_precision(r, 200);
  ScalarTraits<MpfrReal>::set_rational(r, Rational(1) / 3);
  MpfrReal three(3);
  ScalarTraits<MpfrReal>::mul(r, r, three);
  BOOST_CHECK(abs(r - 1) < MpfrReal("1e-59"));
  BOOST_CHECK_EQUAL(mpfr_get_prec(r.backend().data()), 200);
}

BOOST_AUTO_TEST_SUITE_END()
