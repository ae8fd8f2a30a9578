#pragma once
//! \file compiled_system.h
//! A system of expressions compiled once into straight-line programs (common subexpressions
//! shared) and evaluated many times over double, Interval, MpfrReal, MpfiInterval and Complex.
//! The solvers' inner loops call only this; they never call GiNaC.
//!
//! Interval evaluation is an enclosure: for every point of the input boxes the exact value of each
//! output lies in the returned interval (requires a live RoundingGuard).  Rational constants are
//! enclosed exactly; exp, log, sin, cos, sqrt are enclosed as documented in scalar_traits.h.
//! Where an output is undefined on part of a box (log or sqrt of an argument that may be ≤ 0 or
//! < 0) the result has infinite (possibly NaN) bounds: decide exclusion with certainly_nonzero()
//! (scalar_traits.h), never with raw comparisons.  MpfiInterval evaluation is an enclosure by
//! MPFI with the same conventions.
//! MpfrReal and MpfiInterval evaluate at the type's current default precision
//! (MpfrReal::default_precision(), MpfiInterval::default_precision(), in decimal digits as Boost
//! defines it): inputs are rounded (MPFI: enclosed) to it, rational constants are converted at it
//! (correctly rounded, resp. enclosed) and every output carries it.
//! The programs are compiled from the expressions as given (nothing is expanded); common
//! subexpressions are shared across all outputs of a program (values + Jacobian is one program),
//! and the program does not depend on GiNaC's run-dependent term order, so evaluation results are
//! bitwise reproducible from run to run.
//! Thread safety: evaluation uses thread-local scratch space; distinct threads may evaluate the
//! same CompiledSystem concurrently.

#include <memory>
#include <optional>
#include <vector>

#include <ginac/ginac.h>

#include "symbolic/primitive_system.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

namespace detail {
class StraightLineProgram;
}
class PolynomialForm;

//! Whether a CompiledSystem builds the monomial form of its equations (polynomial_form()).  The
//! form costs a symbolic expansion of every equation, so systems that are only evaluated, or whose
//! solves will not use Taylor forms, can go without it.
enum class PolynomialFormBuild {
  always,      //!< whenever the equations admit one (so that TaylorForms::always can use it)
  if_it_pays,  //!< only when taylor_forms_pay() holds, i.e. when TaylorForms::automatic uses it
  never        //!< never (a system that is evaluated, never solved)
};

class CompiledSystem {
 public:
  //! Compiles the equations, the Jacobian (and, if with_hessians, the Hessians of every equation
  //! with respect to the unknowns) and the world point of a primitive system.
  explicit CompiledSystem(const PrimitiveSystem& system, bool with_hessians = false,
                          PolynomialFormBuild forms = PolynomialFormBuild::always);

  //! Compiles arbitrary expressions `equations` in `unknowns` and `parameters`; the Jacobian is
  //! derived here.  world_point() is then the identity on the first three unknowns when n ≥ 3
  //! (and throws PreconditionViolation when n < 3).  `unknowns` may be empty (then only values()
  //! is meaningful; the parameters are the inputs).
  //! Both constructors throw PreconditionViolation if an expression uses a symbol that is neither
  //! an unknown nor a parameter, a symbol is listed twice, a number is not an exact real rational,
  //! an exponent is not an integer or half an odd integer, or a function other than exp, log,
  //! sin, cos (and sqrt, which GiNaC writes as a power) occurs.
  CompiledSystem(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& unknowns,
                 const std::vector<GiNaC::symbol>& parameters, bool with_hessians = false,
                 PolynomialFormBuild forms = PolynomialFormBuild::always);

  ~CompiledSystem();
  CompiledSystem(CompiledSystem&&) noexcept;
  CompiledSystem& operator=(CompiledSystem&&) noexcept;

  std::size_t n_unknowns() const { return n_unknowns_; }
  std::size_t n_parameters() const { return n_parameters_; }
  std::size_t n_equations() const { return n_equations_; }
  bool has_hessians() const { return static_cast<bool>(hessians_); }
  //! True iff world_point() is available (a primitive system, or n ≥ 3 unknowns).
  bool has_world_point() const { return static_cast<bool>(world_point_); }
  //! The monomial form of the equations (polynomial_form.h) when they are polynomial in n ≤ 3
  //! unknowns and small enough (tolerances::polynomial_form_max_terms) and the constructor's
  //! PolynomialFormBuild asked for it, else null.  The subdivision solver uses it for Taylor forms.
  const PolynomialForm* polynomial_form() const { return polynomial_form_.get(); }
  //! True iff Taylor forms are expected to pay on this system, the rule of TaylorForms::automatic:
  //! the form exists, the values+Jacobian program has at least tolerances::taylor_form_instruction_ratio
  //! instructions per Taylor coefficient, and the coefficient program is no longer than it.
  //! With PolynomialFormBuild::if_it_pays the form is skipped without being built when
  //! coefficient_lower_bound_on_a_line() or PolynomialForm::coefficient_lower_bound() already
  //! shows the ratio too small or PolynomialForm::instruction_lower_bound() the coefficient
  //! program too long, so the answer is the same as with PolynomialFormBuild::always.
  bool taylor_forms_pay() const { return taylor_forms_pay_; }
  //! A bound below PolynomialForm::coefficient_lower_bound(), from the compiled equations instead
  //! of their expansion (what PolynomialFormBuild::if_it_pays tries first), or nothing when the
  //! program is not polynomial (then the expansion decides).  With the parameters q_k replaced by
  //! the same numbers (2, 3, 4, ...), each equation f_i is restricted to a fixed line u = a + t b
  //! of the unknowns by the Taylor evaluation along a line, over intervals; k_i is the highest
  //! power of t whose coefficient excludes 0, and the bound is Σ_i C(n + k_i, n).  Proof:
  //! truncated series keep the exact coefficients up to the truncation, so that coefficient of
  //! the restriction is non-zero; a restriction to a line has at most the total degree d′_i of
  //! the specialised f_i, so k_i ≤ d′_i, which is at most the degree of the full expansion (as in
  //! PolynomialForm::coefficient_lower_bound()), and C(n + d, n) grows with d.  The truncation
  //! order is the largest degree the program's registers can reach (sums the larger, products
  //! the sum, powers the multiple).  For a line in general position, and coefficients that the
  //! interval evaluation separates from 0, k_i = d′_i and the bound is the expansion's.
  std::optional<std::size_t> coefficient_lower_bound_on_a_line() const;
  //! Number of arithmetic instructions of the values+Jacobian program (a size measure for reports).
  std::size_t instruction_count() const;

  //! values[i] = f_i(unknowns; parameters), i < m.
  template <class T>
  void values(const T* unknowns, const T* parameters, T* values) const;
  //! values as above and jacobian[i*n + j] = ∂f_i/∂u_j (row-major m × n).
  template <class T>
  void values_and_jacobian(const T* unknowns, const T* parameters, T* values, T* jacobian) const;
  //! hessians[(i*n + j)*n + k] = ∂²f_i/∂u_j∂u_k.  Precondition: has_hessians() (else throws
  //! PreconditionViolation).
  template <class T>
  void hessians(const T* unknowns, const T* parameters, T* hessians) const;
  //! values as above, and derivatives = the Jacobian (m·n, as values_and_jacobian()) followed by
  //! the Hessians (m·n·n, as hessians()), from one program that computes their common
  //! sub-expressions once: cheaper than the two calls when both are wanted, and the same numbers
  //! (each output is evaluated by the same operations).  Precondition: has_hessians().
  template <class T>
  void values_and_derivatives(const T* unknowns, const T* parameters, T* values, T* derivatives) const;
  //! The world point (x, y, z) of the unknowns (e.g. o + u a + v b for a plane system).
  template <class T>
  void world_point(const T* unknowns, const T* parameters, T* xyz) const;

 private:
  std::size_t n_unknowns_ = 0, n_parameters_ = 0, n_equations_ = 0;
  std::unique_ptr<detail::StraightLineProgram> values_;
  std::unique_ptr<detail::StraightLineProgram> values_and_jacobian_;
  std::unique_ptr<detail::StraightLineProgram> hessians_;
  std::unique_ptr<detail::StraightLineProgram> values_and_derivatives_;  //!< with the Hessians
  std::unique_ptr<detail::StraightLineProgram> world_point_;
  std::unique_ptr<PolynomialForm> polynomial_form_;
  bool taylor_forms_pay_ = false;

  //! Compiles hessians_ and values_and_derivatives_.
  void compile_hessians(const std::vector<GiNaC::ex>& equations, const GiNaC::matrix& jacobian,
                        const std::vector<GiNaC::symbol>& unknowns, const std::vector<GiNaC::symbol>& inputs);
  void build_polynomial_form(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& unknowns,
                             const std::vector<GiNaC::symbol>& parameters, PolynomialFormBuild forms);
};

// Explicitly instantiated in compiled_system.cpp for double, Interval, MpfrReal, MpfiInterval, Complex.
#define DELMESH_DECLARE_COMPILED_SYSTEM(T)                                                        \
  extern template void CompiledSystem::values<T>(const T*, const T*, T*) const;                  \
  extern template void CompiledSystem::values_and_jacobian<T>(const T*, const T*, T*, T*) const; \
  extern template void CompiledSystem::hessians<T>(const T*, const T*, T*) const;                \
  extern template void CompiledSystem::values_and_derivatives<T>(const T*, const T*, T*, T*) const; \
  extern template void CompiledSystem::world_point<T>(const T*, const T*, T*) const;
DELMESH_DECLARE_COMPILED_SYSTEM(double)
DELMESH_DECLARE_COMPILED_SYSTEM(Interval)
DELMESH_DECLARE_COMPILED_SYSTEM(MpfrReal)
DELMESH_DECLARE_COMPILED_SYSTEM(MpfiInterval)
DELMESH_DECLARE_COMPILED_SYSTEM(Complex)
#undef DELMESH_DECLARE_COMPILED_SYSTEM

}  // namespace delmesh
