#pragma once
//! \file monomial_basis.h
//! The dense monomial basis {u^α : |α| ≤ d} of polynomials of total degree ≤ d in n unknowns, in
//! one canonical order (graded by total degree, then lexicographic with u_0 highest), shared by
//! PolynomialForm (which emits coefficients in this order) and the subdivision solver's Taylor
//! forms (which shift and scale them).  Also the "fibres" along each axis: for fixed exponents of
//! the other unknowns, the indices of u_k^0, u_k^1, … — a univariate polynomial in u_k.

#include <array>
#include <cstddef>
#include <vector>

namespace delmesh {

class MonomialBasis {
 public:
  static constexpr std::size_t max_unknowns = 3;
  static constexpr int max_degree = 64;
  using Exponent = std::array<int, max_unknowns>;

  //! Precondition: 1 ≤ n ≤ max_unknowns and 0 ≤ degree ≤ max_degree (else PreconditionViolation).
  MonomialBasis(std::size_t n, int degree);

  std::size_t n_unknowns() const { return n_; }
  int degree() const { return degree_; }
  //! Number of monomials, C(n + d, n).
  std::size_t size() const { return exponents_.size(); }
  //! The exponent α of monomial i (entries beyond n are 0).
  const Exponent& exponent(std::size_t i) const { return exponents_[i]; }
  //! |α| of monomial i.
  int total_degree(std::size_t i) const { return total_[i]; }
  //! True iff every exponent of monomial i is even (u^α ≥ 0 everywhere).
  bool all_even(std::size_t i) const { return all_even_[i]; }
  //! The index of u^α, or size() if |α| > degree() (or an entry is negative).
  std::size_t index(const Exponent& alpha) const;
  //! Index of the monomial u_k (a linear monomial); precondition degree() ≥ 1, k < n.
  std::size_t linear(std::size_t k) const { return linear_[k]; }
  //! The fibres along axis k: fibre f lists the indices of u^β u_k^j for j = 0, 1, …, in that
  //! order, for one β with β_k = 0.
  const std::vector<std::vector<std::size_t>>& fibres(std::size_t k) const { return fibres_[k]; }

 private:
  std::size_t n_;
  int degree_;
  std::vector<Exponent> exponents_;
  std::vector<int> total_;
  std::vector<bool> all_even_;
  std::vector<std::size_t> lookup_;  // dense (d+1)^n table → index
  std::array<std::size_t, max_unknowns> linear_{};
  std::array<std::vector<std::vector<std::size_t>>, max_unknowns> fibres_;
};

}  // namespace delmesh
