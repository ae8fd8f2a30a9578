#include "symbolic/compiled_system.h"

#include <algorithm>
#include <optional>
#include <string>

#include "common/errors.h"
#include "common/run_limits.h"
#include "symbolic/detail/straight_line_program.h"
#include "symbolic/complex_interval.h"
#include "symbolic/monomial_basis.h"
#include "symbolic/polynomial_form.h"
#include "symbolic/scalar_traits.h"
#include "common/tolerances.h"

namespace delmesh {

namespace {

std::vector<GiNaC::symbol> concatenate(const std::vector<GiNaC::symbol>& a, const std::vector<GiNaC::symbol>& b) {
  std::vector<GiNaC::symbol> all(a);
  all.insert(all.end(), b.begin(), b.end());
  return all;
}

// CompiledSystem::coefficient_lower_bound_on_a_line() for the program of the equations.
std::optional<std::size_t> lower_bound_on_a_line(const detail::StraightLineProgram& program, std::size_t n_unknowns,
                                                 std::size_t n_parameters) {
  if (n_unknowns < 1 || n_unknowns > MonomialBasis::max_unknowns) return std::nullopt;
  // The truncation order: a bound of every output's degree (nothing for a program that is not
  // polynomial).
  const std::optional<int> order = program.degree_bound(n_unknowns);
  if (!order || *order > MonomialBasis::max_degree) return std::nullopt;
  const std::size_t n_inputs = n_unknowns + n_parameters;
  // A line in general position (arbitrary coordinates): only the bound's tightness depends on it.
  RoundingGuard guard;
  std::vector<Interval> point(n_inputs), direction(n_inputs, Interval(0));
  for (std::size_t j = 0; j < n_unknowns; ++j) {
    point[j] = Interval(0.3 + 0.1234 * static_cast<double>(j));
    direction[j] = Interval(0.7 - 0.2718 * static_cast<double>(j));
  }
  for (std::size_t k = 0; k < n_parameters; ++k) point[n_unknowns + k] = Interval(static_cast<double>(k + 2));
  const std::size_t width = static_cast<std::size_t>(*order) + 1;
  std::vector<Interval> coefficients(program.n_outputs() * width);
  if (!program.evaluate_along_line(point.data(), direction.data(), *order, coefficients.data()))
    return std::nullopt;
  std::size_t bound = 0;
  for (std::size_t i = 0; i < program.n_outputs(); ++i) {
    int top = 0;
    for (std::size_t k = width; k-- > 1;)
      if (certainly_nonzero(coefficients[i * width + k])) {
        top = static_cast<int>(k);
        break;
      }
    bound += MonomialBasis(n_unknowns, top).size();
  }
  return bound;
}

//! Equations followed by the row-major m × n Jacobian.
std::vector<GiNaC::ex> values_and_jacobian_outputs(const std::vector<GiNaC::ex>& equations,
                                                   const GiNaC::matrix& jacobian, std::size_t n) {
  std::vector<GiNaC::ex> out(equations);
  for (std::size_t i = 0; i < equations.size(); ++i)
    for (std::size_t j = 0; j < n; ++j) out.push_back(jacobian(i, j));
  return out;
}

//! ∂²f_i/∂u_j∂u_k, in the order (i, j, k), derived from the Jacobian.
std::vector<GiNaC::ex> hessian_outputs(const GiNaC::matrix& jacobian, const std::vector<GiNaC::symbol>& unknowns,
                                       std::size_t m) {
  const std::size_t n = unknowns.size();
  std::vector<GiNaC::ex> out;
  out.reserve(m * n * n);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < n; ++k) {
        // One derivative may take long on a large expression: the limits are read before each.
        RunLimits::current().check("differentiating the compiled system", true);
        out.push_back(jacobian(i, j).diff(unknowns[k]));
      }
  return out;
}

GiNaC::matrix derive_jacobian(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& unknowns) {
  GiNaC::matrix jacobian(static_cast<unsigned>(std::max<std::size_t>(equations.size(), 1)),
                         static_cast<unsigned>(std::max<std::size_t>(unknowns.size(), 1)));
  for (std::size_t i = 0; i < equations.size(); ++i)
    for (std::size_t j = 0; j < unknowns.size(); ++j) {
      RunLimits::current().check("differentiating the compiled system", true);
      jacobian(i, j) = equations[i].diff(unknowns[j]);
    }
  return jacobian;
}

}  // namespace

CompiledSystem::CompiledSystem(const PrimitiveSystem& system, bool with_hessians, PolynomialFormBuild forms)
    : n_unknowns_(system.n_unknowns()), n_parameters_(system.n_parameters()), n_equations_(system.n_equations()) {
  if (n_equations_ > 0 && n_unknowns_ > 0 &&
      (system.jacobian.rows() != n_equations_ || system.jacobian.cols() != n_unknowns_))
    throw PreconditionViolation("CompiledSystem: the Jacobian of primitive '" + system.name + "' is " +
                                std::to_string(system.jacobian.rows()) + " x " +
                                std::to_string(system.jacobian.cols()) + ", expected " +
                                std::to_string(n_equations_) + " x " + std::to_string(n_unknowns_));
  const std::vector<GiNaC::symbol> inputs = concatenate(system.unknowns, system.parameters);
  values_ = std::make_unique<detail::StraightLineProgram>(system.equations, inputs);
  values_and_jacobian_ = std::make_unique<detail::StraightLineProgram>(
      values_and_jacobian_outputs(system.equations, system.jacobian, n_unknowns_), inputs);
  if (with_hessians) compile_hessians(system.equations, system.jacobian, system.unknowns, inputs);
  world_point_ = std::make_unique<detail::StraightLineProgram>(
      std::vector<GiNaC::ex>(system.world_point.begin(), system.world_point.end()), inputs);
  build_polynomial_form(system.equations, system.unknowns, system.parameters, forms);
}

CompiledSystem::CompiledSystem(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& unknowns,
                               const std::vector<GiNaC::symbol>& parameters, bool with_hessians,
                               PolynomialFormBuild forms)
    : n_unknowns_(unknowns.size()), n_parameters_(parameters.size()), n_equations_(equations.size()) {
  const std::vector<GiNaC::symbol> inputs = concatenate(unknowns, parameters);
  const GiNaC::matrix jacobian = derive_jacobian(equations, unknowns);
  values_ = std::make_unique<detail::StraightLineProgram>(equations, inputs);
  values_and_jacobian_ = std::make_unique<detail::StraightLineProgram>(
      values_and_jacobian_outputs(equations, jacobian, n_unknowns_), inputs);
  if (with_hessians) compile_hessians(equations, jacobian, unknowns, inputs);
  if (n_unknowns_ >= 3)
    world_point_ = std::make_unique<detail::StraightLineProgram>(
        std::vector<GiNaC::ex>{unknowns[0], unknowns[1], unknowns[2]}, inputs);
  build_polynomial_form(equations, unknowns, parameters, forms);
}

void CompiledSystem::compile_hessians(const std::vector<GiNaC::ex>& equations, const GiNaC::matrix& jacobian,
                                      const std::vector<GiNaC::symbol>& unknowns,
                                      const std::vector<GiNaC::symbol>& inputs) {
  std::vector<GiNaC::ex> hessians = hessian_outputs(jacobian, unknowns, n_equations_);
  std::vector<GiNaC::ex> all = values_and_jacobian_outputs(equations, jacobian, n_unknowns_);
  all.insert(all.end(), hessians.begin(), hessians.end());
  hessians_ = std::make_unique<detail::StraightLineProgram>(hessians, inputs);
  values_and_derivatives_ = std::make_unique<detail::StraightLineProgram>(all, inputs);
}

void CompiledSystem::build_polynomial_form(const std::vector<GiNaC::ex>& equations,
                                           const std::vector<GiNaC::symbol>& unknowns,
                                           const std::vector<GiNaC::symbol>& parameters, PolynomialFormBuild forms) {
  if (forms == PolynomialFormBuild::never) return;
  // instructions < ratio · (a lower bound on the coefficients) ≤ ratio · n_coefficients: the rule
  // of taylor_forms_pay() fails whatever the form, so it need not be built.
  const double instructions = static_cast<double>(instruction_count());
  // The bound on a line is never above the expansion's, so it is tried first: when it already
  // decides, the expansion is not needed.
  auto too_few_instructions = [&](std::size_t coefficients) {
    return instructions < tolerances::taylor_form_instruction_ratio * static_cast<double>(coefficients);
  };
  if (forms == PolynomialFormBuild::if_it_pays) {
    const std::optional<std::size_t> on_a_line = coefficient_lower_bound_on_a_line();
    if (on_a_line && too_few_instructions(*on_a_line)) return;
    if (too_few_instructions(PolynomialForm::coefficient_lower_bound(equations, unknowns, parameters))) return;
  }
  // A coefficient program proved longer than the compiled one fails the rule's second condition.
  if (forms == PolynomialFormBuild::if_it_pays &&
      instructions < static_cast<double>(PolynomialForm::instruction_lower_bound(
                         equations, unknowns, parameters, tolerances::polynomial_form_max_terms)))
    return;
  polynomial_form_ = PolynomialForm::try_build(equations, unknowns, parameters, tolerances::polynomial_form_max_terms);
  taylor_forms_pay_ =
      polynomial_form_ &&
      instructions >= tolerances::taylor_form_instruction_ratio * static_cast<double>(polynomial_form_->n_coefficients()) &&
      static_cast<double>(polynomial_form_->instruction_count()) <= instructions;
  if (forms == PolynomialFormBuild::if_it_pays && !taylor_forms_pay_) polynomial_form_.reset();
}

CompiledSystem::~CompiledSystem() = default;
CompiledSystem::CompiledSystem(CompiledSystem&&) noexcept = default;
CompiledSystem& CompiledSystem::operator=(CompiledSystem&&) noexcept = default;

std::optional<std::size_t> CompiledSystem::coefficient_lower_bound_on_a_line() const {
  return lower_bound_on_a_line(*values_, n_unknowns_, n_parameters_);
}

std::size_t CompiledSystem::instruction_count() const { return values_and_jacobian_->instruction_count(); }

template <class T>
void CompiledSystem::values(const T* unknowns, const T* parameters, T* values) const {
  values_->evaluate(unknowns, n_unknowns_, parameters, values, n_equations_, static_cast<T*>(nullptr));
}

template <class T>
void CompiledSystem::values_and_jacobian(const T* unknowns, const T* parameters, T* values, T* jacobian) const {
  values_and_jacobian_->evaluate(unknowns, n_unknowns_, parameters, values, n_equations_, jacobian);
}

template <class T>
void CompiledSystem::hessians(const T* unknowns, const T* parameters, T* hessians) const {
  if (!hessians_) throw PreconditionViolation("CompiledSystem::hessians: compiled without Hessians");
  hessians_->evaluate(unknowns, n_unknowns_, parameters, hessians, hessians_->n_outputs(),
                      static_cast<T*>(nullptr));
}

template <class T>
void CompiledSystem::values_and_derivatives(const T* unknowns, const T* parameters, T* values, T* derivatives) const {
  if (!values_and_derivatives_)
    throw PreconditionViolation("CompiledSystem::values_and_derivatives: compiled without Hessians");
  values_and_derivatives_->evaluate(unknowns, n_unknowns_, parameters, values, n_equations_, derivatives);
}

template <class T>
void CompiledSystem::world_point(const T* unknowns, const T* parameters, T* xyz) const {
  if (!world_point_)
    throw PreconditionViolation("CompiledSystem::world_point: no world point (fewer than 3 unknowns)");
  world_point_->evaluate(unknowns, n_unknowns_, parameters, xyz, 3, static_cast<T*>(nullptr));
}

#define DELMESH_DEFINE_COMPILED_SYSTEM(T)                                                  \
  template void CompiledSystem::values<T>(const T*, const T*, T*) const;                  \
  template void CompiledSystem::values_and_jacobian<T>(const T*, const T*, T*, T*) const; \
  template void CompiledSystem::hessians<T>(const T*, const T*, T*) const;                \
  template void CompiledSystem::values_and_derivatives<T>(const T*, const T*, T*, T*) const; \
  template void CompiledSystem::world_point<T>(const T*, const T*, T*) const;
DELMESH_DEFINE_COMPILED_SYSTEM(double)
DELMESH_DEFINE_COMPILED_SYSTEM(Interval)
DELMESH_DEFINE_COMPILED_SYSTEM(MpfrReal)
DELMESH_DEFINE_COMPILED_SYSTEM(MpfiInterval)
DELMESH_DEFINE_COMPILED_SYSTEM(Complex)
#undef DELMESH_DEFINE_COMPILED_SYSTEM
template void CompiledSystem::values<ComplexInterval>(const ComplexInterval*, const ComplexInterval*,
                                                      ComplexInterval*) const;
template void CompiledSystem::values_and_jacobian<ComplexInterval>(const ComplexInterval*, const ComplexInterval*,
                                                                   ComplexInterval*, ComplexInterval*) const;

}  // namespace delmesh
