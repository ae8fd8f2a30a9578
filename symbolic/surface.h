#pragma once
//! \file surface.h
//! An implicit surface Σ = {E = 0} with E : R³ → R given exactly (GiNaC expression with exact
//! rational coefficients), its exact gradient ∇E and Hessian.  §2.1 of the paper.

#include <array>
#include <string>

#include <ginac/ginac.h>

namespace delmesh {

//! The three coordinate symbols x, y, z shared by every Surface and every derived system.
const GiNaC::symbol& coordinate_x();
const GiNaC::symbol& coordinate_y();
const GiNaC::symbol& coordinate_z();
//! {x, y, z} as a GiNaC list, in that order.
GiNaC::lst coordinates();

//! Axis-aligned box [x0,x1]×[y0,y1]×[z0,z1].  Invariant: lo[i] < hi[i].
struct Box3 {
  std::array<double, 3> lo{};
  std::array<double, 3> hi{};
  //! Parses "x0,x1,y0,y1,z0,z1"; throws InvalidInput on malformed text or an empty box.
  static Box3 parse(const std::string& text);
  bool contains(const std::array<double, 3>& p) const;
  double diagonal() const;
};

class Surface {
 public:
  //! Parses E(x, y, z) with GiNaC's parser.  Decimal literals become exact rationals
  //! (0.16 → 4/25).  Allowed: + - * / ^ with integer exponents, parentheses, exp sqrt sin cos log,
  //! the named constant Pi.  Throws InvalidInput (message says what and where) on a syntax error,
  //! an unknown symbol, a non-integer power, an empty or constant expression.
  static Surface parse(const std::string& text);

  //! Wraps an already built expression in x, y, z; the same validation as parse().
  explicit Surface(GiNaC::ex E, std::string text = {});

  const GiNaC::ex& E() const { return E_; }
  //! ∇E = (∂E/∂x, ∂E/∂y, ∂E/∂z), exact.
  const std::array<GiNaC::ex, 3>& gradient() const { return gradient_; }
  //! The Hessian (∂²E/∂xi∂xj), exact, symmetric 3 × 3.
  const GiNaC::matrix& hessian() const { return hessian_; }
  //! True iff E is a polynomial in x, y, z with rational coefficients.
  bool is_polynomial() const { return polynomial_; }
  //! Total degree of E when is_polynomial(), else -1.
  int degree() const { return degree_; }
  //! The text it was parsed from (or GiNaC's printing of E).
  const std::string& text() const { return text_; }

  //! E at a point, in double (GiNaC evalf; for tests and diagnostics only, not inner loops).
  double evaluate(const std::array<double, 3>& p) const;

 private:
  GiNaC::ex E_;
  std::array<GiNaC::ex, 3> gradient_;
  GiNaC::matrix hessian_{3, 3};
  bool polynomial_ = false;
  int degree_ = -1;
  std::string text_;
};

}  // namespace delmesh
