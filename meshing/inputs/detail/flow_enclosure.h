#pragma once
//! \file flow_enclosure.h
//! Interval enclosures of E, ∇E and the Hessian over boxes and over pieces of a triangle, shared
//! by the gradient-flow certificate (gradient_flow_certificate.h) and the flow distance bound
//! (flow_distance.h).  Every function that evaluates needs a live RoundingGuard.

#include <array>
#include <cmath>
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
double gradient_lower_bound(const Enclosure& en);

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
