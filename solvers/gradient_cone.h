#pragma once
//! \file gradient_cone.h
//! A cheap certificate that a linear functional of the gradient does not vanish on the part of a
//! surface inside a polytope:
//!
//!     prove  ⟨∇E(x), w⟩ ≠ 0  for every x ∈ Σ ∩ P,   Σ = {E = 0},
//!
//! where P is a convex polytope (solvers/domain.h) in chart coordinates u ∈ ℝⁿ (n = 2 or 3) and
//! x = origin + Σ_j u_j c_j is an affine chart into ℝ³ (a Voronoi facet in its plane frame, or a
//! Voronoi cell with the identity chart).
//!
//! Method.  Subdivide P's bounding box; a box U (in interval arithmetic, X its world enclosure) is
//! dropped when
//!  (i)   it lies outside P (classify() proves it), or
//!  (ii)  0 ∉ E(X) ∩ [E(c) + Σ_j ⟨∇E(X), c_j⟩ (U_j − u_c,j)]  (natural and mean-value forms,
//!        c the box centre): then U contains no point of Σ, or
//!  (iii) 0 ∉ ⟨∇E(X), w⟩: then the functional is non-zero on all of U; or, when E was compiled
//!        with Hessians and (ii) did not drop U, 0 ∉ ⟨∇E(c), w⟩ + Σ_j ⟨H(X) w, c_j⟩ (U_j − u_c,j)
//!        (the functional's mean-value form: its gradient is H w, and X holds the segment from
//!        c to every point of U).
//! (A half of a box that classify() proved inside P is inside P: (i) is not tested again on it;
//! nor, on a half, a half-space proved to contain the whole box strictly: classify()'s mask.)
//! A box that none of these drops is bisected across the side j along which E varies most on it,
//! the largest (width of U_j)·max|⟨∇E(X), c_j⟩| (the maximal-smear rule of interval subdivision:
//! near Σ that is the side across the surface, so E's sign separates the halves soonest); when the
//! budget or the depth runs out the certificate fails.  The boxes are examined depth first, and of
//! the two halves of a box the one holding c + δ comes first, where c is the box's centre and δ
//! the least-norm solution of the linearisation at c of f = (E, ⟨∇E, w⟩) (below): when the
//! attempt is refuted by (iv), the box that refutes it is then usually reached after a few boxes
//! instead of after the subtrees before it.  (The rule and the order only order the work: any
//! bisection gives a cover, so the proof below depends on neither.  A proof examines the same
//! boxes in any order, but for the halves of SlopeRefinement, whose budget goes to the boxes met
//! first.)  It also fails at once, refuted, when
//!  (iv)  on a box U that (i)–(iii) keep (E compiled with Hessians), the Krawczyk operator of
//!        f = (E, ⟨∇E, w⟩) — on U itself in dimension 2, on the slice of U through its centre
//!        across one coordinate in dimension 3 — maps the box of the unknowns into its interior,
//!        and U or the image box is proved inside P: then f has a zero x* ∈ P, a point of Σ ∩ P
//!        where the functional vanishes; every box holding x* fails (ii) and (iii) whatever the
//!        subdivision, so no budget could give a proof, and (iv) only saves the boxes a hopeless
//!        attempt would spend.
//! Proof of a certificate: every point of Σ ∩ P lies in some box of the final
//! cover that was not dropped by (i) or (ii), i.e. one dropped by (iii), where the functional is
//! non-zero.  Each test is a rigorous interval enclosure (a RoundingGuard is taken), so `proved`
//! is a proof; a failure proves nothing and the caller must solve the full system.
//!
//! Uses by the mesher (each a sufficient condition for its check to find no witness):
//!  - Silhouette (Lemma 4.14): w = n_p over V_p proves J_{n_p} ∩ V_p = ∅, which is what
//!    SilhouetteCritical and SilhouettePlane look for.
//!  - FacetContact and FacetCycle on a facet F with unit normal m: for w ⟂ m, ⟨∇E, w⟩ ≠ 0 on
//!    Σ ∩ F proves (a) ∇E ∦ m there, so Σ touches the plane nowhere in F (no SurfacePlaneContact
//!    point), and (b) with d = w × m, the tangent t = ∇E × m of the curve Σ ∩ Π satisfies
//!    ⟨t, d⟩ = ⟨∇E, m × d⟩ = ⟨∇E, w⟩ ≠ 0, so the curve has no critical point in direction d
//!    inside F: FacetCycle in direction d has no critical point to shoot a line from, and no
//!    closed curve of Σ ∩ Π lies in F (it would have one).
//!
//! Slope.  A proof also bounds the angle between ∇E and the line of w: on a box dropped by (iii),
//! with Φ ∌ 0 the enclosure of the functional that decided and G an enclosure of ∇E (natural, or
//! the centred form met with it), every x in the box has |⟨∇E(x), w⟩| ≥ ρ_U |∇E(x)| with ρ_U
//! (rounded down) the larger of
//!  - min |Φ| / max |G|: |⟨∇E(x), w⟩| ≥ min |Φ| and |∇E(x)| ≤ max |G| (the Euclidean norm of the
//!    componentwise maxima);
//!  - |w| α / √(α² + τ²), α = min |Φ| and τ the norm of the componentwise maxima of G × w: with θ
//!    the angle between g = ∇E(x) and the line of w, |g × w| = |g| |w| sin θ ≤ τ and
//!    |⟨g, w⟩| = |g| |w| cos θ ≥ α, so tan θ ≤ τ / α and |⟨g, w⟩| / |g| = |w| cos θ ≥ the bound.
//!    It bounds the direction of ∇E only; the first also pays for the variation of |∇E| over the
//!    box, which can make it small however well ∇E keeps its direction.
//! As every point of Σ ∩ P lies in such a box, the least ρ_U over them, the
//! slope ρ, satisfies |⟨∇E(x), w⟩| ≥ ρ |∇E(x)| > 0 on all of Σ ∩ P (ρ = +∞ if no box needed (iii):
//! then Σ ∩ P = ∅).
//!
//! What a slope gives (used by the mesher to certify the facets of a certified cell): let P hold a
//! convex set F in a plane Π with normal vector M, and |⟨w, M⟩| / |M| < ρ.  Then
//! w′ = w − (⟨w, M⟩ / |M|²) M is parallel to Π and, for x ∈ Σ ∩ F and g = ∇E(x),
//!     |⟨g, w′⟩| ≥ |⟨g, w⟩| − (|⟨w, M⟩| / |M|) · |⟨g, M⟩| / |M| ≥ (ρ − |⟨w, M⟩| / |M|) |g| > 0
//! (g ≠ 0 because ⟨g, w⟩ ≠ 0), i.e. the certificate of F with the in-plane direction w′ holds:
//! the conclusions (a) and (b) above for FacetContact and FacetCycle follow without a cover of F.

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "solvers/domain.h"
#include "symbolic/compiled_system.h"

namespace delmesh {

//! x = origin + Σ_j u_j columns[j], j < columns.size() = the domain's dimension.
struct AffineChart {
  std::array<double, 3> origin{};
  std::vector<std::array<double, 3>> columns;
  //! The identity chart of ℝ³.
  static AffineChart identity();
};

struct GradientConeResult {
  bool proved = false;     //!< ⟨∇E, w⟩ ≠ 0 on Σ ∩ P is proved
  std::size_t boxes = 0;   //!< boxes examined
  //! Set when the attempt is refuted: not proved because a point x* of Σ ∩ P where ⟨∇E, w⟩ = 0
  //! was proved to exist (test (iv)).  It holds x* to the rounding of its enclosure: the box of
  //! (iv) that holds x* is narrowed by Krawczyk steps (each replaces the box Y by K(Y) ∩ Y, which
  //! still holds x*) until it stops shrinking, at most tolerances::vanishing_point_narrowing_steps
  //! times; this is the world image of its centre, so it lies within that box's extent of x*.
  std::optional<std::array<double, 3>> vanishing_point;
  //! Not proved because test (iv) proved a point of Σ ∩ P where ⟨∇E, w⟩ = 0 (vanishing_point).
  bool refuted() const { return vanishing_point.has_value(); }
  //! When proved and a slope was asked for (SlopeRefinement::target > 0): the slope ρ of the file
  //! comment, |⟨∇E, w⟩| ≥ ρ |∇E| on Σ ∩ P (+∞ when Σ ∩ P is proved empty); 0 otherwise.
  double slope = 0;
  //! When proved: a box [surface_lo, surface_hi] in world coordinates that holds Σ ∩ P, the
  //! bounding box of the world enclosures of the boxes of the final cover that (i) and (ii) did
  //! not drop (every point of Σ ∩ P lies in one: the proof above).  Empty (surface_lo[k] >
  //! surface_hi[k] for every k) when there is none, i.e. Σ ∩ P = ∅ is proved.
  std::array<double, 3> surface_lo{}, surface_hi{};
  //! When proved: +1 if ⟨∇E, w⟩ > 0 on all of Σ ∩ P, −1 if < 0 there, 0 if neither is proved
  //! (the boxes that (iii) dropped did not all give the functional the same sign, or there were
  //! none).  The sign is that of the enclosure that decided (iii) on each box; every point of
  //! Σ ∩ P lies in such a box (the proof above), so a common sign is the functional's sign on Σ ∩ P.
  int orientation = 0;
};

//! The slope, if asked for (target > 0), and extra subdivision to raise it: a box that (iii)
//! drops with ρ_U < target gets a second bound from the mean-value forms of ∇E and of the
//! functional (when E has Hessians), and if that is still below target it is bisected instead, as
//! long as at most box_budget such halves are made in all.  The halves do not use the
//! certificate's own budget and cannot fail: each lies in a box that (iii) dropped, whose bound
//! stands for a half that no test drops.  So refining never turns a proof into a failure.
struct SlopeRefinement {
  double target = 0;
  std::size_t box_budget = 0;
};

//! Tries to prove ⟨∇E, w⟩ ≠ 0 on Σ ∩ P (see the file comment).  `E` has one equation E in the
//! unknowns (x, y, z) and no parameters; its Jacobian is ∇E.  Throws PreconditionViolation if
//! the chart's columns do not match domain.dimension() or E is not of that shape.
GradientConeResult prove_gradient_cone(const CompiledSystem& E, const AffineChart& chart, const Domain& domain,
                                       const std::array<double, 3>& w, std::size_t box_budget,
                                       const SlopeRefinement& refinement = {});

//! The sign of ⟨∇E(x), w⟩ on the whole segment [a, b], proved by one interval evaluation over
//! the segment's bounding box: +1 or −1, or 0 if the enclosure contains 0 (nothing proved).  A
//! non-zero sign also proves that E is strictly monotone along the segment when w ∥ b − a, so
//! E has at most one zero on it.  Same precondition on E as prove_gradient_cone().
int gradient_functional_sign(const CompiledSystem& E, const std::array<double, 3>& a, const std::array<double, 3>& b,
                             const std::array<double, 3>& w);

//! The sign of E on the box [lo, hi] (lo = hi: at a point), proved by one interval evaluation:
//! +1 or −1, or 0 if the enclosure contains 0 (at a point: E(x) is zero up to the rounding of
//! its evaluation).  A non-zero sign proves that Σ does not meet the box.
int value_sign(const CompiledSystem& E, const std::array<double, 3>& lo, const std::array<double, 3>& hi);

}  // namespace delmesh
