#pragma once
//! \file polynomial_form.h
//! A system f_i(u; q) that is polynomial in its unknowns u (n ≤ 3) written in the monomial basis:
//! f_i(u; q) = Σ_{|α| ≤ d_i} c_{i,α}(q) u^α, with the coefficients c_{i,α} as exact expressions in
//! the parameters q compiled once into a straight-line program.  Evaluating the coefficients over
//! Interval at given parameters gives rigorous enclosures of the exact coefficients; from those the
//! subdivision solver builds Taylor forms of f on each box (solvers/detail/taylor_form.h), whose
//! ranges are far tighter than the natural interval form of the expression.

#include <memory>
#include <vector>

#include <ginac/ginac.h>

#include "symbolic/compiled_system.h"
#include "symbolic/monomial_basis.h"

namespace delmesh {

class PolynomialForm {
 public:
  //! The monomial form of `equations` in `unknowns`, or null when 1 ≤ n ≤ 3 fails, an equation is
  //! not a polynomial in the unknowns (GiNaC's is_polynomial; e.g. exp(x)), a total degree
  //! exceeds 64, or the expanded equations have more than `max_terms` terms in all (the
  //! coefficient program would cost more than it saves).  Coefficients must be expressions that
  //! CompiledSystem accepts (rational numbers, the parameters, exp/log/sin/cos/sqrt of them).
  static std::unique_ptr<PolynomialForm> try_build(const std::vector<GiNaC::ex>& equations,
                                                   const std::vector<GiNaC::symbol>& unknowns,
                                                   const std::vector<GiNaC::symbol>& parameters,
                                                   std::size_t max_terms);

  //! A lower bound on n_coefficients() of try_build(equations, unknowns, parameters, ·) when that
  //! form exists, found without the full expansion: with the parameters q_k replaced by numbers
  //! (2, 3, 4, ...), each equation is expanded in the unknowns alone and its total degree d′_i
  //! read off; the bound is Σ_i C(n + d′_i, n).  Proof: the expansion of a specialisation is the
  //! specialisation of the full expansion, whose coefficients c_{i,α}(q) can only vanish there, so
  //! d′_i ≤ d_i, and C(n + d, n), the size of the basis of degree d, grows with d.  Returns 0 when
  //! the specialisation cannot be evaluated (a division by zero at these numbers) or an equation is
  //! not polynomial in the unknowns (no form exists then anyway).
  static std::size_t coefficient_lower_bound(const std::vector<GiNaC::ex>& equations,
                                             const std::vector<GiNaC::symbol>& unknowns,
                                             const std::vector<GiNaC::symbol>& parameters);

  //! A lower bound on instruction_count() of try_build(equations, unknowns, parameters, max_terms)
  //! when that form exists: the number of distinct monomials of total degree ≥ 2 in the
  //! parameters alone among the terms of the expanded equations.  Proof: each such monomial m is
  //! the parameter part of some term c·u^α·m, so c·m is a term of the coefficient of u^α, and
  //! the coefficient program (compiled without expanding or factoring) computes c·m, or m
  //! itself when c = ±1 (a negative term is subtracted), in a register of its own: its last
  //! product or power is an instruction, and terms with different m are different expressions,
  //! so no two of them share it.  Returns 0 (no bound) when an equation is not polynomial in the
  //! unknowns and the parameters or expansion_term_bound() exceeds max_terms (the expansion
  //! could be huge; try_build() then decides with its cheaper probes).  It costs the expansion
  //! alone, not the coefficients nor their program.
  static std::size_t instruction_lower_bound(const std::vector<GiNaC::ex>& equations,
                                             const std::vector<GiNaC::symbol>& unknowns,
                                             const std::vector<GiNaC::symbol>& parameters, std::size_t max_terms);

  //! An upper bound on the number of terms of the expanded equations, Σ_i term_count(e_i.expand()),
  //! read off the expression trees without expanding, and min(·, cap).  Proof, by induction on the
  //! tree of a polynomial: a symbol or a number expands to one term; a sum to at most the sum of
  //! its operands' counts and a product to at most their product (like terms may merge or
  //! cancel, never split); a^k with k a positive integer, a expanding to m terms, to at most the
  //! number of monomials of degree k in m letters, C(m + k − 1, k).  Any other node (not
  //! polynomial) gets cap, i.e. no bound.  try_build() skips its cheaper specialised expansions
  //! when this bound already shows the terms within max_terms.
  static std::size_t expansion_term_bound(const std::vector<GiNaC::ex>& equations, std::size_t cap);

  std::size_t n_unknowns() const { return n_; }
  std::size_t n_equations() const { return bases_.size(); }
  std::size_t n_parameters() const { return n_parameters_; }
  //! The basis of equation i: its total degree d_i in the unknowns and the order of its coefficients.
  const MonomialBasis& basis(std::size_t i) const { return bases_[i]; }
  //! Equation i's coefficients start at offset(i) in the output of coefficients().
  std::size_t offset(std::size_t i) const { return offsets_[i]; }
  //! Σ_i basis(i).size().
  std::size_t n_coefficients() const { return offsets_.back(); }
  //! The exact coefficient c_{i,α} (α = basis(i).exponent(k)) as an expression in the parameters.
  const GiNaC::ex& coefficient_expression(std::size_t i, std::size_t k) const { return expressions_[offsets_[i] + k]; }

  //! Instructions of the coefficient program (its cost per evaluation).
  std::size_t instruction_count() const { return program_.instruction_count(); }
  //! out[offset(i) + k] = c_{i,α_k}(parameters), n_coefficients() values.  Over Interval (with a
  //! live RoundingGuard) each output encloses the exact coefficient at the given parameters.
  template <class T>
  void coefficients(const T* parameters, T* out) const {
    program_.values<T>(nullptr, parameters, out);
  }

 private:
  PolynomialForm(std::size_t n, std::size_t n_parameters, std::vector<MonomialBasis> bases,
                 std::vector<GiNaC::ex> expressions, const std::vector<GiNaC::symbol>& parameters);

  std::size_t n_, n_parameters_;
  std::vector<MonomialBasis> bases_;
  std::vector<std::size_t> offsets_;
  std::vector<GiNaC::ex> expressions_;
  CompiledSystem program_;  // no unknowns; the parameters are the inputs
};

}  // namespace delmesh
