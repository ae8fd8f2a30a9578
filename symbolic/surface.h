#pragma once
//! \file surface.h
//! An implicit surface Σ = {E = 0} with E : R³ → R given exactly (GiNaC expression with exact
//! rational coefficients), its exact gradient ∇E and Hessian.  §2.1 of the paper.

#include <array>
#include <cstddef>
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
  //! Parses "x0,x1,y0,y1,z0,z1"; throws InvalidInput on malformed text, a non-finite number (one
  //! that overflows says so), a nonzero number below min_coordinate in magnitude (subnormal, or
  //! underflowing to 0), an empty box, or a box so large that a width xi1 − xi0 or the squared
  //! diagonal overflows double.
  static Box3 parse(const std::string& text);
  //! The smallest magnitude of a nonzero coordinate Box3::parse accepts: the smallest normal
  //! double, 2^-1022 ≈ 2.2250738585072014e-308.
  static constexpr double min_coordinate = 2.2250738585072014e-308;
  //! The cube [−h, h]³ centred at the origin.  Precondition: h > 0 (else PreconditionViolation).
  static Box3 cube(double h);
  bool contains(const std::array<double, 3>& p) const;
  double diagonal() const;
};

class Surface {
 public:
  //! Parses E(x, y, z) with GiNaC's parser.  Decimal literals become exact rationals
  //! (0.16 → 4/25, 1.5e-3 → 3/2000).  Allowed: + - * / ^ with integer exponents (** is the same
  //! operator as ^, so the str() of a sympy expression parses), parentheses, exp sqrt sin cos log
  //! (one argument each), the named constant Pi (also spelled pi).
  //! Grammar (a sign is allowed only at the start of an expression or parenthesis, because GiNaC
  //! reads "2*-x+y" as 2*(-x+y); write 2*(-x)+y):
  //!   expression := [+|-] factor ((+|-|*|/) factor)*
  //!   factor     := primary [(^|**) exponent]     exponent := integer | '(' [+|-] exponent ')'
  //!   primary    := number | x | y | z | Pi | pi | f '(' expression ')' | '(' expression ')'
  //! Throws InvalidInput (message quotes the offending token and its 1-based position) on a
  //! syntax error, an unknown symbol or function, a non-integer power (x^0.5, x^y, a^b^c), an
  //! empty or constant expression (3, x-x), or an expression with complex constants (sqrt(-1)).
  //! A function that is not C² (abs, min, max, sign, floor, ceil, also as sympy spells them: Abs,
  //! Min, Max, ceiling) is refused with a one-line hint naming a smooth blend to use instead.
  //! Input limits (so that no input can exhaust the stack, the memory or the time of the exact
  //! arithmetic): at most max_length characters, parentheses nested at most max_nesting deep,
  //! integer powers |n| ≤ max_power, decimal exponents |e| ≤ max_decimal_exponent, and the size
  //! limits of the constructor.  Each violation throws InvalidInput naming the limit.
  static Surface parse(const std::string& text);

  static constexpr std::size_t max_length = 10000;
  static constexpr std::size_t max_nesting = 200;
  static constexpr long max_power = 1000;
  static constexpr long max_decimal_exponent = 400;
  //! Size limits checked on the expression tree before anything is expanded: the total degree in
  //! x, y, z (bounded from the tree: sums take the maximum, products add, powers multiply by |n|)
  //! at most max_degree, and at most max_expanded_terms terms once expanded, also along a general
  //! line E(p + t v) as symbolic/line_polynomial.h expands it (bounded from the tree: sums add,
  //! products multiply, powers take the multinomial count, capped by the number of monomials of
  //! that degree in the variables).
  static constexpr std::size_t max_degree = 200;
  static constexpr std::size_t max_expanded_terms = 200000;
  //! A size limit on differentiation, checked once ∇E is known and before the Hessian is built:
  //! the Hessian, written out as a tree (each shared subexpression counted at every use, as
  //! GiNaC's evaluation and the compiled systems' derivatives of it pay for it), is estimated as
  //! s(∇E)² / s(E) from the tree sizes s of E and ∇E (a product of n factors has derivatives
  //! about n times its size; the estimate is within a factor 2 above the Hessian's size on such
  //! products).  It may be at most max_derivative_tree_size or max_derivative_growth · s(E),
  //! whichever is larger: a large polynomial, whose derivatives are no larger than itself, is
  //! never refused by it.  A product of 100 non-polynomial factors (estimate 6.4·10⁶, minutes
  //! and gigabytes of compilation) is refused; one of 50 (8.6·10⁵) is not, nor sin nested
  //! max_nesting − 1 deep (2·10⁶).
  static constexpr double max_derivative_tree_size = 3e6;
  static constexpr double max_derivative_growth = 100;

  //! Wraps an already built expression in x, y, z; the same validation as parse() on the
  //! expression: symbols ⊂ {x, y, z}, constant Pi, functions exp sin cos log, powers with integer
  //! or half-integer (square root) exponents, real constants, not constant.  Floating-point
  //! numerics become the rational of the shortest decimal that reads back as the same double
  //! (numeric(0.1) → 1/10).  Throws InvalidInput beyond the size limits (max_degree,
  //! max_expanded_terms, max_derivative_tree_size: "expression … too large to differentiate …").
  //! Under a command's limits (common/run_limits.h: RunLimits::current()) it tests them between
  //! its GiNaC steps and throws RunStopped once they have passed.
  //!
  //! A constant factor of E does not change Σ but can put E's values beyond double precision
  //! (1e200*(x^2+y^2+z^2-1)).  So when the largest coefficient magnitude c (of the expanded
  //! polynomial; of the numeric factor of a product otherwise) lies outside
  //! [2^-max_coefficient_exponent, 2^max_coefficient_exponent], E (and its derivatives) are
  //! stored divided by the power of two 2^k nearest c (2^(k−1) < c < 2^(k+1)), exactly;
  //! normalization_exponent() gives k.
  explicit Surface(GiNaC::ex E, std::string text = {});

  static constexpr long max_coefficient_exponent = 64;
  //! The k of the constructor's normalisation: E() = E_given / 2^k (0: E as given).
  int normalization_exponent() const { return normalization_exponent_; }

  const GiNaC::ex& E() const { return E_; }
  //! ∇E = (∂E/∂x, ∂E/∂y, ∂E/∂z), exact.
  const std::array<GiNaC::ex, 3>& gradient() const { return gradient_; }
  //! The Hessian (∂²E/∂xi∂xj), exact, symmetric 3 × 3.
  const GiNaC::matrix& hessian() const { return hessian_; }
  //! True iff E is a polynomial in x, y, z with rational coefficients (no Pi, no sqrt(2)).
  bool is_polynomial() const { return polynomial_; }
  //! Total degree of E when is_polynomial(), else -1.
  int degree() const { return degree_; }
  //! The text it was parsed from (or GiNaC's printing of E).
  const std::string& text() const { return text_; }

  //! E at a point, in double (GiNaC evalf; for tests and diagnostics only, not inner loops).
  //! NaN where E is not real or not defined (sqrt or log of a negative number, 1/0, log 0).
  double evaluate(const std::array<double, 3>& p) const;

 private:
  //! The constructor's division by a power of two (see there), once polynomial_ is known.
  void normalize_constant_factor(const GiNaC::ex& expanded);

  GiNaC::ex E_;
  int normalization_exponent_ = 0;
  std::array<GiNaC::ex, 3> gradient_;
  GiNaC::matrix hessian_{3, 3};
  bool polynomial_ = false;
  int degree_ = -1;
  std::string text_;
};

}  // namespace delmesh
