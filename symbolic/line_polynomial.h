#pragma once
//! \file line_polynomial.h
//! For a polynomial surface, E restricted to the line p + t v as a polynomial in t whose
//! coefficients are expressions in the line parameters (p, v), compiled once per surface.
//! Evaluating the coefficients over Interval gives rigorous coefficient enclosures for the
//! univariate isolator (SurfaceLine, VorEdge).

#include <memory>
#include <mutex>
#include <vector>

#include "symbolic/compiled_system.h"
#include "symbolic/detail/straight_line_program.h"
#include "symbolic/surface.h"

namespace delmesh {

class LinePolynomial {
 public:
  //! Precondition: surface.is_polynomial().  Throws PreconditionViolation otherwise.
  explicit LinePolynomial(const Surface& surface);

  //! Degree in t: the total degree D of E (the coefficient of t^D is E's part of degree D at v,
  //! a non-zero polynomial in v).
  int degree() const { return degree_; }
  //! coefficients[k] = c_k(p, v) with E(p + t v) = Σ_k c_k t^k; parameters are (p, v), 6 doubles.
  //! Output is degree()+1 values, lowest degree first.  Instantiated for double, Interval (needs a
  //! live RoundingGuard; the result encloses the exact coefficient at the given doubles),
  //! MpfrReal, MpfiInterval (at the current default precision) and Complex.  Double and Interval
  //! evaluate E's own program on truncated series in t (StraightLineProgram::evaluate_along_line:
  //! exact in exact arithmetic, far fewer operations than the expanded coefficients); the other
  //! types evaluate the expanded coefficient expressions.
  template <class T>
  void coefficients(const double* p_and_v, T* coefficients) const;

  //! The parameter symbols p0 p1 p2 v0 v1 v2 of the coefficient expressions.
  const std::vector<GiNaC::symbol>& parameters() const { return parameters_; }
  //! c_k(p, v) as exact expanded polynomials in parameters(), lowest degree first.
  const std::vector<GiNaC::ex>& coefficient_expressions() const { return expanded().expressions; }

 private:
  //! The coefficients expanded and compiled, which the types other than double and Interval
  //! evaluate.  The mesher asks only for those two, so this is built on first use (thread-safe).
  struct Expanded {
    std::vector<GiNaC::ex> expressions;  // c_0 … c_deg
    CompiledSystem program;              // no unknowns; parameters (p, v); outputs c_0 … c_deg
  };
  const Expanded& expanded() const;

  GiNaC::ex E_;
  std::vector<GiNaC::symbol> parameters_;  // p0 p1 p2 v0 v1 v2
  int degree_ = 0;
  detail::StraightLineProgram along_line_;  // E in (x, y, z), evaluated on series in t
  mutable std::once_flag expanded_once_;
  mutable std::unique_ptr<const Expanded> expanded_;
};

#define DELMESH_DECLARE_LINE_POLYNOMIAL(T) \
  extern template void LinePolynomial::coefficients<T>(const double*, T*) const;
DELMESH_DECLARE_LINE_POLYNOMIAL(double)
DELMESH_DECLARE_LINE_POLYNOMIAL(Interval)
DELMESH_DECLARE_LINE_POLYNOMIAL(MpfrReal)
DELMESH_DECLARE_LINE_POLYNOMIAL(MpfiInterval)
DELMESH_DECLARE_LINE_POLYNOMIAL(Complex)
#undef DELMESH_DECLARE_LINE_POLYNOMIAL

}  // namespace delmesh
