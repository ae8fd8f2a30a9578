#include "symbolic/polynomial_form.h"

#include <optional>
#include <random>

#include <boost/test/unit_test.hpp>

#include "common/tolerances.h"
#include "symbolic/catalog.h"
#include "solvers/primitives.h"
#include "symbolic/scalar_traits.h"
#include "tests/symbolic/exact_rational.h"

using namespace delmesh;
using delmesh::testing::exact;

namespace {

//! Σ_α c_α u^α rebuilt from the form's coefficient expressions for equation i.
GiNaC::ex rebuild(const PolynomialForm& form, std::size_t i, const std::vector<GiNaC::symbol>& unknowns) {
  GiNaC::ex sum = 0;
  const MonomialBasis& basis = form.basis(i);
  for (std::size_t k = 0; k < basis.size(); ++k) {
    GiNaC::ex monomial = form.coefficient_expression(i, k);
    for (std::size_t j = 0; j < unknowns.size(); ++j) monomial *= GiNaC::pow(unknowns[j], basis.exponent(k)[j]);
    sum += monomial;
  }
  return sum;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(polynomial_form)

BOOST_AUTO_TEST_CASE(coefficients_rebuild_every_catalog_primitive_exactly) {
  // Exact identity: Σ c_α(q) u^α − f_i(u; q) expands to 0, for every primitive of every polynomial
  // catalog surface whose expansion fits the term budget.
  int forms = 0;
  for (const std::string name : {"sphere", "ellipsoid", "torus", "genus2", "tanglecube", "thin_handle"}) {
    const Surface surface = catalog_entry(name).surface();
    for (const PrimitiveInfo& info : primitive_registry()) {
      const PrimitiveSystem system = info.build(surface);
      const auto form = PolynomialForm::try_build(system.equations, system.unknowns, system.parameters,
                                                  tolerances::polynomial_form_max_terms);
      if (!form) continue;
      ++forms;
      BOOST_TEST(form->n_equations() == system.n_equations());
      BOOST_TEST(form->n_unknowns() == system.n_unknowns());
      for (std::size_t i = 0; i < system.n_equations(); ++i)
        BOOST_TEST((rebuild(*form, i, system.unknowns) - system.equations[i]).expand().is_zero(),
                   name << " " << info.name << " equation " << i);
    }
  }
  BOOST_TEST(forms >= 24);  // at least the 4 primitives in 3 unknowns or on lines of each surface
}

BOOST_AUTO_TEST_CASE(degrees_are_the_total_degrees) {
  const Surface torus = catalog_entry("torus").surface();
  const PrimitiveSystem critical = surface_critical_system(torus);
  const CompiledSystem compiled(critical);
  const PolynomialForm* form = compiled.polynomial_form();
  BOOST_REQUIRE(form);
  BOOST_TEST(form->basis(0).degree() == 4);  // E
  BOOST_TEST(form->basis(1).degree() == 3);  // ⟨∇E, a⟩
  BOOST_TEST(form->basis(2).degree() == 3);
  BOOST_TEST(form->n_coefficients() == 35u + 20u + 20u);
}

BOOST_AUTO_TEST_CASE(non_polynomial_or_oversized_systems_have_no_form) {
  const PrimitiveSystem metaball = surface_critical_system(catalog_entry("metaball").surface());
  BOOST_TEST(!CompiledSystem(metaball).polynomial_form());
  const PrimitiveSystem torus = surface_critical_system(catalog_entry("torus").surface());
  BOOST_TEST(!PolynomialForm::try_build(torus.equations, torus.unknowns, torus.parameters, 5));
  GiNaC::symbol x("x"), y("y"), p("p");
  BOOST_TEST(!PolynomialForm::try_build({x / y + 1, y - 1}, {x, y}, {p}, 100));
  BOOST_TEST(!PolynomialForm::try_build({x * y}, {}, {x, y}, 100));  // no unknowns
}

// try_build rejects some systems from a partial expansion (parameters fixed to numbers) before
// expanding them fully; the outcome must be exactly "more than max_terms terms in all".
BOOST_AUTO_TEST_CASE(early_rejection_agrees_with_the_full_term_count) {
  int rejected = 0, accepted = 0;
  for (const std::string name : {"torus", "genus2", "tanglecube"}) {
    for (const PrimitiveInfo& info : primitive_registry()) {
      const PrimitiveSystem system = info.build(catalog_entry(name).surface());
      if (system.n_unknowns() < 1 || system.n_unknowns() > 3) continue;
      std::size_t terms = 0;
      for (const GiNaC::ex& e : system.equations) {
        const GiNaC::ex x = e.expand();
        terms += GiNaC::is_a<GiNaC::add>(x) ? x.nops() : 1;
      }
      for (const std::size_t max_terms : {terms - 1, terms}) {
        const bool built = static_cast<bool>(
            PolynomialForm::try_build(system.equations, system.unknowns, system.parameters, max_terms));
        BOOST_TEST(built == (terms <= max_terms), name << " " << info.name << " max_terms " << max_terms);
        (built ? accepted : rejected) += 1;
      }
    }
  }
  BOOST_TEST(accepted >= 12);
  BOOST_TEST(rejected >= 12);
}

// The term bound read off the trees is never below the terms of the full expansion, is exact on
// a product of sums with no merging, and is a real bound (below the cap) for the polynomial
// systems of the catalog's primitives, the plane systems in nine parameters included.
BOOST_AUTO_TEST_CASE(expansion_term_bound_holds_the_expanded_terms) {
  const GiNaC::symbol a("a"), b("b"), c("c"), d("d");
  BOOST_TEST(PolynomialForm::expansion_term_bound({(a + b) * (c + d)}, 1000) == 4u);
  BOOST_TEST(PolynomialForm::expansion_term_bound({GiNaC::pow(a + b + c, 2)}, 1000) == 6u);  // C(4, 2)
  BOOST_TEST(PolynomialForm::expansion_term_bound({GiNaC::pow(a + b, 40)}, 30) == 30u);       // saturated
  BOOST_TEST(PolynomialForm::expansion_term_bound({GiNaC::exp(a)}, 77) == 77u);             // no bound
  constexpr std::size_t cap = 100000;
  int bounded = 0;
  for (const std::string name : {"torus", "genus2", "tanglecube", "thin_handle", "metaball", "sphere"}) {
    const Surface surface = catalog_entry(name).surface();
    for (const PrimitiveInfo& info : primitive_registry()) {
      const PrimitiveSystem system = info.build(surface);
      const std::size_t bound = PolynomialForm::expansion_term_bound(system.equations, cap);
      if (bound >= cap) continue;
      std::size_t terms = 0;
      for (const GiNaC::ex& e : system.equations) {
        const GiNaC::ex x = e.expand();
        terms += GiNaC::is_a<GiNaC::add>(x) ? x.nops() : 1;
      }
      BOOST_TEST(terms <= bound, name << " " << info.name << ": " << terms << " terms, bound " << bound);
      ++bounded;
    }
  }
  BOOST_TEST(bounded >= 24);
}

// The bound from a specialised expansion never exceeds the form's coefficient count, and it is
// exact where no coefficient vanishes at the numbers (every catalog primitive here); the bound
// on the coefficient program never exceeds its instructions, and it exceeds the compiled
// program's on the plane primitives.  With
// PolynomialFormBuild::if_it_pays a system keeps a form exactly when taylor_forms_pay() holds, and
// that answer is the one PolynomialFormBuild::always gives (a Kostlan system, where Taylor forms
// pay, is among them).  The bound read off the compiled program on a line never exceeds the
// expansion's, and equals it on most polynomial programs here.
BOOST_AUTO_TEST_CASE(coefficient_lower_bound_and_the_forms_built_only_if_they_pay) {
  int exact_bounds = 0, paying = 0, skipped = 0, long_programs = 0, bounds_on_a_line = 0, equal_on_a_line = 0;
  std::vector<Surface> surfaces;
  for (const std::string name : {"torus", "genus2", "tanglecube", "thin_handle", "metaball"})
    surfaces.push_back(catalog_entry(name).surface());
  surfaces.push_back(Surface::parse("x^4+y^4+z^4+2*x^2*y^2*z^2-3*x*y*z+x^3-y^3+z^2*x-1"));
  for (const Surface& surface : surfaces) {
    for (const PrimitiveInfo& info : primitive_registry()) {
      const PrimitiveSystem system = info.build(surface);
      const std::size_t bound = PolynomialForm::coefficient_lower_bound(system.equations, system.unknowns,
                                                                        system.parameters);
      const CompiledSystem always(system, false, PolynomialFormBuild::always);
      const CompiledSystem if_it_pays(system, false, PolynomialFormBuild::if_it_pays);
      const CompiledSystem never(system, false, PolynomialFormBuild::never);
      if (const PolynomialForm* form = always.polynomial_form()) {
        BOOST_TEST(bound <= form->n_coefficients(), surface.text() << " " << info.name);
        exact_bounds += bound == form->n_coefficients() ? 1 : 0;
        const std::size_t instructions = PolynomialForm::instruction_lower_bound(
            system.equations, system.unknowns, system.parameters, tolerances::polynomial_form_max_terms);
        BOOST_TEST(instructions <= form->instruction_count(), surface.text() << " " << info.name);
        long_programs += instructions > always.instruction_count() ? 1 : 0;
      }
      BOOST_TEST(if_it_pays.taylor_forms_pay() == always.taylor_forms_pay(), surface.text() << " " << info.name);
      BOOST_TEST(static_cast<bool>(if_it_pays.polynomial_form()) == always.taylor_forms_pay());
      if (const std::optional<std::size_t> on_a_line = never.coefficient_lower_bound_on_a_line()) {
        BOOST_TEST(*on_a_line <= bound, surface.text() << " " << info.name);
        ++bounds_on_a_line;
        equal_on_a_line += *on_a_line == bound ? 1 : 0;
      }
      BOOST_TEST(!never.polynomial_form());
      BOOST_TEST(!never.taylor_forms_pay());
      paying += always.taylor_forms_pay() ? 1 : 0;
      skipped += always.polynomial_form() && !if_it_pays.polynomial_form() ? 1 : 0;
    }
  }
  BOOST_TEST(exact_bounds >= 20);
  BOOST_TEST(bounds_on_a_line >= 20);
  BOOST_TEST(equal_on_a_line >= bounds_on_a_line - 4);
  BOOST_TEST(long_programs >= 10);  // the plane primitives, skipped without their forms
  BOOST_TEST(paying >= 1);
  BOOST_TEST(skipped >= 12);
  // A coefficient that vanishes at the numbers: q·u² with q ↦ 2 keeps degree 2, (q − 2)·u² drops it.
  GiNaC::symbol u("u"), q("q");
  BOOST_TEST(PolynomialForm::coefficient_lower_bound({q * u * u + 1}, {u}, {q}) == 3u);
  BOOST_TEST(PolynomialForm::coefficient_lower_bound({(q - 2) * u * u + u}, {u}, {q}) == 2u);
  BOOST_TEST(PolynomialForm::coefficient_lower_bound({u / (q - 2)}, {u}, {q}) == 0u);  // division by zero
}

BOOST_AUTO_TEST_CASE(interval_coefficients_enclose_the_exact_ones) {
  const PrimitiveSystem system = silhouette_critical_system(catalog_entry("genus2").surface());
  const CompiledSystem compiled(system);
  const PolynomialForm* form = compiled.polynomial_form();
  BOOST_REQUIRE(form);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1, 1);
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<double> q(system.n_parameters());
    GiNaC::exmap at;
    for (std::size_t j = 0; j < q.size(); ++j) q[j] = uni(rng), at[system.parameters[j]] = exact(q[j]);
    std::vector<Interval> params(q.begin(), q.end()), c(form->n_coefficients());
    {
      RoundingGuard guard;
      form->coefficients(params.data(), c.data());
    }
    for (std::size_t i = 0; i < form->n_equations(); ++i)
      for (std::size_t k = 0; k < form->basis(i).size(); ++k) {
        const GiNaC::numeric value = GiNaC::ex_to<GiNaC::numeric>(form->coefficient_expression(i, k).subs(at));
        const Interval& e = c[form->offset(i) + k];
        BOOST_TEST((exact(e.inf()) <= value && value <= exact(e.sup())));
      }
  }
}

BOOST_AUTO_TEST_SUITE_END()
