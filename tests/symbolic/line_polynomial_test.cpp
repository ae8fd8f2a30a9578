#include "symbolic/line_polynomial.h"

#include <cmath>
#include <random>
#include <sstream>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <gmp.h>
#include <mpfr.h>

#include "common/errors.h"
#include "symbolic/catalog.h"
#include "tests/symbolic/exact_rational.h"

using namespace delmesh;
using delmesh::testing::exact;

namespace {

GiNaC::numeric to_numeric(const GiNaC::ex& e) {
  BOOST_REQUIRE(GiNaC::is_a<GiNaC::numeric>(e));
  return GiNaC::ex_to<GiNaC::numeric>(e);
}

//! The coefficients of E(p + t v) for exact p, v, computed independently of LinePolynomial
//! (numbers substituted first, then expanded in t).
std::vector<GiNaC::numeric> reference_coefficients(const Surface& s, const double* pv, int degree) {
  const GiNaC::symbol t("t");
  const GiNaC::ex along = s.E()
                              .subs(GiNaC::lst{coordinate_x() == exact(pv[0]) + t * exact(pv[3]),
                                               coordinate_y() == exact(pv[1]) + t * exact(pv[4]),
                                               coordinate_z() == exact(pv[2]) + t * exact(pv[5])})
                              .expand();
  BOOST_REQUIRE(along.degree(t) <= degree);
  std::vector<GiNaC::numeric> c;
  for (int k = 0; k <= degree; ++k) c.push_back(to_numeric(along.coeff(t, k)));
  return c;
}

//! lower(I) ≤ q ≤ upper(I), compared exactly (MPFR against GMP rationals).
bool encloses(const MpfiInterval& I, const GiNaC::numeric& q) {
  std::ostringstream text;
  text << q.numer() << "/" << q.denom();
  mpq_t r;
  mpq_init(r);
  mpq_set_str(r, text.str().c_str(), 10);
  mpq_canonicalize(r);
  const MpfrReal lo = lower(I), hi = upper(I);
  const bool inside = mpfr_cmp_q(lo.backend().data(), r) <= 0 && mpfr_cmp_q(hi.backend().data(), r) >= 0;
  mpq_clear(r);
  return inside;
}

//! Random line parameters: dyadic rationals k/64 in [-2, 2] (exact doubles).
std::vector<double> random_line(std::mt19937& rng) {
  std::uniform_int_distribution<int> k(-128, 128);
  std::vector<double> pv(6);
  for (double& c : pv) c = k(rng) / 64.0;
  if (pv[3] == 0 && pv[4] == 0 && pv[5] == 0) pv[3] = 1;
  return pv;
}

const char* const kPolynomialSurfaces[] = {"sphere", "ellipsoid", "torus", "genus2", "chair", "tanglecube",
                                           "thin_handle", "near_sheets"};

}  // namespace

BOOST_AUTO_TEST_SUITE(line_polynomial)

BOOST_AUTO_TEST_CASE(degree_is_the_total_degree) {
  for (const char* name : kPolynomialSurfaces) {
    const Surface s = catalog_entry(name).surface();
    const LinePolynomial line(s);
    BOOST_TEST_CONTEXT(name) {
      BOOST_TEST(line.degree() == s.degree());
      BOOST_TEST(line.coefficient_expressions().size() == static_cast<std::size_t>(s.degree() + 1));
      BOOST_TEST(line.parameters().size() == 6u);
    }
  }
}

BOOST_AUTO_TEST_CASE(non_polynomial_surface_is_a_precondition_violation) {
  BOOST_CHECK_THROW(LinePolynomial(catalog_entry("metaball").surface()), PreconditionViolation);
  BOOST_CHECK_THROW(LinePolynomial(Surface::parse("sqrt(2)*x+y^2+z^2-1")), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(coefficient_expressions_reproduce_E_on_the_line_exactly) {
  std::mt19937 rng(5);
  for (const char* name : {"torus", "genus2", "chair"}) {
    const Surface s = catalog_entry(name).surface();
    const LinePolynomial line(s);
    for (int trial = 0; trial < 3; ++trial) {
      const std::vector<double> pv = random_line(rng);
      const std::vector<GiNaC::numeric> reference = reference_coefficients(s, pv.data(), line.degree());
      GiNaC::exmap m;
      for (std::size_t i = 0; i < 6; ++i) m[line.parameters()[i]] = exact(pv[i]);
      for (int k = 0; k <= line.degree(); ++k)
        BOOST_TEST_CONTEXT(name << " c_" << k)
        BOOST_TEST((line.coefficient_expressions()[k].subs(m) - reference[k]).is_zero());
    }
  }
}

BOOST_AUTO_TEST_CASE(compiled_coefficients_are_accurate_and_enclosing) {
  std::mt19937 rng(17);
  for (const char* name : kPolynomialSurfaces) {
    const Surface s = catalog_entry(name).surface();
    const LinePolynomial line(s);
    const std::size_t n = static_cast<std::size_t>(line.degree()) + 1;
    for (int trial = 0; trial < 10; ++trial) {
      const std::vector<double> pv = random_line(rng);
      const std::vector<GiNaC::numeric> reference = reference_coefficients(s, pv.data(), line.degree());
      double scale = 1;
      for (const GiNaC::numeric& c : reference) scale = std::max(scale, std::fabs(c.to_double()));

      std::vector<double> value(n);
      line.coefficients(pv.data(), value.data());
      std::vector<Interval> enclosure(n);
      {
        RoundingGuard guard;
        line.coefficients(pv.data(), enclosure.data());
      }
      std::vector<MpfiInterval> wide(n);
      {
        const unsigned saved = MpfiInterval::default_precision();
        MpfiInterval::default_precision(30);  // decimal digits, about 100 bits
        line.coefficients(pv.data(), wide.data());
        MpfiInterval::default_precision(saved);
      }
      for (std::size_t k = 0; k < n; ++k) {
        BOOST_TEST_CONTEXT(name << " trial " << trial << " c_" << k << " = " << reference[k]) {
          BOOST_TEST(std::fabs(value[k] - reference[k].to_double()) <= 1e-13 * scale);
          BOOST_TEST(exact(enclosure[k].inf()) <= reference[k]);
          BOOST_TEST(reference[k] <= exact(enclosure[k].sup()));
          BOOST_TEST(encloses(wide[k], reference[k]));
          BOOST_TEST(width(wide[k]).convert_to<double>() <= 1e-20 * scale);
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(line_through_sphere_centre) {
  const LinePolynomial line(catalog_entry("sphere").surface());
  // p = 0, v = (3/5, 4/5, 0): E(t v) = t^2 - 1.
  const double pv[6] = {0, 0, 0, 0.6, 0.8, 0};
  double c[3];
  line.coefficients(pv, c);
  BOOST_TEST(c[0] == -1.0);
  BOOST_TEST(c[1] == 0.0);
  BOOST_TEST(c[2] == 1.0, boost::test_tools::tolerance(1e-15));
  // p = (2, 0, 0), v = e_x: (t + 2)^2 - 1 = t^2 + 4t + 3, roots -1 and -3.
  const double shifted[6] = {2, 0, 0, 1, 0, 0};
  line.coefficients(shifted, c);
  BOOST_TEST(c[0] == 3.0);
  BOOST_TEST(c[1] == 4.0);
  BOOST_TEST(c[2] == 1.0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_CASE(cancelling_terms_of_higher_degree_leave_the_coefficients_exact) {
  // The cubic terms cancel: E has degree 2 though E's own program computes cubes.
  const Surface s = Surface::parse("(x+1)^3 - x^3 - 3*y^2 - 3*z^2 - 1");
  const LinePolynomial line(s);
  BOOST_TEST_REQUIRE(line.degree() == 2);
  const double pv[6] = {0.5, -0.25, 2, 1, 2, -3};
  const std::vector<GiNaC::numeric> reference = reference_coefficients(s, pv, 2);
  RoundingGuard guard;
  Interval c[3];
  line.coefficients(pv, c);
  for (int k = 0; k < 3; ++k) {
    BOOST_TEST(exact(c[k].inf()) <= reference[k]);
    BOOST_TEST(reference[k] <= exact(c[k].sup()));
    BOOST_TEST(c[k].sup() - c[k].inf() <= 1e-13);
  }
}
