#pragma once
//! \file flow_enclosure.h
//! Interval enclosures of E, ∇E and the Hessian over boxes and over pieces of a triangle, shared
//! by the gradient-flow certificate (gradient_flow_certificate.h) and the flow distance bound
//! (flow_distance.h).  Every function that evaluates needs a live RoundingGuard.

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "symbolic/compiled_system.h"
#include "symbolic/scalar_traits.h"

namespace delmesh::detail {

using P3 = std::array<double, 3>;
using IBox = std::array<Interval, 3>;

//! Both bounds finite.
inline bool finite(const Interval& a) { return std::isfinite(a.inf()) && std::isfinite(a.sup()); }
//! The intersection of two enclosures of one number (the first if it is the only finite one, or
//! if they are disjoint, which rounding alone cannot cause).
Interval meet(const Interval& a, const Interval& b);
//! The largest |x| over an enclosure (infinity for a non-finite one).
double magnitude(const Interval& a);
//! A point of the box near its centre (inside it despite rounding).
P3 centre_of(const IBox& x);
//! The widest side of the box.
double width_of(const IBox& x);
inline IBox interval_point(const P3& p) { return {Interval(p[0]), Interval(p[1]), Interval(p[2])}; }

//! The system {E, ∂xE, ∂yE, ∂zE} over (x, y, z), whose Jacobian rows 1–3 are the Hessian of E.
CompiledSystem compile_value_and_gradient(const GiNaC::ex& E, const std::array<GiNaC::ex, 3>& gradient);

//! {E, ∂xE, ∂yE, ∂zE} of compile_value_and_gradient over a box X and at its centre c: E(X),
//! ∇E(X), H(X) (Jacobian rows 1–3), E(c), ∇E(c), and X − c.
struct Enclosure {
  Interval v[4], j[12], vc[4];
  IBox d;
  P3 c{};
  bool c2 = false;  //!< every enclosure finite: E is C² on X and the Taylor forms apply

  Enclosure(const CompiledSystem& system, const IBox& x);
  Interval hessian(int i, int k) const { return j[3 * (1 + i) + k]; }
  //! E over X: the natural enclosure met with the mean-value form.
  Interval value() const;
  //! ⟨∇E(x), w⟩ over X for a vector w (enclosed): natural met with mean value.
  Interval directional(const IBox& w) const;
  //! E over the convex hull of `corners` ⊆ X: the natural enclosure E(X) met with the Taylor
  //! form at c, E(c) + ⟨∇E(c), x − c⟩ + ½ (x − c)ᵀ H(X) (x − c), whose affine term is bounded by
  //! its values at the corners.
  Interval value_on_hull(const std::array<IBox, 3>& corners) const;
};

//! A lower bound of |∇E| over the enclosure's box (0 if none is proved): |⟨∇E, g⟩|/‖g‖ for
//! g ≈ ∇E(c) and for the three axes.
double gradient_lower_bound(const Enclosure& en, double enough = std::numeric_limits<double>::infinity());

//! F = E / sqrt(|∇E|² + η²) (η > 0) and ⟨∇F, w⟩ over a box X, composed from an Enclosure of E's
//! system (E, ∇E and the Hessian H of E over X and at its centre c) instead of F's own symbolic
//! derivatives:
//!   F = E s,  s = (|∇E|² + η²)^(−1/2),  ∂s/∂x_i = −s³ (H∇E)_i,  ∇F = s ∇E − E s³ H∇E.
//! ∇E over X is the natural enclosure met with the mean-value form ∇E(c) + H(X)(X − c); each
//! factor then holds the value at every x ∈ X, so the products do.  In ⟨∇F, w⟩ the term
//! s⟨∇E, w⟩ = a / sqrt(a²/|w|² + b), with a = ⟨∇E, w⟩ and b = |∇E − (a/|w|²) w|² + η² ≥ η², is
//! increasing in a and, for a of one sign, monotone in b (decreasing for a > 0, increasing for
//! a < 0): its range over the box of (a, b) is spanned by the two corners (a_lo, b_hi or b_lo)
//! and (a_hi, b_lo or b_hi), each evaluated in interval arithmetic over |w|²; that range is met
//! with the product s·a.
struct NormalizedEnclosure {
  double eta = 0;
  Enclosure e;          //!< E's system over X
  IBox gradient;        //!< ∇E over X
  Interval s;           //!< (|∇E|² + η²)^(−1/2) over X
  Interval s_centre;    //!< the same at c
  bool usable = false;  //!< η > 0 and every enclosure finite (else the functions below return the whole line)

  //! Precondition: a live RoundingGuard.
  NormalizedEnclosure(const CompiledSystem& system_of_E, const IBox& x, double eta);
  //! F over X.
  Interval value() const;
  //! F(c).
  Interval value_at_centre() const;
  //! ⟨∇F(x), w⟩ over X for a vector w (enclosed).
  Interval directional(const IBox& w) const;
  //! ∇F(c) in floating point (a direction, not a bound; 0 where not finite), from the system this
  //! enclosure was made from.
  P3 centre_gradient(const CompiledSystem& system_of_E) const;
};

//! A lower bound of |∇F| over the box (0 if none is proved): |⟨∇F, w⟩|/‖w‖ for w = g (g ≈ ∇F(c),
//! when not 0) and for the three axes.
double gradient_lower_bound(const NormalizedEnclosure& en, const P3& g,
                            double enough = std::numeric_limits<double>::infinity());

//! A piece of a triangle abc in its barycentric parameters (u, v), x = a + u (b − a) + v (c − a):
//! corners dyadic, so the four children of a piece tile it exactly.
struct TrianglePiece {
  std::array<std::array<double, 2>, 3> uv{{{0, 0}, {1, 0}, {0, 1}}};
  int depth = 0;
  //! The four children by the midpoints of the sides, each at depth + 1.
  std::array<TrianglePiece, 4> children() const;
};

//! A triangle abc prepared for enclosures of its pieces.
class EnclosedTriangle {
 public:
  EnclosedTriangle(const P3& a, const P3& b, const P3& c);
  //! The corners of `piece` (enclosed) and their bounding box.
  void corners(const TrianglePiece& piece, std::array<IBox, 3>& corner, IBox& box) const;
  //! An enclosure of (b − a) × (c − a).
  const IBox& normal() const { return normal_; }

 private:
  IBox a_, ab_, ac_, normal_;
};

//! E at the centroid of the enclosed corners (the midpoints of the enclosures), in floating point:
//! a value E takes on the piece up to rounding, for adaptive tolerances (not a bound).
double centroid_value(const CompiledSystem& system, const std::array<IBox, 3>& corner);

}  // namespace delmesh::detail
