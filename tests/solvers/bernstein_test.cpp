#include "solvers/detail/bernstein.h"

#include <vector>

#include <boost/multiprecision/gmp.hpp>
#include <boost/test/unit_test.hpp>

using namespace delmesh;

namespace {

using Rational = boost::multiprecision::mpq_rational;
using Integer = boost::multiprecision::mpz_int;

bool encloses(const Interval& a, const Rational& q) { return Rational(a.inf()) <= q && q <= Rational(a.sup()); }

Integer binomial(int n, int k) {
  Integer c = 1;
  for (int j = 1; j <= k; ++j) c = c * (n - k + j) / j;
  return c;
}

//! Bernstein coefficients on [0, 1] (t0 = 0, h = 1) of the monomial coefficients c_0..c_d.
std::vector<Interval> bernstein_coefficients(const std::vector<double>& c) {
  const int d = static_cast<int>(c.size()) - 1;
  RoundingGuard guard;
  std::vector<Interval> ci(c.begin(), c.end()), b(c.size()), scratch(c.size());
  detail::bernstein_from_monomial(d, ci.data(), 0.0, Interval(1.0), b.data(), scratch.data());
  return b;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(bernstein)

BOOST_AUTO_TEST_CASE(monomials_enclose_exact_coefficients_up_to_max_degree) {
  // s^k = Σ_{i ≥ k} C(i, k) / C(d, k) B_{i,d}(s): every enclosure holds the exact rational, for
  // every degree the conversion accepts (C(d, k) exceeds 2^53 from d = 57 on).
  for (int d = 0; d <= detail::max_bernstein_degree; ++d) {
    for (int k = 0; k <= d; ++k) {
      std::vector<double> c(d + 1, 0.0);
      c[k] = 1;
      const std::vector<Interval> b = bernstein_coefficients(c);
      const Integer cdk = binomial(d, k);
      int wrong = 0;
      for (int i = 0; i <= d; ++i) {
        const Rational exact = i < k ? Rational(0) : Rational(binomial(i, k), cdk);
        wrong += !encloses(b[i], exact);
      }
      BOOST_TEST(wrong == 0, "d = " << d << ", k = " << k << ": " << wrong << " coefficients not enclosed");
    }
  }
}

BOOST_AUTO_TEST_CASE(degree_56_zero_coefficient_is_not_given_a_sign) {
  // q(s) = s^24 − 1 as a degree-56 polynomial: b_56 = q(1) = 0 exactly, and b_i = C(i, 24) / C(56, 24) − 1.
  // C(56, 24) = 4355031703297275 < 2^53; computing it as C(56, 23) · 33 / 24 in doubles rounds the
  // product, and an overestimated binomial makes every enclosure of b_i (i ≥ 24) miss, b_56 by
  // being certainly negative: Descartes' rule would exclude the zero at s = 1.
  std::vector<double> c(57, 0.0);
  c[0] = -1;
  c[24] = 1;
  const std::vector<Interval> b = bernstein_coefficients(c);
  BOOST_TEST(encloses(b[56], Rational(0)));
  for (int i = 0; i <= 56; ++i) {
    const Rational exact = i < 24 ? Rational(-1) : Rational(binomial(i, 24), binomial(56, 24)) - 1;
    BOOST_TEST(encloses(b[i], exact), "b_" << i << " = [" << b[i].inf() << ", " << b[i].sup() << "]");
  }
}

BOOST_AUTO_TEST_SUITE_END()
