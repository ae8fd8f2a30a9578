#include "solvers/detail/taylor_form.h"

#include <random>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <ginac/ginac.h>

#include "tests/symbolic/exact_rational.h"

using namespace delmesh;
using delmesh::testing::exact;

namespace {

bool encloses(const Interval& a, const GiNaC::numeric& value) {
  return exact(a.inf()) <= value && value <= exact(a.sup());
}

//! A random polynomial of total degree d in n unknowns with dyadic coefficients, as point
//! intervals in basis order and as an exact expression.
struct RandomPolynomial {
  std::vector<Interval> coefficients;
  GiNaC::ex expression;
};

RandomPolynomial random_polynomial(const MonomialBasis& basis, const std::vector<GiNaC::symbol>& s, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> numerator(-64, 64);
  RandomPolynomial p;
  p.expression = 0;
  for (std::size_t i = 0; i < basis.size(); ++i) {
    const double c = numerator(rng) / 16.0;
    p.coefficients.emplace_back(c);
    GiNaC::ex monomial = exact(c);
    for (std::size_t k = 0; k < basis.n_unknowns(); ++k) monomial *= GiNaC::pow(s[k], basis.exponent(i)[k]);
    p.expression += monomial;
  }
  return p;
}

std::vector<GiNaC::symbol> symbols() { return {GiNaC::symbol("s0"), GiNaC::symbol("s1"), GiNaC::symbol("s2")}; }

}  // namespace

BOOST_AUTO_TEST_SUITE(taylor_form)

BOOST_AUTO_TEST_CASE(affine_substitution_encloses_the_exact_coefficients) {
  // g(s) ↦ g(s with s_k = μ + ρ s_k) against GiNaC's exact expansion, for general doubles μ, ρ
  // (rounded arithmetic) and the bisection values μ = ±1/2, ρ = 1/2.
  const auto s = symbols();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uni(-1, 1);
  RoundingGuard guard;
  for (std::size_t n = 2; n <= 3; ++n)
    for (int d : {1, 4, 7}) {
      const MonomialBasis basis(n, d);
      for (int trial = 0; trial < 4; ++trial) {
        RandomPolynomial p = random_polynomial(basis, s, rng);
        const std::size_t axis = static_cast<std::size_t>(trial) % n;
        const double mu = trial == 0 ? 0.5 : uni(rng), rho = trial == 0 ? 0.5 : 0.5 + 0.5 * std::abs(uni(rng));
        detail::substitute_affine(basis, axis, Interval(mu), Interval(rho), p.coefficients.data());
        const GiNaC::ex exact_form = p.expression.subs(s[axis] == exact(mu) + exact(rho) * s[axis]).expand();
        for (std::size_t i = 0; i < basis.size(); ++i) {
          GiNaC::ex c = exact_form;
          for (std::size_t k = 0; k < n; ++k) c = c.coeff(s[k], basis.exponent(i)[k]);
          BOOST_TEST(encloses(p.coefficients[i], GiNaC::ex_to<GiNaC::numeric>(c)), "n " << n << " d " << d);
        }
      }
    }
}

BOOST_AUTO_TEST_CASE(bisection_encloses_the_exact_halves) {
  const auto s = symbols();
  std::mt19937_64 rng(4);
  RoundingGuard guard;
  const MonomialBasis basis(3, 6);
  for (int side : {-1, 1})
    for (std::size_t axis = 0; axis < 3; ++axis) {
      RandomPolynomial p = random_polynomial(basis, s, rng);
      detail::bisect_axis(basis, axis, side, p.coefficients.data());
      const GiNaC::ex half = p.expression.subs(s[axis] == GiNaC::numeric(side, 2) + s[axis] / 2).expand();
      for (std::size_t i = 0; i < basis.size(); ++i) {
        GiNaC::ex c = half;
        for (std::size_t k = 0; k < 3; ++k) c = c.coeff(s[k], basis.exponent(i)[k]);
        BOOST_TEST(encloses(p.coefficients[i], GiNaC::ex_to<GiNaC::numeric>(c)));
      }
    }
}

BOOST_AUTO_TEST_CASE(ranges_and_gradients_enclose_sampled_values) {
  const auto s = symbols();
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> grid(-32, 32);
  RoundingGuard guard;
  for (double rho : {1.0, 1.125}) {
    const MonomialBasis basis(3, 5);
    const std::vector<Interval> rho_powers = detail::radius_powers(rho, 5);
    const RandomPolynomial p = random_polynomial(basis, s, rng);
    const Interval range = detail::range_on_cube(basis, p.coefficients.data(), rho_powers.data());
    Interval gradient[3];
    detail::gradient_on_cube(basis, p.coefficients.data(), rho_powers.data(), gradient);
    for (int sample = 0; sample < 40; ++sample) {
      GiNaC::exmap at;
      for (std::size_t k = 0; k < 3; ++k) at[s[k]] = exact(rho * grid(rng) / 32.0);  // includes the faces ±ρ
      BOOST_TEST(encloses(range, GiNaC::ex_to<GiNaC::numeric>(p.expression.subs(at))));
      for (std::size_t k = 0; k < 3; ++k)
        BOOST_TEST(encloses(gradient[k], GiNaC::ex_to<GiNaC::numeric>(p.expression.diff(s[k]).subs(at))));
    }
  }
}

BOOST_AUTO_TEST_CASE(monomial_ranges_are_exact) {
  // s0² s1⁴ ranges over [0, 1] and s0 s1 over [−1, 1] on the unit cube: each monomial's range is
  // exact, so the range of a single monomial is not overestimated at all.
  const MonomialBasis basis(2, 6);
  RoundingGuard guard;
  const std::vector<Interval> unit = detail::radius_powers(1, 6);
  std::vector<Interval> even(basis.size(), Interval(0)), odd(basis.size(), Interval(0));
  even[basis.index({2, 4, 0})] = Interval(3);
  odd[basis.index({1, 1, 0})] = Interval(-2);
  const Interval re = detail::range_on_cube(basis, even.data(), unit.data());
  const Interval ro = detail::range_on_cube(basis, odd.data(), unit.data());
  BOOST_TEST(re.inf() == 0);
  BOOST_TEST(re.sup() == 3);
  BOOST_TEST(ro.inf() == -2);
  BOOST_TEST(ro.sup() == 2);
}

BOOST_AUTO_TEST_SUITE_END()
