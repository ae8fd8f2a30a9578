#include "solvers/detail/taylor_form.h"

#include <algorithm>

namespace delmesh::detail {

namespace {

//! Accumulates an enclosure of Σ c_i m_i over the cube, m_i a monomial with range [0, B_i] (all
//! exponents even) or [−B_i, B_i], as two sums of non-negative upper bounds — what the terms
//! can add above and below — rounded upward (the RoundingGuard's mode), so that
//! [lo − below, hi + above] encloses the sum.  Cheaper than interval products.
struct CubeSum {
  double below = 0, above = 0;
  void add(const Interval& c, double scale, bool all_even, double bound) {
    const double b = scale * bound;  // rounded up
    if (all_even) {
      above += std::max(c.sup(), 0.0) * b;
      below += std::max(-c.inf(), 0.0) * b;
    } else {
      const double m = std::max(c.sup(), -c.inf()) * b;
      above += m;
      below += m;
    }
  }
  Interval around(const Interval& centre) const { return Interval(-(below - centre.inf()), centre.sup() + above); }
};

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

void bisect_axis(const MonomialBasis& basis, std::size_t axis, int side, Interval* a) {
  for (const auto& fibre : basis.fibres(axis)) {
    const std::size_t e = fibre.size() - 1;
    // p((σ + s)/2) = P(σ + s) with P(x) = p(x/2): scale by 2^−j, then shift by σ = ±1 (additions).
    double scale = 1;
    for (std::size_t j = 1; j <= e; ++j) {
      scale *= 0.5;
      a[fibre[j]] *= Interval(scale);
    }
    for (std::size_t i = 0; i < e; ++i)
      for (std::size_t j = e; j-- > i;) {
        if (side > 0)
          a[fibre[j]] += a[fibre[j + 1]];
        else
          a[fibre[j]] -= a[fibre[j + 1]];
      }
  }
}

std::vector<Interval> radius_powers(double rho, int degree) {
  std::vector<Interval> powers(static_cast<std::size_t>(degree) + 1, Interval(1));
  for (std::size_t j = 1; j < powers.size(); ++j) powers[j] = powers[j - 1] * Interval(rho);
  return powers;
}

Interval range_on_cube(const MonomialBasis& basis, const Interval* a, const Interval* rho_powers) {
  CubeSum sum;
  for (std::size_t i = 1; i < basis.size(); ++i)
    sum.add(a[i], 1, basis.all_even(i), rho_powers[basis.total_degree(i)].sup());
  return sum.around(a[0]);
}

void gradient_on_cube(const MonomialBasis& basis, const Interval* a, const Interval* rho_powers, Interval* gradient) {
  const std::size_t n = basis.n_unknowns();
  CubeSum sums[MonomialBasis::max_unknowns];
  Interval linear[MonomialBasis::max_unknowns];
  for (std::size_t k = 0; k < n; ++k) linear[k] = Interval(0);
  for (std::size_t i = 1; i < basis.size(); ++i) {
    const auto& alpha = basis.exponent(i);
    if (basis.total_degree(i) == 1) {
      for (std::size_t k = 0; k < n; ++k)
        if (alpha[k] == 1) linear[k] = a[i];
      continue;
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (alpha[k] == 0) continue;
      // ∂/∂s_k of s^α is α_k s^{α − e_k}: all exponents even iff α_k is odd and the others even.
      bool even = alpha[k] % 2 == 1;
      for (std::size_t l = 0; l < n; ++l)
        if (l != k && alpha[l] % 2 != 0) even = false;
      sums[k].add(a[i], alpha[k], even, rho_powers[basis.total_degree(i) - 1].sup());
    }
  }
  for (std::size_t k = 0; k < n; ++k) gradient[k] = sums[k].around(linear[k]);
}

}  // namespace delmesh::detail
