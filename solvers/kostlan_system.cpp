#include "solvers/kostlan_system.h"

#include <cmath>
#include <string>

#include "common/errors.h"
#include "symbolic/surface.h"

namespace delmesh {

double KostlanRng::uniform() {
  // 53 random bits → a double in [0, 1); shifted by half an ulp so 0 never occurs.
  const std::uint64_t bits = engine_() >> 11;
  return (static_cast<double>(bits) + 0.5) * 0x1.0p-53;
}

double KostlanRng::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = uniform(), u2 = uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * M_PI * u2;
  spare_ = radius * std::sin(angle);
  has_spare_ = true;
  return radius * std::cos(angle);
}

namespace {

//! The double x as an exact GiNaC rational (every finite double is a dyadic rational).
GiNaC::numeric exact_rational(double x) {
  if (!std::isfinite(x)) throw PreconditionViolation("kostlan: non-finite number " + std::to_string(x));
  if (x == 0) return 0;
  int exponent = 0;
  const double mantissa = std::frexp(x, &exponent);  // x = mantissa · 2^exponent, |mantissa| ∈ [1/2, 1)
  const auto integer = static_cast<long long>(std::ldexp(mantissa, 53));  // exact
  return GiNaC::numeric(integer) * GiNaC::numeric(2).power(GiNaC::numeric(exponent - 53));
}

//! Multi-indices α ∈ N^n with |α| ≤ degree, graded (by |α|) then lexicographic (descending α_1, …).
void exponents_of_degree(std::size_t n, int total, std::vector<int>& prefix,
                         std::vector<std::vector<int>>& out) {
  if (prefix.size() + 1 == n) {
    prefix.push_back(total);
    out.push_back(prefix);
    prefix.pop_back();
    return;
  }
  for (int k = total; k >= 0; --k) {
    prefix.push_back(k);
    exponents_of_degree(n, total - k, prefix, out);
    prefix.pop_back();
  }
}

//! d! / ((d − |α|)! α_1! ⋯ α_n!) in double (exact for the degrees used here).
double multinomial(int degree, const std::vector<int>& alpha) {
  double value = 1;
  int remaining = degree;
  for (int a : alpha) {
    // binomial(remaining, a)
    for (int k = 1; k <= a; ++k) value = value * (remaining - a + k) / k;
    remaining -= a;
  }
  return value;
}

}  // namespace

GiNaC::ex kostlan_polynomial(const std::vector<GiNaC::symbol>& variables, int degree, KostlanRng& rng,
                             KostlanCoefficients coefficients) {
  if (variables.empty()) throw PreconditionViolation("kostlan_polynomial: no variables");
  if (degree < 1) throw InvalidInput("kostlan_polynomial: degree must be ≥ 1, got " + std::to_string(degree));
  const std::size_t n = variables.size();
  GiNaC::ex sum = 0;
  for (int total = 0; total <= degree; ++total) {
    std::vector<std::vector<int>> alphas;
    std::vector<int> prefix;
    exponents_of_degree(n, total, prefix, alphas);
    for (const auto& alpha : alphas) {
      const double sample = rng.normal() * std::sqrt(multinomial(degree, alpha));
      GiNaC::ex coefficient;
      if (coefficients == KostlanCoefficients::exact_rational)
        coefficient = exact_rational(std::ldexp(std::nearbyint(std::ldexp(sample, 24)), -24));
      else
        coefficient = GiNaC::numeric(sample);
      GiNaC::ex monomial = 1;
      for (std::size_t i = 0; i < n; ++i) monomial *= GiNaC::pow(variables[i], alpha[i]);
      sum += coefficient * monomial;
    }
  }
  return sum;
}

namespace {

void finish_system(PrimitiveSystem& system) {
  const std::size_t m = system.equations.size(), n = system.unknowns.size();
  system.jacobian = GiNaC::matrix(m, n);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < n; ++j) system.jacobian(i, j) = system.equations[i].diff(system.unknowns[j]);
}

}  // namespace

PrimitiveSystem kostlan_system(const std::vector<int>& degrees, std::uint64_t seed,
                               KostlanCoefficients coefficients) {
  if (degrees.empty()) throw PreconditionViolation("kostlan_system: no equations");
  const std::size_t n = degrees.size();
  PrimitiveSystem system;
  system.name = "kostlan";
  if (n <= 3) {
    const GiNaC::symbol* xyz[3] = {&coordinate_x(), &coordinate_y(), &coordinate_z()};
    for (std::size_t i = 0; i < n; ++i) system.unknowns.push_back(*xyz[i]);
  } else {
    for (std::size_t i = 0; i < n; ++i) system.unknowns.emplace_back("u" + std::to_string(i));
  }
  KostlanRng rng(seed);
  for (int degree : degrees) system.equations.push_back(kostlan_polynomial(system.unknowns, degree, rng, coefficients));
  for (std::size_t k = 0; k < 3; ++k) system.world_point[k] = k < n ? GiNaC::ex(system.unknowns[k]) : GiNaC::ex(0);
  finish_system(system);
  return system;
}

PrimitiveSystem scale_into_box(const PrimitiveSystem& system, const SolverBox& box) {
  const std::size_t n = system.unknowns.size();
  if (box.bounds.size() != n)
    throw PreconditionViolation("scale_into_box: the box has " + std::to_string(box.bounds.size()) +
                                " sides, the system " + std::to_string(n) + " unknowns");
  GiNaC::exmap substitution;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& [lo, hi] = box.bounds[i];
    if (!(lo < hi)) throw PreconditionViolation("scale_into_box: empty side " + std::to_string(i));
    const GiNaC::numeric l = exact_rational(lo), h = exact_rational(hi);
    const GiNaC::numeric centre = (l + h) / 2, half = (h - l) / 2;
    substitution[system.unknowns[i]] = (system.unknowns[i] - centre) / half;
  }
  PrimitiveSystem scaled = system;
  scaled.name = system.name + "_scaled";
  for (auto& equation : scaled.equations) equation = equation.subs(substitution).expand();
  finish_system(scaled);
  return scaled;
}

}  // namespace delmesh
