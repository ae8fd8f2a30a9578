#include "solvers/detail/taylor_form.h"

namespace delmesh::detail {

namespace {

//! An enclosure of {s^β : s ∈ [−ρ, ρ]^n} for a monomial of total degree t, scaled by a.
Interval monomial_term(const Interval& a, bool all_even, int t, const Interval* rho_powers) {
  const double bound = rho_powers[t].sup();
  return a * (all_even ? Interval(0, bound) : Interval(-bound, bound));
}

}  // namespace

void substitute_affine(const MonomialBasis& basis, std::size_t axis, const Interval& mu, const Interval& rho,
                       Interval* a) {
  for (const auto& fibre : basis.fibres(axis)) {
    const std::size_t e = fibre.size() - 1;  // degree of the fibre in s_axis
    // Taylor shift by μ (repeated synthetic division), then scale the j-th coefficient by ρ^j.
    for (std::size_t i = 0; i < e; ++i)
      for (std::size_t j = e; j-- > i;) a[fibre[j]] += mu * a[fibre[j + 1]];
    Interval power = rho;
    for (std::size_t j = 1; j <= e; ++j) {
      a[fibre[j]] *= power;
      if (j < e) power *= rho;
    }
  }
}

Interval range_on_cube(const MonomialBasis& basis, const Interval* a, const Interval* rho_powers) {
  Interval sum = a[0];
  for (std::size_t i = 1; i < basis.size(); ++i)
    sum += monomial_term(a[i], basis.all_even(i), basis.total_degree(i), rho_powers);
  return sum;
}

void gradient_on_cube(const MonomialBasis& basis, const Interval* a, const Interval* rho_powers, Interval* gradient) {
  const std::size_t n = basis.n_unknowns();
  for (std::size_t k = 0; k < n; ++k) gradient[k] = Interval(0);
  for (std::size_t i = 1; i < basis.size(); ++i) {
    const auto& alpha = basis.exponent(i);
    for (std::size_t k = 0; k < n; ++k) {
      if (alpha[k] == 0) continue;
      // ∂/∂s_k of s^α is α_k s^{α − e_k}: all exponents even iff α_k is odd and the others even.
      bool even = alpha[k] % 2 == 1;
      for (std::size_t l = 0; l < n; ++l)
        if (l != k && alpha[l] % 2 != 0) even = false;
      gradient[k] += monomial_term(a[i] * Interval(alpha[k]), even, basis.total_degree(i) - 1, rho_powers);
    }
  }
}

}  // namespace delmesh::detail
