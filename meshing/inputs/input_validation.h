#pragma once
//! \file input_validation.h
//! Checks made before meshing, each failing with InvalidInput and a clear message.  Every check
//! has a budget; none can hang.  (The third input condition, Σ non-empty in the box, is checked
//! by SampleTopology: no critical point in the height direction means no component of Σ, since a
//! compact component has a maximum.)
//!
//! ## Method
//! Both checks are exclusion proofs by interval subdivision (depth first, bisecting the widest
//! side), with the enclosures of CompiledSystem over {E, ∂xE, ∂yE, ∂zE}: on a box B it gives
//! enclosures E(B), ∇E(B) and, from its Jacobian, the Hessian H(B); at the centre c (a double
//! point of B) it gives E(c) and ∇E(c).  All interval work runs under a RoundingGuard.
//!
//! ## Why every dropped box is sound
//! Interval evaluation encloses (compiled_system.h): for every x ∈ B, E(x) ∈ E(B), ∇E(x) ∈ ∇E(B),
//! Hess E(x) ∈ H(B).  An enclosure with a NaN or infinite bound never drops a box
//! (certainly_nonzero() is false for it), and the mean-value forms below are used only when the
//! derivative enclosures they rely on are finite, i.e. when every operation of the compiled
//! derivative program is defined (log and sqrt of positive arguments, non-zero divisors) on B, so
//! that E is C² on B and the mean-value theorem applies along every segment [c, x] ⊂ B.
//! 1. *E excludes 0 on B* (validate_box_faces on a face rectangle, validate_regular on a box):
//!    E(x) lies in the natural enclosure E(B) and, by the mean-value theorem (ξ ∈ [c, x] ⊂ B),
//!    E(x) = E(c) + ⟨∇E(ξ), x − c⟩ ∈ E(c) + Σᵢ ∂ᵢE(B)(Bᵢ − cᵢ).  So E(x) lies in the
//!    intersection of the two enclosures; if it excludes 0, E has no zero on B (on a face, the
//!    sum runs over the two free coordinates only, the fixed one has Bᵢ − cᵢ = 0).
//! 2. *∇E ≠ 0 on B* (validate_regular): for a fixed vector g (any doubles; we take g ≈ ∇E(c), and
//!    also the three axis vectors), ⟨∇E(x), g⟩ ≠ 0 implies ∇E(x) ≠ 0.  ⟨∇E(x), g⟩ lies in the
//!    natural enclosure Σᵢ ∂ᵢE(B) gᵢ and, by the mean-value theorem applied to x ↦ ⟨∇E(x), g⟩
//!    (whose gradient is Hess E · g), in ⟨∇E(c), g⟩ + Σⱼ (Σᵢ H(B)ᵢⱼ gᵢ)(Bⱼ − cⱼ).  If their
//!    intersection excludes 0, ∇E has no zero on B (the cone of gradients over B stays in an open
//!    half-space), so B holds no point of Σ where ∇E = 0.
//! A box that is not dropped is bisected; the union of the dropped boxes is the whole domain when
//! the check passes, which proves the claim on every point of it.
//!
//! ## Budget
//! The regularity check examines boxes in rounds of tolerances::mesher_box_budget_global.  At the
//! end of a round the volume of the boxes not yet examined is measured; if it is smaller than at
//! the end of the round before (the round decided some of the domain), another round follows, up
//! to tolerances::validation_box_rounds rounds.  Surfaces of high degree, whose enclosures are
//! loose (a product of three tori, degree 12), need several rounds; a check that has stopped
//! deciding volume ends after one more.  Running out reports the rounds, the boxes left and the
//! share of the domain's volume they hold.
//!
//! ## Undecided boxes: "singular" only with a proof
//! A box narrower than tolerances::validation_min_box_relative_width (relative to the widest side
//! of the domain) that is not dropped is looked at for a singular point.  From the box's centre,
//! damped Gauss–Newton on (E, ∇E) = 0 reaches a point p; p must lie within one box width of the
//! box.  Then Krawczyk on ∇E = 0 is tried on boxes p ± r (tolerances::
//! singular_evidence_krawczyk_attempts radii, from the box width down by factors of 16):
//!  - it proves no zero of ∇E in p ± r: no singular point there (∇E(p) ≠ 0, however small);
//!  - it certifies a unique critical point x* of E in p ± r, refined to a tight box X: if E(X)
//!    excludes 0, x* is off Σ and there is no singular point in p ± r;
//!  - if E(X) contains 0 and is narrower than tolerances::singular_evidence_relative_residual times
//!    the scale of E, or (a degenerate critical point, e.g. two spheres touching, where Krawczyk
//!    cannot apply) |E(p)| and ‖∇E(p)‖∞ are below that fraction of their scales, E and ∇E could not
//!    be separated there, which is no proof.  A proof is then sought (tolerances::
//!    singular_proof_*): a rational point of the box near p or X at which E, ∂xE, ∂yE, ∂zE evaluate
//!    to exactly 0 in rational arithmetic (GiNaC, with the expression's exact rational constants),
//!    or, for a polynomial E, a non-constant common factor g of E and its three derivatives that
//!    takes both signs at rational points of the box (g has a zero on the segment between them, by
//!    the intermediate value theorem, and E and ∇E, multiples of g, vanish there).
//! Only a proof makes the surface "singular".  The scales are the largest |E| and ‖∇E‖∞ at the 27
//! points of the domain's 3 × 3 × 3 grid.  A box without a proof is not undecided yet: it is
//! bisected on down to tolerances::validation_deep_min_box_relative_width (below, within
//! tolerances::validation_deep_box_budget boxes).
//!
//! ## Escalation
//! The boxes still undecided are examined again by the same two exclusion tests over MPFI
//! intervals at tolerances::validation_mpfi_precisions_bits (the constants of E enclosed at that
//! precision, e.g. 1 + 10⁻¹⁷, which double precision rounds to 1), bisected while their double
//! midpoints split them, within tolerances::validation_mpfi_box_budget boxes.  What stays
//! undecided gets "cannot certify", with a point near the first undecided box and how small |∇E|
//! is there (its value at the point of smallest residual found, an upper bound on its minimum):
//! never "singular".  So two unit spheres 1e-6 apart validate, two spheres of radius 0.5 2e-10
//! apart in a box of size 2.6 get "cannot certify" (Krawczyk puts the critical point between them
//! off Σ), and so do two unit spheres 2·10⁻¹⁷ apart (which double precision makes touch).

#include <cstddef>

#include "symbolic/surface.h"

namespace delmesh {

//! Work done by validate_input.
struct [[nodiscard]] ValidationReport {
  double seconds = 0;              //!< wall-clock time of both checks (including compilation of E)
  std::size_t face_boxes = 0;      //!< rectangles examined by validate_box_faces (all six faces)
  std::size_t regular_boxes = 0;   //!< boxes examined by validate_regular
};

//! Certifies E ≠ 0 on each of the six faces of the box by interval subdivision of the face
//! (quadtree; natural and mean-value enclosures, see the file comment; depth at most
//! tolerances::box_face_max_depth, at most tolerances::mesher_box_budget_global rectangles per
//! face).  Throws InvalidInput naming the face if E changes sign (or vanishes) at the centres of
//! its rectangles — Σ meets the box boundary — or "cannot certify" if some rectangle stays
//! undecided.  Returns the number of rectangles examined.
std::size_t validate_box_faces(const Surface& surface, const Box3& box);

//! Certifies that ∇E does not vanish on Σ ∩ box: no zero of {E, ∂xE, ∂yE, ∂zE} in the box, by
//! the subdivision of the file comment (in rounds of tolerances::mesher_box_budget_global boxes
//! while each round decides volume, at most tolerances::validation_box_rounds of them).
//! Throws InvalidInput:
//!  - "the surface is singular: the gradient of E vanishes on it ..." with the proof (a rational
//!    point where E and ∇E are exactly 0, or a sign-changing common factor; file comment);
//!  - "cannot certify that the gradient of E is non-zero on the surface ..." when boxes stay
//!    undecided without a proof (also after the MPFI escalation) or the budget runs out; it names
//!    a point near the first undecided box and how small |∇E| is there.
//! Returns the number of boxes examined.
std::size_t validate_regular(const Surface& surface, const Box3& box);

//! Both checks above (faces first), timed.  Precondition: box.lo < box.hi componentwise.
//! Under a command's limits (common/run_limits.h: RunLimits::current()) every box or rectangle
//! of both checks tests them, and the check throws RunStopped once they have passed.
ValidationReport validate_input(const Surface& surface, const Box3& box);

}  // namespace delmesh
