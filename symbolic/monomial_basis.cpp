#include "symbolic/monomial_basis.h"

#include <string>

#include "common/errors.h"

namespace delmesh {

namespace {

//! Every α with |α| = total in n unknowns, lexicographically decreasing (u_0 highest first).
void append_degree(std::size_t n, int total, std::size_t k, MonomialBasis::Exponent& alpha,
                   std::vector<MonomialBasis::Exponent>& out) {
  if (k + 1 == n) {
    alpha[k] = total;
    out.push_back(alpha);
    alpha[k] = 0;
    return;
  }
  for (int a = total; a >= 0; --a) {
    alpha[k] = a;
    append_degree(n, total - a, k + 1, alpha, out);
  }
  alpha[k] = 0;
}

}  // namespace

MonomialBasis::MonomialBasis(std::size_t n, int degree) : n_(n), degree_(degree) {
  if (n < 1 || n > max_unknowns || degree < 0 || degree > max_degree)
    throw PreconditionViolation("MonomialBasis: " + std::to_string(n) + " unknowns, degree " + std::to_string(degree) +
                                " (need 1 ≤ n ≤ " + std::to_string(max_unknowns) + ", 0 ≤ degree ≤ " +
                                std::to_string(max_degree) + ")");
  Exponent alpha{};
  for (int t = 0; t <= degree; ++t) append_degree(n, t, 0, alpha, exponents_);
  std::size_t table = 1;
  for (std::size_t k = 0; k < n; ++k) table *= static_cast<std::size_t>(degree + 1);
  lookup_.assign(table, exponents_.size());
  total_.resize(exponents_.size());
  all_even_.assign(exponents_.size(), true);
  for (std::size_t i = 0; i < exponents_.size(); ++i) {
    std::size_t key = 0;
    for (std::size_t k = 0; k < n; ++k) {
      key = key * static_cast<std::size_t>(degree + 1) + static_cast<std::size_t>(exponents_[i][k]);
      total_[i] += exponents_[i][k];
      if (exponents_[i][k] % 2 != 0) all_even_[i] = false;
    }
    lookup_[key] = i;
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (degree >= 1) {
      Exponent e{};
      e[k] = 1;
      linear_[k] = index(e);
    }
    for (std::size_t i = 0; i < exponents_.size(); ++i) {
      if (exponents_[i][k] != 0) continue;
      std::vector<std::size_t> fibre;
      Exponent e = exponents_[i];
      for (int j = 0; j + total_[i] <= degree; ++j) {
        e[k] = j;
        fibre.push_back(index(e));
      }
      fibres_[k].push_back(std::move(fibre));
    }
  }
}

std::size_t MonomialBasis::index(const Exponent& alpha) const {
  std::size_t key = 0;
  int total = 0;
  for (std::size_t k = 0; k < n_; ++k) {
    if (alpha[k] < 0 || alpha[k] > degree_) return size();
    total += alpha[k];
    key = key * static_cast<std::size_t>(degree_ + 1) + static_cast<std::size_t>(alpha[k]);
  }
  return total > degree_ ? size() : lookup_[key];
}

}  // namespace delmesh
