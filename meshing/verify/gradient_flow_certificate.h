#pragma once
//! \file gradient_flow_certificate.h
//! The isotopy certificate of any closed triangle mesh M for Σ = {E = 0} ⊂ B, by the gradient
//! flow of E, with a certified two-sided Hausdorff bound.  Unlike the restricted-Delaunay
//! certificate (certificate.h) it does not ask M to be Tri S|Σ of its vertices: meshes from
//! other programs (marching cubes, CGAL Mesh_3) are certified on the same terms.
//!
//! ## The theorem
//! Let ε ≥ 0, ε′ > ε, T = {x ∈ B : |E(x)| ≤ ε′}, G > 0, and suppose
//!  (a) |E| > ε′ on the boundary of B;
//!  (b) |∇E| ≥ G on T (so ∇E ≠ 0 there);
//!  (c) M is a closed orientable 2-manifold (as a simplicial complex) with |E| ≤ ε on M;
//!  (d) every triangle τ of M, oriented consistently within its component, is transverse to ∇E:
//!      ⟨∇E(x), n_τ⟩ > 0 for every x ∈ τ (n_τ the normal (b − a) × (c − a) of τ = abc), after
//!      reversing every triangle of a component whose triangles all have ⟨∇E, n_τ⟩ < 0;
//!  (e) on Σ ∩ B a generic height function h(x) = ⟨x, d⟩ has finitely many critical points, all
//!      certified (SurfaceCritical, no undecided region), and through each critical point c a
//!      polygonal path γ_c is proved to start where E < −ε′, end where E > ε′, be crossed by E
//!      increasingly (⟨∇E, γ′⟩ > 0 along each segment), and meet M with algebraic intersection
//!      number 1.
//! Then M is ambient-isotopic to Σ ∩ B, and every point of M is within ε/G of Σ and every point
//! of Σ within ε/G of M (two-sided Hausdorff distance ≤ ε/G).
//!
//! Proof.  By (a) and (b), T is a compact region inside B on which ∇E ≠ 0; the normalised flow
//! φ (dx/ds = ∇E/|∇E|², so dE/ds = 1) carries {E = −ε′} onto {E = ε′}, and T ≅ Σ × [−ε′, ε′]
//! with every point of T on exactly one arc, each arc crossing Σ once (Morse theory without
//! critical points; Milnor, *Morse theory*, Thm. 3.1).  Let π : T → Σ slide each point along its
//! arc.  On a triangle τ of M, (d) makes π a local diffeomorphism that preserves orientation.
//! Across an edge shared by τ and τ′, both images keep their orientation, and the two triangles
//! run through the edge in opposite directions, so their images lie on the two sides of the
//! image of the edge: π is a local homeomorphism there.  At a vertex, the images of the
//! triangles around it wind w ≥ 1 times around its image.  So each component M_j of M is a
//! branched covering of one component Σ_i of Σ of some degree d_j ≥ 1 (M_j is compact and lies
//! in the component T_i of T that holds Σ_i), branched at most at vertices, and every arc of T_i
//! meets M_j in d_j points counted with sign, all crossings having sign +1 (d).  For a path γ in
//! T_i from {E = −ε′} to {E = ε′}, the algebraic intersection number with M_j equals d_j: γ is
//! homotopic to an arc with its ends kept on those two boundary components (each is connected,
//! ≅ Σ_i), and intersection numbers with the closed M_j ⊂ int T are invariant under such
//! homotopies.  The part of γ_c with |E| ≤ ε′ is such a path (E is monotone along γ_c), in the
//! component holding c, so (e) gives Σ_j d_j = 1 over the components of M above Σ_i: exactly one
//! component, of degree 1.  Every component of Σ has a critical point of h (it is compact), so
//! every Σ_i is reached, and every M_j lies above some Σ_i: π : M → Σ is a branched covering of
//! degree one on each component, hence a homeomorphism (a branch point of index w ≥ 2 would need
//! degree ≥ 2).  Each arc meets M exactly once, transversally; sliding along the arcs, with a
//! bump function in the flow parameter, is an ambient isotopy of B taking M onto Σ.  Along an
//! arc |dx/ds| = 1/|∇E| ≤ 1/G, and the point x ∈ M reaches Σ after |E(x)| ≤ ε units of s: its
//! distance to Σ is at most ε/G, and every point of Σ is that close to the one point of M on its
//! arc.  ∎
//!
//! ## The normalised function
//! Nothing above asks E to be the function that defines Σ in the catalog: any C² function F on
//! B with F = 0 exactly on Σ ∩ B, and with F and E of one sign on each side of Σ, serves, with
//! (a)–(e) stated for F (ε bounding |F| on M, T = {|F| ≤ ε′}, ∇F in (b), (d) and along the
//! paths), while the critical points of (e) stay those of the height function on Σ, which
//! depends on Σ alone.  When a condition that depends on the function is not proved with E, the
//! certificate tries F = E / sqrt(|∇E|² + η²), η > 0 (tolerances::flow_normalized_eta_relative
//! times the median of |∇E| over M's vertices): F is C² (the root's argument is at least η²),
//! vanishes exactly where E does, and has E's sign.  Near Σ, F is close to the signed distance
//! (|∇F| ≈ 1 where |∇E| ≫ η), so its tube has about the same width everywhere, where E's tube
//! is wide where |∇E| is small; and at a critical point c of E, |F(c)| = |E(c)|/η, so c lies in
//! F's tube only if |E(c)| ≤ ε′η.  The bounds are then distances along F's flow, ε_F/G_F.
//!
//! The enclosures of F and ∇F over the boxes of (a) and (b) are composed from those of E, ∇E and
//! E's Hessian (detail::NormalizedEnclosure, flow_enclosure.h, which states the formulas and why
//! they enclose; times 2^−k, exactly, where Surface stores F divided by 2^k), and met with the
//! natural and mean-value enclosures of F's own symbolic derivatives where the composed ones do
//! not decide a box.  F's tube proofs may examine tolerances::flow_normalized_box_budget boxes
//! per round, in up to tolerances::flow_normalized_box_rounds rounds: a round that leaves less
//! unexplored volume (the boxes still to examine) than there was when it began earns the next
//! (FlowCertificate::box_rounds counts them).  The budget bounds the time only; what is proved
//! does not depend on it.
//!
//! ## The one-sided tube
//! The theorem and its proof hold with T = {x ∈ B : a ≤ E(x) ≤ b} for any a < 0 < b in place of
//! {|E| ≤ ε′}: (a) asks E ∉ [a, b] on ∂B, (c) a < E < b on M (and still |E| ≤ ε there), and the
//! paths of (e) start where E < a and end where E > b.  In the proof the flow carries {E = a}
//! onto {E = b}, T ≅ Σ × [a, b], and the part of γ_c in T runs from {E = a} to {E = b}; nothing
//! else changes, the distance bound included (x ∈ M reaches Σ after |E(x)| ≤ ε units of s).  When
//! F's flow with ±ε′ leaves a condition that depends on the function and the tube unproved (not
//! the transversality of the triangles, which is the same with any tube), the certificate
//! tries F once more with a = f·ℓ and b = f·u, f = tolerances::flow_tube_factor, ℓ ≤ 0 ≤ u bounds
//! of min F and max F on M (b = the least positive double if u = 0, a likewise): a mesh whose
//! triangles lie on one side of Σ near a narrow gap (chords of the two spheres of near_sheets,
//! with vertices on Σ) needs a wide tube on that side only, while the other side stays clear of
//! the critical point of F in the gap.  The pieces of the triangles are then refined towards the
//! least and the greatest value met at their centres separately (see below).
//!
//! The bound for one triangle τ is e_τ/G with e_τ = max over τ of |E|, or the smaller bound of
//! flow_distance.h on τ where that one is proved: the arc from a point of τ to Σ is at most
//! e_τ/G long, so the lemma there applies within that radius, and within any radius it proves.
//! hausdorff_upper_bound is the largest triangle bound: every point of Σ lies on the arc of one
//! point of M.
//!
//! ## How each condition is proved
//! All enclosures are interval arithmetic (CompiledSystem over {E, ∂xE, ∂yE, ∂zE}, whose Jacobian
//! rows 1–3 are the Hessian) under a RoundingGuard; a NaN or infinite bound proves nothing.
//!  - (c): checked combinatorially (mesh_checker.h); the triangles are oriented consistently per
//!    component by walking across edges.  ε is the largest of the bounds below.
//!  - |E| on a triangle: τ is cut into pieces in its barycentric parameters (dyadic, so the pieces
//!    tile τ exactly); on a piece P with box X ⊇ P and centre c ∈ X, Taylor's theorem gives
//!    E(x) ∈ E(c) + ⟨∇E(c), x − c⟩ + ½ (x − c)ᵀ H(X) (x − c), the middle term affine in x and so
//!    bounded by its values at P's three corners (enclosed as intervals), the last by the interval
//!    Hessian over X; intersected with the natural enclosure E(X).
//!  - (d): ⟨∇E(x), N⟩ with N the interval enclosure of (b − a) × (c − a), over each piece's box
//!    (natural ∇E(X) and mean-value ∇E(c) + H(X)(X − c)).  A piece is cut in four, down to
//!    tolerances::flow_triangle_max_depth, while the sign is not decided or its bound of |E|
//!    exceeds tolerances::flow_epsilon_slack times the largest |E| met at a piece's centre (with
//!    the one-sided tube: while its upper bound of E exceeds the slack times max(0, the greatest
//!    E met) or its lower bound is below the slack times min(0, the least E met)).  ℓ and u are
//!    the least lower and the greatest upper bound of E over the pieces kept.
//!  - (a): each face of B is subdivided (flat boxes) until every rectangle's enclosure of E
//!    excludes [−ε′, ε′] (with the one-sided tube, [a, b]).
//!  - (b): B is subdivided as in input_validation.h: a box whose enclosure of E excludes
//!    [−ε′, ε′] (resp. [a, b]) holds no point of T and is dropped; otherwise, for g ≈ ∇E(c)/|∇E(c)| (then the
//!    axes), the enclosure of ⟨∇E, g⟩ over the box (natural ∩ mean value) with lower bound ℓ > 0
//!    gives |∇E| ≥ ℓ there.  A box is cut until ℓ ≥ tolerances::flow_gradient_quality · min(|∇E(c)|, m)
//!    (or it reaches the minimum width, where any ℓ > 0 is kept), m being the least |∇E| met so
//!    far at points of T (M's vertices, and the centres of the boxes examined where |E| ≤ ε′ is
//!    proved): a box where |∇E| is well above its least value on T need not be cut for a bound
//!    that could not lower G.  G is the least ℓ kept, whatever m is.
//!  - the distances: per triangle, the least of e_τ/G and the bounds of flow_distance.h within
//!    the radii e_τ/G and FlowCertificateOptions::distance_radius.
//!  - (e): the critical points come from the seed solve of meshing/inputs/seed_solve.h (certified, no
//!    undecided region; generic directions seeded by FlowCertificateOptions::seed).  The root box
//!    X_c must lie in T.  γ_c follows the flow from z, the root's midpoint, both ways: each
//!    segment starts along ±∇E at its first point (the first along g ≈ ∇E(z)/|∇E(z)|), its
//!    length starts at ε′/|∇E(z)| and doubles after a segment on whose boxes ⟨∇E, q − p⟩ > 0 is
//!    proved (halves after a failure), until an end has E > ε′ (resp. < −ε′; interval point
//!    values; with the one-sided tube b, a and first lengths b/|∇E(z)|, −a/|∇E(z)|).  The crossings of γ_c with the triangles are decided with exact orientation
//!    predicates; a path through an edge or a vertex of M, or with a joint in a triangle's
//!    plane, is replaced by one whose first direction is perturbed.
//! Each piece, box and path test also reads the options' interrupt flag and deadline.
//!
//! ## Status
//!  - certified: (a)–(e) proved; M is isotopic to Σ and within hausdorff_upper_bound of it;
//!  - refuted: a proof that M and Σ differ topologically: M is not a closed orientable 2-manifold
//!    while Σ is one (validate_input proves E ≠ 0 on ∂B and ∇E ≠ 0 on Σ), or Σ ∩ B is empty (no
//!    critical point of the height function, certified, with (a) proved) while M is not;
//!  - undecided: some condition could not be proved; `reason` names the first, `location` a
//!    point near it.  Not being Tri S|Σ of its vertices plays no part.

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/enum_names.h"
#include "meshing/core/surface_mesh.h"
#include "symbolic/surface.h"

namespace delmesh {

enum class FlowCertificateStatus { certified, refuted, undecided };
constexpr auto enum_names(FlowCertificateStatus) {
  return name_table<FlowCertificateStatus>("FlowCertificateStatus",
                                           {{FlowCertificateStatus::certified, "certified"},
                                            {FlowCertificateStatus::refuted, "refuted"},
                                            {FlowCertificateStatus::undecided, "undecided"}});
}
inline std::ostream& operator<<(std::ostream& out, FlowCertificateStatus status) { return write_enum(out, status); }

struct FlowCertificateOptions {
  std::uint64_t seed = 1;  //!< seeds the height directions of (e) and the paths' perturbations
  //! If given, the certificate stops at its next test after it becomes true (status undecided,
  //! `interrupted`).
  const std::atomic<bool>* interrupt = nullptr;
  //! If given, the certificate stops at its next test after it has passed (status undecided,
  //! `time_limited`); the seed solve gets it too.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  //! If positive, each triangle's distance bound is also tried by flow_distance.h within this
  //! radius (`delmesh mesh --max-distance` passes its δ, the radius its refinement proved).
  double distance_radius = 0;
  //! The caller has already run validate_input(surface, box) with success (the mesher, or
  //! certify_topology after the restricted-Delaunay certificate): it is not run again.  The
  //! proof still rests on that validation.
  bool surface_validated = false;
};

//! The function whose flow proved (or last failed to prove) the certificate.
enum class FlowFunction {
  E,          //!< E itself
  normalized  //!< F = E / sqrt(|∇E|² + η²) (file comment, "The normalised function")
};

struct [[nodiscard]] FlowCertificate {
  FlowCertificateStatus status = FlowCertificateStatus::undecided;
  std::string reason;                            //!< the first condition not proved (or the refutation)
  std::optional<std::array<double, 3>> location;  //!< a point near it
  bool interrupted = false;
  bool time_limited = false;

  FlowFunction function = FlowFunction::E;
  double eta = 0;              //!< η of the normalised function (0: it was not tried)
  std::string reason_with_E;   //!< why E's flow did not prove it, when the normalised one was tried
  double epsilon = 0;        //!< ε: the largest certified bound of |E| over the triangles
  double tube = 0;           //!< ε′ = tolerances::flow_tube_factor · ε (T's half-width in E)
  //! T = {tube_lower ≤ E ≤ tube_upper}: −ε′ and ε′, or with one_sided_tube the tube of "The
  //! one-sided tube" (file comment).
  double tube_lower = 0, tube_upper = 0;
  bool one_sided_tube = false;
  double min_gradient = 0;   //!< G: certified lower bound of |∇E| on T (0: not proved)
  //! The largest of triangle_distance_bounds (≤ ε/G) when certified, else infinity: the two-sided
  //! Hausdorff distance between M and Σ is at most this.
  double hausdorff_upper_bound = 0;
  double box_diagonal = 0;
  //! Per triangle of the soup (its index order): a bound on the distance from its points to Σ
  //! along the flow (see "The bound for one triangle" above); empty unless certified.
  std::vector<double> triangle_distance_bounds;

  std::size_t mesh_components = 0;
  std::size_t critical_points = 0;      //!< of the height function on Σ, each with its path counted
  std::size_t triangle_pieces = 0;      //!< pieces examined for (c) and (d)
  std::size_t boxes = 0;                //!< boxes and rectangles examined for (a) and (b)
  //! The rounds of tolerances::flow_normalized_box_budget boxes the normalised function's tube
  //! proofs began (0: it was not tried).
  std::size_t box_rounds = 0;
  double seconds = 0;
  std::uint64_t seed = 1;
};

//! The certificate of the triangle soup (points, triangles) for Σ = {E = 0} in `box` (see the
//! file comment).  Throws InvalidInput if an index is out of range, a triangle repeats an index,
//! a referenced point is not finite, the soup has no triangle, or Σ fails validate_input (not
//! strictly inside the box, or not certified smooth; input_validation.h).
FlowCertificate certify_gradient_flow(const std::vector<Point3>& points,
                                      const std::vector<std::array<std::size_t, 3>>& triangles,
                                      const Surface& surface, const Box3& box, const FlowCertificateOptions& options = {});

//! {status, reason, location, epsilon, tube, min_gradient, function ("E" or
//!  "E/sqrt(|grad E|^2+eta^2)"), eta, reason_with_E, hausdorff_upper_bound,
//!  hausdorff_relative (to the box diagonal), mesh_components, critical_points, triangle_pieces,
//!  tube_lower, tube_upper, one_sided_tube, boxes, box_rounds, interrupted, time_limited, seed,
//!  seconds}; with `per_triangle`, also
//!  triangle_distance_bounds.
nlohmann::json to_json(const FlowCertificate& certificate, bool per_triangle = false);

}  // namespace delmesh
