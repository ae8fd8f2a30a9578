#include <boost/test/unit_test.hpp>

#include <cmath>
#include <sstream>

#include "common/errors.h"
#include "solvers/homotopy_solver.h"
#include "solvers/kostlan_system.h"
#include "symbolic/surface.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(kostlan_system_test)

BOOST_AUTO_TEST_CASE(same_seed_same_system_other_seed_other_system) {
  const auto a = kostlan_system({4, 5, 6}, 17);
  const auto b = kostlan_system({4, 5, 6}, 17);
  const auto c = kostlan_system({4, 5, 6}, 18);
  for (std::size_t i = 0; i < 3; ++i) {
    BOOST_TEST((a.equations[i] - b.equations[i]).expand().is_zero());
    BOOST_TEST(!(a.equations[i] - c.equations[i]).expand().is_zero());
  }
}

BOOST_AUTO_TEST_CASE(degrees_and_dense_support) {
  const auto system = kostlan_system({4, 5, 6}, 3);
  BOOST_TEST(system.n_unknowns() == 3u);
  BOOST_TEST(system.is_square());
  BOOST_TEST(equation_degrees(system) == std::vector<int>({4, 5, 6}), boost::test_tools::per_element());
  // dense: all binomial(3 + d, 3) monomials of degree ≤ d are present (a coefficient 0 has probability 0)
  const int expected_terms[] = {35, 56, 84};
  for (std::size_t i = 0; i < 3; ++i) {
    const GiNaC::ex e = system.equations[i].expand();
    BOOST_TEST(GiNaC::is_a<GiNaC::add>(e));
    BOOST_TEST(e.nops() == static_cast<std::size_t>(expected_terms[i]));
  }
  // exact Jacobian
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      BOOST_TEST((system.jacobian(i, j) - system.equations[i].diff(system.unknowns[j])).expand().is_zero());
  // world point is (x, y, z)
  BOOST_TEST((system.world_point[0] - coordinate_x()).is_zero());
  BOOST_TEST((system.world_point[2] - coordinate_z()).is_zero());
}

BOOST_AUTO_TEST_CASE(coefficients_exact_or_double) {
  const auto exact = kostlan_system({3, 3}, 5, KostlanCoefficients::exact_rational);
  const auto rounded = kostlan_system({3, 3}, 5, KostlanCoefficients::double_rounded);
  const GiNaC::ex x = coordinate_x(), y = coordinate_y();
  const GiNaC::ex ce = exact.equations[0].expand().coeff(x, 2).coeff(y, 1);
  const GiNaC::ex cd = rounded.equations[0].expand().coeff(x, 2).coeff(y, 1);
  BOOST_TEST(GiNaC::is_a<GiNaC::numeric>(ce));
  BOOST_TEST(GiNaC::ex_to<GiNaC::numeric>(ce).is_rational());
  BOOST_TEST(GiNaC::is_a<GiNaC::numeric>(cd));
  BOOST_TEST(!GiNaC::ex_to<GiNaC::numeric>(cd).is_rational());
  // the same samples: exact = the double rounded to a multiple of 2^-24
  const double de = GiNaC::ex_to<GiNaC::numeric>(ce).to_double(), dd = GiNaC::ex_to<GiNaC::numeric>(cd).to_double();
  BOOST_TEST(std::abs(de - dd) <= std::ldexp(1.0, -25));
  BOOST_TEST(GiNaC::ex_to<GiNaC::numeric>(ce * GiNaC::numeric(1 << 24)).is_integer());
}

BOOST_AUTO_TEST_CASE(coefficient_variance_is_multinomial) {
  // Coefficient of x^2 y in a degree-4 polynomial in (x, y): variance 4!/(1! 2! 1!) = 12;
  // of x^4: 1; of the constant: 1.  2000 seeded samples: the sample variance of N(0, σ²) has
  // relative standard deviation √(2/2000) ≈ 3.2 %, so ±15 % is a > 4σ band.
  const int samples = 2000;
  double sum_xy = 0, sum_x4 = 0, sum_1 = 0;
  const GiNaC::ex x = coordinate_x(), y = coordinate_y();
  for (int k = 0; k < samples; ++k) {
    KostlanRng rng(1000 + k);
    const GiNaC::ex p = kostlan_polynomial({coordinate_x(), coordinate_y()}, 4, rng).expand();
    const double cxy = GiNaC::ex_to<GiNaC::numeric>(p.coeff(x, 2).coeff(y, 1)).to_double();
    const double cx4 = GiNaC::ex_to<GiNaC::numeric>(p.coeff(x, 4).coeff(y, 0)).to_double();
    const double c1 = GiNaC::ex_to<GiNaC::numeric>(p.coeff(x, 0).coeff(y, 0)).to_double();
    sum_xy += cxy * cxy;
    sum_x4 += cx4 * cx4;
    sum_1 += c1 * c1;
  }
  BOOST_TEST(sum_xy / samples == 12.0, boost::test_tools::tolerance(0.15));
  BOOST_TEST(sum_x4 / samples == 1.0, boost::test_tools::tolerance(0.15));
  BOOST_TEST(sum_1 / samples == 1.0, boost::test_tools::tolerance(0.15));
}

BOOST_AUTO_TEST_CASE(rng_normal_moments) {
  KostlanRng rng(42);
  const int samples = 20000;
  double sum = 0, sum2 = 0;
  for (int k = 0; k < samples; ++k) {
    const double z = rng.normal();
    sum += z;
    sum2 += z * z;
  }
  BOOST_TEST(std::abs(sum / samples) < 0.03);  // σ of the mean ≈ 0.007
  BOOST_TEST(sum2 / samples == 1.0, boost::test_tools::tolerance(0.05));
}

BOOST_AUTO_TEST_CASE(scale_into_box_is_the_affine_substitution) {
  const auto f = kostlan_system({3, 4}, 9);
  SolverBox box;
  box.bounds = {{{0.5, 2.5}}, {{-3.0, 1.0}}};
  const auto g = scale_into_box(f, box);
  // g(c + h u) == f(u) exactly, with c = (1.5, -1), h = (1, 2)
  const GiNaC::ex x = coordinate_x(), y = coordinate_y();
  GiNaC::exmap back;
  back[x] = GiNaC::numeric(3, 2) + x;
  back[y] = -1 + 2 * y;
  for (std::size_t i = 0; i < 2; ++i) BOOST_TEST((g.equations[i].subs(back) - f.equations[i]).expand().is_zero());
  BOOST_TEST(equation_degrees(g) == std::vector<int>({3, 4}), boost::test_tools::per_element());
  // a simple case: x − 1/2 on [−1, 1] → root 3 on [0, 4]... via the same substitution
  PrimitiveSystem line;
  line.unknowns = {coordinate_x()};
  line.equations = {coordinate_x() - GiNaC::numeric(1, 2)};
  SolverBox wide;
  wide.bounds = {{{0.0, 4.0}}};
  const auto scaled = scale_into_box(line, wide);
  BOOST_TEST(scaled.equations[0].subs(x == 3).is_zero());
}

BOOST_AUTO_TEST_CASE(invalid_arguments_throw) {
  BOOST_CHECK_THROW(kostlan_system({}, 1), PreconditionViolation);
  BOOST_CHECK_THROW(kostlan_system({2, 0}, 1), InvalidInput);  // degree < 1
  KostlanRng rng(1);
  BOOST_CHECK_THROW(kostlan_polynomial({}, 2, rng), PreconditionViolation);
  const auto f = kostlan_system({2, 2}, 1);
  SolverBox box;
  box.bounds = {{{0.0, 1.0}}};
  BOOST_CHECK_THROW(scale_into_box(f, box), PreconditionViolation);
  box.bounds = {{{0.0, 1.0}}, {{1.0, 1.0}}};
  BOOST_CHECK_THROW(scale_into_box(f, box), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(enum_prints) {
  std::ostringstream out;
  out << KostlanCoefficients::exact_rational << ' ' << KostlanCoefficients::double_rounded;
  BOOST_TEST(out.str() == "exact_rational double_rounded");
}

BOOST_AUTO_TEST_SUITE_END()
