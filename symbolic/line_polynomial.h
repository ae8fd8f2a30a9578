#pragma once
//! \file line_polynomial.h
//! For a polynomial surface, E restricted to the line p + t v as a polynomial in t whose
//! coefficients are expressions in the line parameters (p, v), compiled once per surface.
//! Evaluating the coefficients over Interval gives rigorous coefficient enclosures for the
//! univariate isolator (SurfaceLine, VorEdge).

#include <optional>

#include "symbolic/compiled_system.h"
#include "symbolic/surface.h"

namespace delmesh {

class LinePolynomial {
 public:
  //! Precondition: surface.is_polynomial().  Throws PreconditionViolation otherwise.
  explicit LinePolynomial(const Surface& surface);

  //! Degree in t (= total degree of E, or lower for special E).
  int degree() const { return degree_; }
  //! coefficients[k] = c_k(p, v) with E(p + t v) = Σ_k c_k t^k; parameters are (p, v), 6 doubles.
  //! Output is degree()+1 values, lowest degree first.
  template <class T>
  void coefficients(const double* p_and_v, T* coefficients) const;

 private:
  int degree_ = 0;
  CompiledSystem program_;  // no unknowns; parameters (p, v); outputs c_0 … c_deg
};

}  // namespace delmesh
