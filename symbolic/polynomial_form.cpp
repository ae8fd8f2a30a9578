#include "symbolic/polynomial_form.h"

namespace delmesh {

std::unique_ptr<PolynomialForm> PolynomialForm::try_build(const std::vector<GiNaC::ex>& equations,
                                                          const std::vector<GiNaC::symbol>& unknowns,
                                                          const std::vector<GiNaC::symbol>& parameters,
                                                          std::size_t max_terms) {
  const std::size_t n = unknowns.size();
  if (n < 1 || n > MonomialBasis::max_unknowns || equations.empty()) return nullptr;
  GiNaC::lst unknown_list;
  for (const auto& u : unknowns) unknown_list.append(u);
  std::vector<GiNaC::ex> expanded;
  std::size_t terms = 0;
  for (const GiNaC::ex& e : equations) {
    if (!e.is_polynomial(unknown_list)) return nullptr;
    expanded.push_back(e.expand());
    terms += GiNaC::is_a<GiNaC::add>(expanded.back()) ? expanded.back().nops() : 1;
    if (terms > max_terms) return nullptr;
  }
  std::vector<MonomialBasis> bases;
  std::vector<GiNaC::ex> expressions;
  for (const GiNaC::ex& e : expanded) {
    int degree = 0;
    std::vector<std::pair<MonomialBasis::Exponent, GiNaC::ex>> monomials;
    const std::size_t count = GiNaC::is_a<GiNaC::add>(e) ? e.nops() : 1;
    for (std::size_t t = 0; t < count; ++t) {
      const GiNaC::ex term = GiNaC::is_a<GiNaC::add>(e) ? e.op(t) : e;
      MonomialBasis::Exponent alpha{};
      GiNaC::ex coefficient = term;
      int total = 0;
      for (std::size_t k = 0; k < n; ++k) {
        alpha[k] = term.degree(unknowns[k]);
        total += alpha[k];
        coefficient = coefficient.coeff(unknowns[k], alpha[k]);
      }
      if (total > 64) return nullptr;
      degree = std::max(degree, total);
      monomials.emplace_back(alpha, coefficient);
    }
    bases.emplace_back(n, degree);
    std::vector<GiNaC::ex> dense(bases.back().size(), GiNaC::ex(0));
    for (const auto& [alpha, coefficient] : monomials) dense[bases.back().index(alpha)] += coefficient;
    expressions.insert(expressions.end(), dense.begin(), dense.end());
  }
  return std::unique_ptr<PolynomialForm>(
      new PolynomialForm(n, parameters.size(), std::move(bases), std::move(expressions), parameters));
}

PolynomialForm::PolynomialForm(std::size_t n, std::size_t n_parameters, std::vector<MonomialBasis> bases,
                               std::vector<GiNaC::ex> expressions, const std::vector<GiNaC::symbol>& parameters)
    : n_(n),
      n_parameters_(n_parameters),
      bases_(std::move(bases)),
      expressions_(std::move(expressions)),
      program_(expressions_, {}, parameters) {
  offsets_.push_back(0);
  for (const MonomialBasis& b : bases_) offsets_.push_back(offsets_.back() + b.size());
}

}  // namespace delmesh
