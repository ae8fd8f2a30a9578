#include "meshing/core/theorem_bounds.h"

#include <cmath>
#include <functional>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;

namespace {

const double pi = std::acos(-1.0);

//! Largest λ in (lo, hi) at which predicate holds, by bisection (predicate true at lo, false at hi).
double threshold(const std::function<bool(double)>& predicate, double lo, double hi) {
  BOOST_REQUIRE(predicate(lo));
  BOOST_REQUIRE(!predicate(hi));
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (predicate(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(theorem_bounds_suite)

BOOST_AUTO_TEST_CASE(alpha_closed_form) {
  BOOST_TEST(alpha(0.06) == 0.06 / 0.82, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(alpha(0.1) == 0.1 / 0.7, boost::test_tools::tolerance(1e-15));
  // α(λ)/λ → 1 as λ → 0.
  BOOST_TEST(alpha(1e-8) / 1e-8 == 1.0, boost::test_tools::tolerance(1e-7));
}

BOOST_AUTO_TEST_CASE(beta_closed_form_and_asymptotics) {
  // λ = 1/20, every term written out.
  const double l = 0.05;
  const double expected = (2 * l) / (1 - 6 * l) + std::asin(l) +
                          std::asin(2.0 * std::sin(2.0 * std::asin(l)) / std::sqrt(3.0));
  BOOST_TEST(beta(l) == expected, boost::test_tools::tolerance(1e-15));
  // β(λ) = O(λ): β(λ)/λ → 2 + 1 + 4/√3 as λ → 0 (sin(2 arcsin λ) ≈ 2λ).
  BOOST_TEST(beta(1e-8) / 1e-8 == 3.0 + 4.0 / std::sqrt(3.0), boost::test_tools::tolerance(1e-6));
  // Monotone increasing on (0, 1/6).
  double previous = 0;
  for (double lam = 0.005; lam < 1.0 / 6.0; lam += 0.005) {
    BOOST_TEST(beta(lam) > previous);
    previous = beta(lam);
  }
  // At λ₀ = 0.06 the roughness bound 2β is about 44.27 degrees.
  BOOST_TEST(2 * beta(0.06) * 180 / pi == 44.2661848, boost::test_tools::tolerance(1e-8));
}

BOOST_AUTO_TEST_CASE(bounds_of_theorem_6_1) {
  for (double lam : {0.01, 0.03, 0.06, 0.1}) {
    const TheoremBounds b = theorem_bounds(lam);
    BOOST_TEST(b.max_radius_edge_ratio == 1 + lam);
    BOOST_TEST(b.max_roughness_rad == 2 * beta(lam));
    // A triangle with smallest angle θ has radius-edge ratio 1/(2 sin θ): the min angle bound is
    // exactly the angle at which that ratio equals 1+λ.
    const double theta = b.min_angle_deg * pi / 180;
    BOOST_TEST(1.0 / (2.0 * std::sin(theta)) == 1 + lam, boost::test_tools::tolerance(1e-14));
    BOOST_TEST(b.min_angle_deg < 30.0);
  }
  BOOST_TEST(theorem_bounds(0.06).min_angle_deg == 28.1445813, boost::test_tools::tolerance(1e-8));
}

BOOST_AUTO_TEST_CASE(section_4_inequalities_hold_up_to_lambda0) {
  for (double lam = 0.001; lam <= 0.06 + 1e-12; lam += 0.001) {
    BOOST_TEST(theorem_conditions_hold(lam), "lambda " << lam);
  }
}

BOOST_AUTO_TEST_CASE(section_4_inequalities_fail_above_lambda0) {
  // Inequality (1) is the binding one: it fails first, at λ* ≈ 0.0695616.
  const double first = threshold(theorem_conditions_hold, 0.06, 0.08);
  BOOST_TEST(first == 0.0695616, boost::test_tools::tolerance(1e-6));
  const double d1 = threshold([](double l) { return theorem_conditions(l).distance_cosine; }, 0.06, 0.08);
  BOOST_TEST(d1 == first);
  const TheoremConditions just_above = theorem_conditions(first + 1e-6);
  BOOST_TEST(!just_above.distance_cosine);
  BOOST_TEST(just_above.angle_below_60deg);
  BOOST_TEST(just_above.arccos_bound);
  BOOST_TEST(!theorem_conditions_hold(0.07));
  // (2) α+β < π/3 fails at ≈ 0.10387, (3) arccos λ > α+β at ≈ 0.12021.
  const double d2 = threshold([](double l) { return theorem_conditions(l).angle_below_60deg; }, 0.06, 0.16);
  const double d3 = threshold([](double l) { return theorem_conditions(l).arccos_bound; }, 0.06, 0.16);
  BOOST_TEST(d2 == 0.1038696, boost::test_tools::tolerance(1e-6));
  BOOST_TEST(d3 == 0.1202113, boost::test_tools::tolerance(1e-6));
}

BOOST_AUTO_TEST_CASE(preconditions) {
  BOOST_CHECK_THROW(alpha(0.0), PreconditionViolation);
  BOOST_CHECK_THROW(alpha(1.0 / 3.0), PreconditionViolation);
  BOOST_CHECK_THROW(alpha(-0.1), PreconditionViolation);
  BOOST_CHECK_THROW(alpha(std::nan("")), PreconditionViolation);
  BOOST_CHECK_NO_THROW(alpha(0.2));
  BOOST_CHECK_THROW(beta(0.2), PreconditionViolation);
  BOOST_CHECK_THROW(beta(1.0 / 6.0), PreconditionViolation);
  BOOST_CHECK_THROW(theorem_bounds(0.0), PreconditionViolation);
  BOOST_CHECK_THROW(theorem_bounds(0.17), PreconditionViolation);
  BOOST_CHECK_THROW(theorem_conditions_hold(-1.0), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
