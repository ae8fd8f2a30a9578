#pragma once
//! \file flow_distance.h
//! A certified bound on how far the points of one triangle are from Σ = {E = 0}, measured along
//! the flow of ∇E: the per-triangle distance of `delmesh mesh --max-distance` (quality.h,
//! distance_witness) and of the gradient-flow certificate's Hausdorff bound
//! (gradient_flow_certificate.h).
//!
//! ## The lemma
//! Let τ be a triangle, r > 0, N the box of τ grown by r on every side, e ≥ max over τ of |E|
//! and g > 0 with |∇E| ≥ g on N (E C¹ there).  If e ≤ g·r, then from every x ∈ τ the curve of
//! steepest descent of |E|, dx/dσ = −sign(E(x)) ∇E/|∇E| (unit speed), reaches Σ after a length
//! of at most |E(x)|/g ≤ e/g; so d(x, Σ) ≤ e/g.
//!
//! Proof.  While the curve stays in N, d|E|/dσ = −|∇E| ≤ −g, so |E| falls to 0 by σ = |E(x)|/g
//! ≤ e/g ≤ r (until then E keeps its sign and ∇E ≠ 0, so the curve is defined).  The point at
//! length σ is within σ of x ∈ τ, hence in N while σ ≤ r: the curve cannot leave N before it
//! meets Σ.  ∎
//!
//! The curve is an arc of the normalised flow of gradient_flow_certificate.h, parametrised by
//! length.  Where that certificate proves that each arc of its tube meets the mesh M exactly
//! once, every point of Σ is reached by the arc of one point of M, so the largest bound over
//! M's triangles bounds the two-sided Hausdorff distance.  Alone, the lemma bounds only the
//! distance from the triangle to Σ.
//!
//! ## How it is computed
//! Under a RoundingGuard: g by gradient_lower_bound (detail/flow_enclosure.h) on N, bisected down
//! to tolerances::flow_distance_gradient_depth levels while the bound fails, the least over the
//! boxes; e over dyadic pieces of τ in its barycentric parameters (Taylor forms, as in the
//! certificate), a piece cut in four while its bound exceeds g·r, down to
//! tolerances::flow_triangle_max_depth.  A piece whose centroid value already exceeds g·r ends
//! the attempt (no bound).  Every bound is rounded up.

#include <array>

#include "common/vec3.h"
#include "symbolic/compiled_system.h"
#include "symbolic/surface.h"

namespace delmesh {

//! The answer for one triangle and radius.
struct TriangleDistance {
  bool proved = false;        //!< e ≤ g·r was proved
  double value_bound = 0;     //!< e: bound of |E| on the triangle (when proved)
  double gradient_bound = 0;  //!< g: lower bound of |∇E| on N (0: none proved)
  double distance = 0;        //!< min(e/g rounded up, r) when proved; else +∞
};

//! Bounds per the lemma above for the surface {E = 0} it was made from.  Evaluation is const and
//! may run on several threads at once.
class FlowDistance {
 public:
  explicit FlowDistance(const Surface& surface);

  //! The bound for the triangle abc within radius r.  Precondition: r > 0 and finite (else
  //! PreconditionViolation).  Not proved (distance +∞) when E or ∇E cannot be enclosed on N,
  //! |∇E| is not bounded away from 0 there, or |E| on the triangle is not proved ≤ g·r.
  TriangleDistance bound(const Vec3& a, const Vec3& b, const Vec3& c, double radius) const;

  //! The compiled {E, ∂xE, ∂yE, ∂zE} (detail/flow_enclosure.h), for other enclosures of the
  //! same surface.
  const CompiledSystem& system() const { return system_; }

 private:
  CompiledSystem system_;
};

}  // namespace delmesh
