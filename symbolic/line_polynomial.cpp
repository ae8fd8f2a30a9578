#include "symbolic/line_polynomial.h"

#include <array>
#include <type_traits>

#include "common/errors.h"

namespace delmesh {

namespace {

std::vector<GiNaC::symbol> line_parameters() {
  return {GiNaC::symbol("p0"), GiNaC::symbol("p1"), GiNaC::symbol("p2"),
          GiNaC::symbol("v0"), GiNaC::symbol("v1"), GiNaC::symbol("v2")};
}

//! The coefficients of E(p + t v) in t, expanded, lowest degree first.
std::vector<GiNaC::ex> expand_along_line(const GiNaC::ex& E, const std::vector<GiNaC::symbol>& pv) {
  const GiNaC::symbol t("t");
  const GiNaC::lst on_line{coordinate_x() == pv[0] + t * pv[3], coordinate_y() == pv[1] + t * pv[4],
                           coordinate_z() == pv[2] + t * pv[5]};
  const GiNaC::ex along = E.subs(on_line).expand();
  const int degree = along.degree(t);
  std::vector<GiNaC::ex> coefficients;
  coefficients.reserve(static_cast<std::size_t>(degree) + 1);
  for (int k = 0; k <= degree; ++k) coefficients.push_back(along.coeff(t, k));
  return coefficients;
}

//! The surface's E, checked to be a polynomial with rational coefficients.
const GiNaC::ex& polynomial_E(const Surface& surface) {
  if (!surface.is_polynomial())
    throw PreconditionViolation("LinePolynomial: E = " + surface.text() +
                                " is not a polynomial with rational coefficients");
  return surface.E();
}

}  // namespace

LinePolynomial::LinePolynomial(const Surface& surface)
    : E_(polynomial_E(surface)),
      parameters_(line_parameters()),
      degree_(surface.degree()),
      along_line_({E_}, {coordinate_x(), coordinate_y(), coordinate_z()}) {}

const LinePolynomial::Expanded& LinePolynomial::expanded() const {
  std::call_once(expanded_once_, [this] {
    std::vector<GiNaC::ex> expressions = expand_along_line(E_, parameters_);
    CompiledSystem program(expressions, {}, parameters_);
    expanded_.reset(new Expanded{std::move(expressions), std::move(program)});
  });
  return *expanded_;
}

template <class T>
void LinePolynomial::coefficients(const double* p_and_v, T* coefficients) const {
  if constexpr (std::is_same_v<T, double> || std::is_same_v<T, Interval>) {
    const std::array<T, 3> p{T(p_and_v[0]), T(p_and_v[1]), T(p_and_v[2])};
    const std::array<T, 3> v{T(p_and_v[3]), T(p_and_v[4]), T(p_and_v[5])};
    if (along_line_.evaluate_along_line(p.data(), v.data(), degree_, coefficients)) return;
  }
  std::array<T, 6> parameters;
  for (std::size_t i = 0; i < 6; ++i) parameters[i] = T(p_and_v[i]);
  expanded().program.values<T>(nullptr, parameters.data(), coefficients);
}

#define DELMESH_DEFINE_LINE_POLYNOMIAL(T) \
  template void LinePolynomial::coefficients<T>(const double*, T*) const;
DELMESH_DEFINE_LINE_POLYNOMIAL(double)
DELMESH_DEFINE_LINE_POLYNOMIAL(Interval)
DELMESH_DEFINE_LINE_POLYNOMIAL(MpfrReal)
DELMESH_DEFINE_LINE_POLYNOMIAL(MpfiInterval)
DELMESH_DEFINE_LINE_POLYNOMIAL(Complex)
#undef DELMESH_DEFINE_LINE_POLYNOMIAL

}  // namespace delmesh
