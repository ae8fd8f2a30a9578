#include "symbolic/polynomial_form.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

namespace delmesh {

namespace {

std::size_t term_count(const GiNaC::ex& expanded) {
  return GiNaC::is_a<GiNaC::add>(expanded) ? expanded.nops() : 1;
}

//! Term t < term_count(expanded) of an expanded expression.
GiNaC::ex term_at(const GiNaC::ex& expanded, std::size_t t) {
  return GiNaC::is_a<GiNaC::add>(expanded) ? expanded.op(t) : expanded;
}

//! The parameters q_k ↦ k + 2 (any numbers would do).
GiNaC::exmap parameter_numbers(const std::vector<GiNaC::symbol>& parameters, std::size_t first) {
  GiNaC::exmap numbers;
  for (std::size_t i = first; i < parameters.size(); ++i) numbers[parameters[i]] = GiNaC::numeric(static_cast<long>(i + 2));
  return numbers;
}

// The bound of PolynomialForm::expansion_term_bound() for one expression, saturated at cap.
std::size_t term_bound(const GiNaC::ex& e, std::size_t cap) {
  auto saturated = [cap](double v) { return v >= static_cast<double>(cap) ? cap : static_cast<std::size_t>(v); };
  if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
    const bool sum = GiNaC::is_a<GiNaC::add>(e);
    double total = sum ? 0 : 1;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const auto part = static_cast<double>(term_bound(e.op(i), cap));
      total = sum ? total + part : total * part;
      if (total >= static_cast<double>(cap)) return cap;
    }
    return saturated(total);
  }
  if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1))) {
    const auto k = GiNaC::ex_to<GiNaC::numeric>(e.op(1));
    if (!k.is_pos_integer()) return cap;  // not a polynomial: no bound claimed
    const double m = static_cast<double>(term_bound(e.op(0), cap));
    if (m <= 1) return static_cast<std::size_t>(m);
    double count = 1;  // C(m + k − 1, k), accumulated as Π_{i=1..k} (m + i − 1) / i
    for (long i = 1; i <= k.to_long(); ++i) {
      count = count * (m + static_cast<double>(i) - 1) / static_cast<double>(i);
      if (count >= static_cast<double>(cap)) return cap;
    }
    return saturated(std::ceil(count));
  }
  return GiNaC::is_a<GiNaC::symbol>(e) || GiNaC::is_a<GiNaC::numeric>(e) ? 1 : cap;
}

// True iff the expansion of the equations has more than max_terms terms in all, proved from a
// cheaper expansion: with the parameters q_k, q_{k+1}, ... replaced by numbers (any will do; we
// take 2, 3, 4, ...), every term of the full expansion (a constant times a monomial in the
// unknowns and parameters) becomes one term or merges with others, or vanishes, so the
// specialised expansion has at most as many terms.  Tried for k = 1, 2, 4, ... < #parameters;
// each is far cheaper than the full expansion when that one is huge (E(o + u a + v b) in nine
// parameters for the degree-12 orthocircle: 0.2 s instead of 6 s per system).
// Precondition: the equations are polynomial in the unknowns and the parameters.
bool specialisation_exceeds(const std::vector<GiNaC::ex>& equations, const std::vector<GiNaC::symbol>& parameters,
                            std::size_t max_terms) {
  for (std::size_t k = 1; k < parameters.size(); k *= 2) {
    const GiNaC::exmap numbers = parameter_numbers(parameters, k);
    std::size_t terms = 0;
    for (const GiNaC::ex& e : equations) {
      terms += term_count(e.subs(numbers).expand());
      if (terms > max_terms) return true;
    }
  }
  return false;
}

}  // namespace

std::size_t PolynomialForm::expansion_term_bound(const std::vector<GiNaC::ex>& equations, std::size_t cap) {
  std::size_t bound = 0;
  for (const GiNaC::ex& e : equations) bound = std::min(bound + term_bound(e, cap), cap);
  return bound;
}

std::size_t PolynomialForm::instruction_lower_bound(const std::vector<GiNaC::ex>& equations,
                                                    const std::vector<GiNaC::symbol>& unknowns,
                                                    const std::vector<GiNaC::symbol>& parameters,
                                                    std::size_t max_terms) {
  GiNaC::lst symbols;
  for (const auto& u : unknowns) symbols.append(u);
  for (const auto& q : parameters) symbols.append(q);
  for (const GiNaC::ex& e : equations)
    if (!e.is_polynomial(symbols)) return 0;
  if (expansion_term_bound(equations, max_terms + 1) > max_terms) return 0;
  // The exponents of the parameters in a factor q^k or q, added to `exponents`; false if the
  // factor is not a power of a parameter, an unknown or a number.
  auto add_factor = [&](const GiNaC::ex& factor, std::vector<int>& exponents) {
    GiNaC::ex base = factor;
    int k = 1;
    if (GiNaC::is_a<GiNaC::power>(factor)) {
      if (!GiNaC::is_a<GiNaC::numeric>(factor.op(1)) || !GiNaC::ex_to<GiNaC::numeric>(factor.op(1)).is_pos_integer())
        return false;
      base = factor.op(0);
      k = GiNaC::ex_to<GiNaC::numeric>(factor.op(1)).to_int();
    }
    if (GiNaC::is_a<GiNaC::numeric>(base)) return true;
    if (!GiNaC::is_a<GiNaC::symbol>(base)) return false;
    for (std::size_t i = 0; i < parameters.size(); ++i)
      if (base.is_equal(parameters[i])) {
        exponents[i] += k;
        return true;
      }
    for (const auto& u : unknowns)
      if (base.is_equal(u)) return true;
    return false;
  };
  std::set<std::vector<int>> monomials;
  for (const GiNaC::ex& e : equations) {
    const GiNaC::ex expanded = e.expand();
    for (std::size_t t = 0; t < term_count(expanded); ++t) {
      const GiNaC::ex term = term_at(expanded, t);
      std::vector<int> exponents(parameters.size(), 0);
      if (GiNaC::is_a<GiNaC::mul>(term)) {
        for (std::size_t i = 0; i < term.nops(); ++i)
          if (!add_factor(term.op(i), exponents)) return 0;
      } else if (!add_factor(term, exponents)) {
        return 0;
      }
      int degree = 0;
      for (int k : exponents) degree += k;
      if (degree >= 2) monomials.insert(std::move(exponents));
    }
  }
  return monomials.size();
}

std::size_t PolynomialForm::coefficient_lower_bound(const std::vector<GiNaC::ex>& equations,
                                                    const std::vector<GiNaC::symbol>& unknowns,
                                                    const std::vector<GiNaC::symbol>& parameters) {
  const std::size_t n = unknowns.size();
  if (n < 1 || n > MonomialBasis::max_unknowns) return 0;
  GiNaC::lst unknown_list;
  for (const auto& u : unknowns) unknown_list.append(u);
  const GiNaC::exmap numbers = parameter_numbers(parameters, 0);
  std::size_t bound = 0;
  try {
    for (const GiNaC::ex& e : equations) {
      if (!e.is_polynomial(unknown_list)) return 0;
      const GiNaC::ex special = e.subs(numbers).expand();
      int degree = 0;
      for (std::size_t t = 0; t < term_count(special); ++t) {
        const GiNaC::ex term = term_at(special, t);
        int total = 0;
        for (const auto& u : unknowns) total += term.degree(u);
        degree = std::max(degree, total);
      }
      if (degree > MonomialBasis::max_degree) return 0;
      bound += MonomialBasis(n, degree).size();
    }
  } catch (const std::exception&) {
    return 0;  // e.g. GiNaC's division by zero
  }
  return bound;
}

std::unique_ptr<PolynomialForm> PolynomialForm::try_build(const std::vector<GiNaC::ex>& equations,
                                                          const std::vector<GiNaC::symbol>& unknowns,
                                                          const std::vector<GiNaC::symbol>& parameters,
                                                          std::size_t max_terms) {
  const std::size_t n = unknowns.size();
  if (n < 1 || n > MonomialBasis::max_unknowns || equations.empty()) return nullptr;
  GiNaC::lst unknown_list, symbol_list;
  for (const auto& u : unknowns) unknown_list.append(u), symbol_list.append(u);
  for (const auto& q : parameters) symbol_list.append(q);
  bool polynomial_in_all = true;
  for (const GiNaC::ex& e : equations) {
    if (!e.is_polynomial(unknown_list)) return nullptr;
    polynomial_in_all = polynomial_in_all && e.is_polynomial(symbol_list);
  }
  // The probes are skipped when the expansion is proved small without them: a specialised
  // expansion has no more terms than the full one, so they could not find more than max_terms.
  if (polynomial_in_all && expansion_term_bound(equations, max_terms + 1) > max_terms &&
      specialisation_exceeds(equations, parameters, max_terms))
    return nullptr;
  std::vector<GiNaC::ex> expanded;
  std::size_t terms = 0;
  for (const GiNaC::ex& e : equations) {
    expanded.push_back(e.expand());
    terms += term_count(expanded.back());
    if (terms > max_terms) return nullptr;
  }
  std::vector<MonomialBasis> bases;
  std::vector<GiNaC::ex> expressions;
  for (const GiNaC::ex& e : expanded) {
    int degree = 0;
    std::vector<std::pair<MonomialBasis::Exponent, GiNaC::ex>> monomials;
    for (std::size_t t = 0; t < term_count(e); ++t) {
      const GiNaC::ex term = term_at(e, t);
      MonomialBasis::Exponent alpha{};
      GiNaC::ex coefficient = term;
      int total = 0;
      for (std::size_t k = 0; k < n; ++k) {
        alpha[k] = term.degree(unknowns[k]);
        total += alpha[k];
        coefficient = coefficient.coeff(unknowns[k], alpha[k]);
      }
      if (total > MonomialBasis::max_degree) return nullptr;
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
      program_(expressions_, {}, parameters, false, PolynomialFormBuild::never) {
  offsets_.push_back(0);
  for (const MonomialBasis& b : bases_) offsets_.push_back(offsets_.back() + b.size());
}

}  // namespace delmesh
