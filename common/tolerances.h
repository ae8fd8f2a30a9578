#pragma once
//! \file tolerances.h
//! Every numerical tolerance of delmesh lives here; there are no magic epsilons elsewhere.
//! Certified answers never depend on these values for their correctness, only for how much work
//! is done before a region is reported as undecided.

#include <array>
#include <cstddef>
#include <limits>

namespace delmesh::tolerances {

//! A box whose widest side is below this (relative to the domain's widest side) is not bisected
//! further by the subdivision solvers; it is reported undecided unless it was certified.
inline constexpr double min_box_relative_width = 1e-12;

//! Default maximum number of boxes one subdivision solve may visit before it stops with
//! status box_limit (the remaining boxes are returned as undecided).
inline constexpr std::size_t default_box_budget = 200000;

//! MPFI precisions (bits) tried, in order, when double intervals cannot decide a box.
inline constexpr int escalation_precisions[] = {106, 212};

//! Homotopy continuation: smallest step in the path parameter before a path is declared failed.
inline constexpr double homotopy_min_step = 1e-14;

//! Homotopy continuation: a solution whose largest imaginary part is below this is a candidate
//! real root (it is then certified by Krawczyk over the reals, so this only filters candidates).
inline constexpr double homotopy_real_candidate = 1e-6;


// ---- homotopy continuation (solvers/homotopy_solver.cpp, solvers/detail/homotopy_tracker.cpp) ----

//! Homotopy: first step in the path parameter s ∈ [0, 1], and the largest step allowed.
inline constexpr double homotopy_initial_step = 1e-2;
inline constexpr double homotopy_max_step = 1e-1;
//! Homotopy step control: after this many accepted steps in a row the step doubles (up to the
//! largest step); a rejected step halves it.
inline constexpr int homotopy_step_growth_successes = 2;
//! Homotopy: paths re-tracked because one may have jumped take steps (first and largest) and a
//! corrector trust region this many times smaller, and homotopy_retrack_step_budget_factor times
//! the step budget.
inline constexpr double homotopy_retrack_step_divisor = 10;
inline constexpr std::size_t homotopy_retrack_step_budget_factor = 4;
//! Homotopy Newton iterations (on f at an endpoint, and the real polish): from this many steps on,
//! a correction larger than the one before means the round-off level is reached, and they stop.
inline constexpr int homotopy_newton_noise_after_steps = 3;

//! Homotopy corrector: Newton corrections must fall below this (relative to 1 + ‖u‖∞) within
//! homotopy_corrector_iterations iterations, else the step is rejected and halved.
inline constexpr double homotopy_corrector_tolerance = 1e-8;
inline constexpr int homotopy_corrector_iterations = 3;
//! Homotopy corrector: the first Newton correction after a predictor step may not exceed this
//! (relative to 1 + ‖u‖∞); a larger one means the step was too long (guards against path jumping).
inline constexpr double homotopy_corrector_trust = 1e-3;

//! Homotopy endgame: a path whose ‖u‖∞ exceeds this (|X_0| ‖X‖∞⁻¹ below its inverse) at a point of
//! the endgame (s ≥ homotopy_endgame_start), or whose endgame estimate does, goes to a solution at
//! infinity (diverging); a path whose step underflows before homotopy_endgame_start has failed
//! (and makes the solve undecided).
inline constexpr double homotopy_divergence_norm = 1e8;
inline constexpr double homotopy_endgame_start = 0.9;

//! Homotopy endpoint: a finite endpoint whose Jacobian condition number (2-norm) exceeds this is
//! singular; it comes back undecided (singular_root) when it lies in the domain.
inline constexpr double homotopy_singular_condition = 1e10;
//! Homotopy endpoint: a well-conditioned endpoint is a zero of f only if the Newton correction
//! J_f(u)⁻¹ f(u) there, after Newton's refinement, is at most this (relative to 1 + ‖u‖∞); else
//! the path has failed.  Far below homotopy_near_real, so that an endpoint dropped as not real is
//! not real; at a regular zero the correction is round-off, of the order of the condition number
//! times the machine epsilon (about 1e-11 at condition 4e8).
inline constexpr double homotopy_endpoint_newton_step = 1e-6;
//! Homotopy endpoint: Newton on f from an endpoint estimate takes at most this many steps (a
//! regular zero converges quadratically, a singular one only linearly), and stops before a step
//! that would carry the point farther than homotopy_endpoint_newton_travel (relative to 1 + ‖u‖∞)
//! from the estimate: farther is not this path's end.
inline constexpr int homotopy_endpoint_newton_iterations = 60;
inline constexpr double homotopy_endpoint_newton_travel = 1e-3;
//! Half-width (relative to 1 + ‖u‖∞) of the undecided box reported around a singular endpoint.
inline constexpr double homotopy_singular_box_radius = 1e-5;
//! Homotopy endpoint: a singular endpoint estimate u (the endgame's loops closed after c > 1 turns,
//! or J_f is ill conditioned at u) is a zero of f only if ‖f(u)‖∞ ≤ this · (1 + ‖u‖∞) · ‖J_f(u)‖∞;
//! else the path has failed.  Within δ of a zero z, f(u) = J_f(u)(u − z) + O(δ²) and the ratio
//! ‖f‖/‖J_f‖ is about δ or less (δ/m at an m-fold root in one variable), so every estimate accurate
//! to this passes; and ‖f‖/‖J_f‖ ≤ ‖J_f⁻¹ f‖, so it is the Newton correction's lower bound, which
//! unlike the correction stays meaningful where J_f is singular.  The same level as
//! homotopy_endpoint_newton_step, far below homotopy_near_real: a singular endpoint dropped as not
//! real is then an approximate zero that far from the reals.
inline constexpr double homotopy_singular_endpoint_residual = 1e-6;
//! Homotopy Newton iterations stop once a correction is at most this many machine epsilons
//! relative to the point: on f in the affine chart and in the real polish before certification
//! (homotopy_newton_converged_ulps), and on H(·, t) when a sample of the endgame is refined
//! (homotopy_refine_converged_ulps, at most homotopy_refine_iterations steps: the corrector has
//! already converged to its own tolerance).  A loop of the endgame has also closed when its end is
//! within homotopy_loop_closure_ulps machine epsilons (relative) of its start, whatever the spacing
//! of its samples.
inline constexpr double homotopy_newton_converged_ulps = 4;
inline constexpr double homotopy_refine_converged_ulps = 16;
inline constexpr int homotopy_refine_iterations = 2;
inline constexpr double homotopy_loop_closure_ulps = 64;
//! Homotopy certification: the real Newton polish of an endpoint takes at most this many steps
//! (it starts at a point accurate to the endgame's tolerance, so a few quadratic steps suffice).
inline constexpr int homotopy_polish_iterations = 12;
//! Homotopy certification: Krawczyk iteration contracts a certified box at most this many times.
inline constexpr int homotopy_contract_iterations = 8;
//! Homotopy: a box built around an estimate whose last Newton correction (or endgame accuracy) is c
//! has half-width at least this · c, so that the zero the correction points to lies well inside.
inline constexpr double homotopy_correction_box_factor = 16;

//! Homotopy: two regular endpoints closer than this (relative to 1 + ‖u‖∞) mean that a path
//! jumped; the paths are re-tracked with smaller steps.
inline constexpr double homotopy_duplicate_endpoint = 1e-8;

//! Homotopy certification: Krawczyk boxes around a polished real endpoint start at this
//! half-width (relative to 1 + ‖u‖∞) and grow by homotopy_certify_growth, at most
//! homotopy_certify_attempts times.
inline constexpr double homotopy_certify_radius = 1e-10;
inline constexpr double homotopy_certify_growth = 100;
inline constexpr int homotopy_certify_attempts = 4;

//! Homotopy: real endpoints within this margin (relative to the domain's widest side) outside the
//! domain box are still certified and classified (they may straddle a face).
inline constexpr double homotopy_domain_margin = 1e-6;

//! Homotopy: an endpoint whose largest imaginary part lies above homotopy_real_candidate but not
//! above this (relative to 1 + ‖u‖∞) is near-real: it may be a real root computed with that error
//! (a regular endpoint may have a Jacobian condition number up to homotopy_singular_condition, so
//! an error of 1e10 · 2.2e-16 ≈ 2e-6 is possible), or a non-real root that close to the reals (then
//! the real Jacobian is nearly singular there: a near-tangency).  It comes back undecided unless
//! Krawczyk decides the box of half-width homotopy_near_real_box_ratio · ‖Im u‖∞ around Re u.
inline constexpr double homotopy_near_real = 1e-4;
inline constexpr double homotopy_near_real_box_ratio = 4;

//! Homotopy: a diverging path whose last tracked point u lies within this distance (relative to
//! the domain's widest side) of the domain box — Re u within it of the box, ‖Im u‖∞ at most it —
//! makes the solve undecided: the numerical test for a path at infinity (|X_0| small, or
//! valuation estimates) may have taken a path to a finite root there for a diverging one.
inline constexpr double homotopy_diverging_near_domain = 1;

//! Certificate of a homotopy solve (solvers/homotopy_certificate.h).  The barrier is proved for
//! t_e = homotopy_barrier_t.  Each piece of the domain's box gets the barrier box that extends it
//! by μ = m · (its widest side) for the first m of homotopy_barrier_margins whose boundary stays
//! homotopy_barrier_clearance · μ (∞-norm on R^{2n}) away from every proposed zero of f (else the
//! m of largest clearance); its faces are bisected until proved or homotopy_barrier_piece_budget
//! boxes were evaluated; a piece not proved is bisected, up to homotopy_barrier_max_pieces pieces
//! and homotopy_barrier_box_budget face boxes in all.
inline constexpr double homotopy_barrier_t = 1e-3;
inline constexpr std::array<double, 7> homotopy_barrier_margins = {0.25, 0.125, 0.5, 0.0625, 1.0, 0.03125, 0.015625};
inline constexpr double homotopy_barrier_clearance = 0.25;
inline constexpr std::size_t homotopy_barrier_piece_budget = 1000;
inline constexpr std::size_t homotopy_barrier_max_pieces = 256;
inline constexpr std::size_t homotopy_barrier_box_budget = 30000;

//! Homotopy: the most predictor–corrector steps one path may take before it is declared failed.
inline constexpr std::size_t homotopy_max_steps_per_path = 20000;

//! Homotopy Cauchy endgame (solvers/detail/homotopy_tracker.h), from t = 1 − homotopy_endgame_start:
//! loops |t| = t_k with homotopy_endgame_samples samples each (the trapezoid rule's error is
//! O(t_k^samples)), t_{k+1} = homotopy_endgame_ratio · t_k; the endpoint estimate is accepted when two
//! successive estimates agree to homotopy_endgame_tolerance (relative, max norm of the projective
//! point); a path that needs more than homotopy_endgame_max_winding loops to close up, or that has
//! not converged when t_k would fall below homotopy_endgame_min_t, has failed.  A loop has closed
//! when its end is within homotopy_endgame_closure times the smallest distance between two successive
//! samples of its start (an unclosed loop ends on another branch, about a sample spacing away or more).
inline constexpr int homotopy_endgame_samples = 8;
inline constexpr double homotopy_endgame_ratio = 0.5;
inline constexpr double homotopy_endgame_tolerance = 1e-10;
inline constexpr int homotopy_endgame_max_winding = 16;
inline constexpr double homotopy_endgame_min_t = 1e-12;
inline constexpr double homotopy_endgame_closure = 0.1;
//! Homotopy endgame, valuations ν_j = lim t X_j'/X_j of the homogeneous coordinates (X_j ~ t^{ν_j}),
//! estimated at each t_k and shifted so that the smallest is 0: the loops start once no estimate
//! changed by more than homotopy_endgame_valuation_stable from t_{k−1} to t_k (the path is in its
//! Puiseux regime); a path whose ν_0 and its Aitken extrapolation are at least
//! homotopy_endgame_valuation_infinity, with the estimates stable at three successive steps
//! t_{k−1} → t_k, goes to infinity (diverging).
inline constexpr double homotopy_endgame_valuation_stable = 0.05;
inline constexpr double homotopy_endgame_valuation_infinity = 0.05;
//! Homotopy endgame: the valuation test for infinity is applied only at t_k ≤ this (paths can
//! look like going to infinity for a while and turn back to a finite endpoint).
inline constexpr double homotopy_endgame_valuation_max_t = 1e-4;
//! Homotopy endgame: a homogeneous coordinate below this fraction of ‖X‖∞ gets no valuation
//! estimate (too small to estimate).  The Aitken extrapolation of the valuation of X_0 takes a
//! sequence whose last difference is at most homotopy_aitken_settled as settled at its last value,
//! and one whose ratio of differences is not in (0, homotopy_aitken_max_ratio] as not geometric
//! (no limit).
inline constexpr double homotopy_valuation_floor = 1e-10;
inline constexpr double homotopy_aitken_settled = 1e-3;
inline constexpr double homotopy_aitken_max_ratio = 0.9;
//! Homotopy endgame: at t_0, and after a loop closes with winding number 1, the path may finish by
//! tracking straight to t = 0 in at most this many steps (accepted only at a regular,
//! well-conditioned zero).
inline constexpr std::size_t homotopy_endgame_direct_steps = 8;

//! Outward widening, in ulps, of each endpoint of an Interval exp, log, sin or cos (see
//! symbolic/scalar_traits.h).  glibc's libm test suite fails any of these functions whose error
//! exceeds 9 ulp in any of the four rounding modes, so 10 ulps outward covers glibc's error
//! whatever rounding mode is active (Interval evaluation runs with upward rounding).
inline constexpr int libm_ulp_margin = 10;

//! Interval sin and cos treat an extremum x* = c + 2πk as possibly inside [lo, hi] when
//! (lo − c)/2π − m ≤ k ≤ (hi − c)/2π + m with m = this · (1 + |k|).  Only the inclusion side
//! matters for rigour (it replaces an endpoint value by ±1), and it covers the rounding error of
//! those quotients (≈ 4e-16 · (1 + |k|)) many times over.
inline constexpr double trig_extremum_margin = 1e-10;


// ---- certified subdivision and univariate isolation (solvers/{krawczyk,univariate_isolator,
// ---- subdivision_solver}.cpp) ----

//! Below this width (relative to the domain's widest side, or to t1 − t0 for the univariate
//! isolator) a region that can be neither excluded nor certified and on which the derivative
//! (the interval Jacobian determinant) is not excludable from 0 is not bisected further: the
//! subdivision solver escalates it to MPFI once, then reports it undecided (singular_root /
//! boundary_root); the univariate isolator reports it singular_root at once (escalating a
//! tangency would only turn a double root on a rounded Voronoi edge into "no crossing").  A double
//! root's undecidable zone has width ~ sqrt(unit roundoff) ≈ 1e-8, so it ends here in a handful of
//! boxes instead of millions; two simple roots closer than this are reported undecided, never
//! certified as one.
inline constexpr double singular_box_relative_width = 1e-6;
//! The same width for a solve in exclusion mode (an over-determined system, whose zeros are
//! isolated points where there are any: SurfacePlaneContact).  Its undecided regions become
//! candidate witnesses, so a wide stop turns every thin region where the system is small without
//! a zero into witnesses: two sheets 10⁻⁶ of a facet's size apart stop at
//! singular_box_relative_width on both sheets all along the gap.  Bisecting on to this width
//! costs a few boxes per level at an isolated zero.
inline constexpr double exclusion_singular_box_relative_width = 1e-9;
//! The second look at a square solve's singular regions (refine_singular_regions in
//! solvers/subdivision_solver.h): each region is bisected on down to this width (relative to the
//! whole domain), within singular_refinement_box_budget boxes.  Two sheets of Σ 10⁻⁶ of a cell
//! apart are separated there; a true singular root costs the budget and stays undecided.  With
//! this budget two unit spheres 10⁻⁶ apart mesh complete (with 256 they do not); a larger one
//! only spends more boxes on true singular roots (thin_handle's SilhouettePlane solves have
//! some) for the same mesh.
inline constexpr double refined_singular_box_relative_width = 1e-9;
inline constexpr std::size_t singular_refinement_box_budget = 1024;

//! When more than this many boxes of one solve end undecided at singular_box_relative_width, the
//! solutions are taken to form a curve (non-isolated, e.g. the critical circle of a torus whose
//! axis is the direction): the solve stops with status non_isolated and returns every remaining
//! region as undecided.
inline constexpr std::size_t non_isolated_box_count = 64;

//! Krawczyk is applied to the box X inflated by this fraction of its width on every side
//! (ε-inflation), so that a root lying on a bisection face is certified from either side.
inline constexpr double krawczyk_inflation = 0.0625;

//! A Krawczyk step that shrinks the widest side of the box below this fraction is repeated on
//! the contracted box instead of bisecting.
inline constexpr double krawczyk_contraction_ratio = 0.5;

//! Most Krawczyk iterations used to shrink a certified root's box (to classify it against the
//! polytope); the iteration also stops when the box stops shrinking.
inline constexpr int root_refinement_iterations = 12;

//! Univariate isolator: half-width of the tight interval around a Newton-refined root that is
//! certified by a sign change and a non-vanishing derivative (relative to max(|t|, t1 − t0)).
inline constexpr double univariate_root_relative_radius = 4e-15;


//! Homotopy: two endpoints that coincide (homotopy_duplicate_endpoint) and whose Jacobian
//! condition number exceeds this are a cluster of paths converging to one multiple root; they
//! are treated as singular rather than as a path jump.
inline constexpr double homotopy_cluster_condition = 1e6;

// ---- meshing: the mesher's budgets and geometric tolerances ----

//! Box budget of one 2-D solve of the mesher (a Voronoi facet: FacetContact, FacetCycle,
//! SilhouettePlane).  A solve that runs out returns its unexplored boxes as undecided, which the
//! mesher treats as candidate witnesses.
inline constexpr std::size_t mesher_box_budget_2d = 4000;
//! Box budget of one 3-D solve of the mesher over a Voronoi cell (SilhouetteCritical).
inline constexpr std::size_t mesher_box_budget_3d = 20000;
//! Box budget of the seed solve (SurfaceCritical over the whole box) and of the input checks.
inline constexpr std::size_t mesher_box_budget_global = 400000;
//! Box budget of one univariate isolation on a Voronoi edge or a FacetCycle line.
inline constexpr std::size_t mesher_box_budget_1d = 20000;
//! The seed solve goes on in the regions its box budget left unexplored, each solved again with
//! mesher_box_budget_global boxes of its own, round after round while a round certifies a root,
//! until none is left or the boxes of all its solves reach this many times
//! mesher_box_budget_global.
inline constexpr std::size_t seed_solve_budget_factor = 16;
//! Different generic height directions tried for the seeds before giving up with InvalidInput.
inline constexpr int mesher_height_direction_retries = 6;
//! Newton projection of a candidate witness onto Σ: iterations, and convergence |E|/|∇E| below
//! this fraction of the box diagonal.
inline constexpr int projection_iterations = 30;
inline constexpr double projection_relative_tolerance = 1e-13;
//! A candidate point is accepted as lying in a Voronoi face's polytope if it violates no
//! half-space by more than this fraction of the box diagonal.  It covers the rounding of the
//! constructions of one face (a few units in the last place of the box size), while staying far
//! below the gaps one meshes (sheets 10⁻⁶ of the box apart).  It does not cover the error of a
//! circumcentre, which for a sliver can exceed it many times: the shortcuts that compare faces
//! built in different ways widen it to twice the certified error radii of the Voronoi vertices
//! involved where those are larger (meshing/voronoi/voronoi_geometry.h: certified_voronoi_vertex()).
inline constexpr double face_membership_relative_tolerance = 1e-10;
//! A Voronoi vertex whose certified error radius exceeds this fraction of its distance to its
//! sites (a nearly flat cell: a sliver, or a cell across a narrow gap) is constructed exactly
//! and rounded to doubles instead (meshing/voronoi/voronoi_geometry.h: voronoi_vertex()).  For cells
//! smaller than a tenth of the box this keeps every vertex within the membership margin above.
inline constexpr double voronoi_vertex_exact_relative_error = 1e-9;
//! Clipping a Voronoi cell's polytope by a half-space (meshing/voronoi/detail/convex_polytope.h): a vertex
//! within this fraction of the largest vertex distance to the plane counts as on the plane, and
//! cut points that close together are one vertex.  The distance is floored at
//! polytope_clip_min_extent so that the tolerance is positive.
inline constexpr double polytope_clip_relative_tolerance = 1e-13;
inline constexpr double polytope_clip_min_extent = 1e-300;
//! A half-space whose normal makes |⟨n, d⟩| ≤ this·|n|·|d| with a line's direction d is taken as
//! parallel to the line when the line is clipped by it: it keeps the whole line or nothing.
inline constexpr double parallel_half_space_relative_slope = 1e-15;
//! Two corners of a clipped Voronoi facet closer than this fraction of the facet's extent (or
//! of the box diagonal, if larger) are one corner; a facet whose polygon then has fewer than
//! three corners or no more area than this length squared is degenerate.
inline constexpr double facet_repeated_corner_relative_distance = 1e-12;
//! A witness closer than this fraction of the box diagonal to an existing sample is a duplicate
//! and is not inserted (it is counted as rejected).
inline constexpr double duplicate_sample_relative_distance = 1e-9;
//! A check whose answer rests on a seeded generic choice (FacetCycle's in-plane direction,
//! Silhouette's d′; CheckInfo::generic_choice) and all of whose witnesses were rejected is run
//! again with another choice, up to this many choices in all, before its face is left unsettled.
inline constexpr int generic_choice_attempts = 3;
//! Boxes evaluated, at most, to prove that E keeps one sign on the bounding box of a Voronoi
//! facet's vertices (RestrictedDelaunay::facet_misses_surface): the box, then halves of its widest
//! side.  Each is one interval evaluation of E, far cheaper than building the facet.
inline constexpr std::size_t facet_miss_box_budget = 8;
//! Box budget of one gradient-cone certificate (solvers/gradient_cone.h) over a Voronoi facet;
//! the full solvers run when it does not suffice.  A failed certificate costs the whole budget,
//! a solve it spares costs more, so the budget is large enough for most certificates on the
//! catalog surfaces to succeed (on the torus at size bound 0.05, all but a few dozen of several
//! thousand), and small enough that a failure stays cheap.  The meshes do not depend on it.
inline constexpr std::size_t gradient_cone_box_budget = 192;
//! The same over a Voronoi cell (Silhouette).  The cells of the topology phase are large, and the
//! SilhouetteCritical solve a failed certificate leads to costs about five times as much per box
//! (three equations, second derivatives) as the certificate, so the budget is larger than the
//! facet's: a certificate that succeeds with more boxes is still cheaper than the solve.  The
//! meshes do not depend on it.
inline constexpr std::size_t gradient_cone_cell_box_budget = 1024;
//! The box the mesher clips its Voronoi faces to (SurfaceOracle::clip_box(), solvers/surface_box.h,
//! whose SurfaceBoxOptions default to the first two):
//! each side's search stops at boxes narrower than this fraction of the side of B, or after this
//! many boxes (on the catalog surfaces a few hundred to a few thousand, well under a millisecond
//! each side), and the box found is widened by this fraction of B's diagonal (then met with B), so
//! that Σ lies in its interior.
inline constexpr double surface_box_resolution = 1.0 / 64;
inline constexpr std::size_t surface_box_evaluations_per_side = 4096;
inline constexpr double surface_box_relative_margin = 1e-3;
//! Krawczyk steps, at most, that narrow the box of a refuted gradient-cone certificate around its
//! proved point (GradientConeResult::vanishing_point).  The steps converge quadratically and stop
//! as soon as the box stops shrinking, which a box of a few units in the last place reaches well
//! within this many.
inline constexpr int vanishing_point_narrowing_steps = 12;
//! The order of a gradient-cone subdivision's halves steers towards the least-norm zero of the
//! linearised pair (E, ⟨∇E, w⟩); its two rows a, b count as parallel, and only E's row is used,
//! when det [a·a a·b; a·b b·b] ≤ this times |a|² |b|².  (It orders work only; no proof rests on
//! it.)
inline constexpr double cone_guess_parallel_rows = 1e-12;
//! Facets from a cell certificate (RestrictedDelaunay::cell_certified()): a facet pq of a
//! certified cell V_p follows from the cell when |⟨n_p, q − p⟩| / |q − p| is below the proof's
//! slope.  The cover of V_p is refined (solvers/gradient_cone.h, SlopeRefinement) towards the
//! largest of these values up to the cap, times the margin, within the box budget; facets beyond
//! the cap (q across Σ from p, where the slope would have to approach 1) get their own cover.
//! During the geometric refinement the attempt is made when p is inserted, for the facets of its
//! new edges (Refinement::prepare_new_edges), with a cover budget
//! that keeps a failure cheap (a failed attempt is not kept: Silhouette tries again later, with
//! gradient_cone_cell_box_budget, on a cell that may have shrunk).
inline constexpr double cell_slope_cap = 0.2;
inline constexpr double cell_slope_margin = 1.05;
inline constexpr std::size_t cell_slope_box_budget = 128;
inline constexpr std::size_t cell_slope_cover_budget = 192;
//! The relative margin by which a facet's slope test in doubles (meshing/voronoi/restricted_delaunay.cpp)
//! may fail before its interval test is skipped: more than the one rounding of that comparison
//! that falls outside the interval enclosure, so the skipped test could not have passed.
inline constexpr double slope_pretest_relative_margin = 1e-12;
//! The most checks of one row between two clock readings of the refinement loop (Refinement::run):
//! a reading costs about as much as a cheap check, and the time limit and the progress line are
//! tested at readings (the point limit and an interrupt before every check).
inline constexpr std::size_t checks_per_clock_reading = 32;
//! The least batch of edge records that an insertion computes on several threads
//! (detail::ParallelFor, `--threads`); a smaller one runs on the calling thread.  Handing a batch
//! to TBB's threads and waiting for them costs tens of microseconds, while an edge record is about
//! a microsecond (one interval evaluation, or a SurfaceLine solve), so a batch of a few records
//! is slower on the threads than on the calling thread.  An ordinary insertion's batches stay
//! below this value and run on the calling thread; batches this large come from wide
//! invalidations only.
inline constexpr std::size_t parallel_least_records = 256;
//! Interval subdivision of a box face to certify E ≠ 0 on it: maximal depth of the quadtree.
inline constexpr int box_face_max_depth = 14;
//! Input validation (meshing/inputs/input_validation.h): a box of the regularity check narrower than this
//! (relative to the widest side of the domain) that is neither excluded nor proved free of
//! critical points is not bisected further; it is undecided, and looked at for evidence of a
//! singular point.  A singular point's undecided zone shrinks with the box (the gradient grows
//! linearly away from it), so only O(1) boxes per level reach this width.
inline constexpr double validation_min_box_relative_width = 1e-6;
//! Input validation: a proof of a singular point near an undecided box is sought only if a point
//! is found there where |E| and ‖∇E‖∞ are at most this fraction of their largest values over the
//! domain's 3 × 3 × 3 grid (or a Krawczyk-certified critical point of E whose tight box has an
//! enclosure of E containing 0 and narrower than this fraction); the point is sought by at most
//! singular_evidence_iterations damped Gauss–Newton steps on (E, ∇E) = 0 (degenerate singular
//! points converge linearly, so the count must allow a few dozen halvings of the distance).
inline constexpr double singular_evidence_relative_residual = 1e-10;
inline constexpr int singular_evidence_iterations = 100;
//! Input validation: Krawczyk is tried on ∇E = 0 around that point on boxes of radius w, w/16,
//! w/16², … (w the undecided box's width), at most this many times: near a nearly degenerate
//! critical point the interval Hessian is contractive only on boxes much smaller than w.
inline constexpr int singular_evidence_krawczyk_attempts = 8;
//! Input validation: boxes of the regularity check narrower than validation_min_box_relative_width
//! in which no singular point was proved are bisected on, down to this relative width, at most
//! validation_deep_box_budget of them in all: smooth surfaces whose sheets come closer than the
//! first limit (two unit spheres 1e-6 apart) are then certified.
inline constexpr double validation_deep_min_box_relative_width = 1e-10;
inline constexpr std::size_t validation_deep_box_budget = 100000;
//! Input validation: the regularity check works in rounds of mesher_box_budget_global boxes; a
//! round that leaves less unexplored volume than the one before it earns another, up to this
//! many rounds in all (surfaces of high degree, whose enclosures are loose, need more boxes; a
//! check that stops deciding volume stops after one round).
inline constexpr std::size_t validation_box_rounds = 32;
//! Input validation: the surface is called singular only with a proof, sought near a point where
//! E and ∇E could not be separated: a rational point at which E, ∂xE, ∂yE, ∂zE evaluate to exactly
//! 0, tried at the point's coordinates rounded to 0 … singular_proof_decimal_places decimal places
//! and to 1 … singular_proof_binary_places binary places (and at the point itself).
inline constexpr int singular_proof_decimal_places = 17;
inline constexpr int singular_proof_binary_places = 52;
//! Input validation: that proof is also sought, from the box's centre and the Gauss–Newton point,
//! near the first this many undecided boxes, whatever E and ∇E are there (Gauss–Newton approaches
//! a degenerate singular point slowly).
inline constexpr std::size_t singular_proof_boxes_without_evidence = 16;
//! Input validation: a box that stays undecided in double-precision intervals is examined again
//! with MPFI at these precisions (bits, in turn), bisected while its double midpoint splits it, at
//! most validation_mpfi_box_budget boxes over all undecided boxes.
inline constexpr std::array<int, 2> validation_mpfi_precisions_bits = {128, 256};
inline constexpr std::size_t validation_mpfi_box_budget = 4000;
//! Remeshing a triangle mesh (meshing/inputs/input_mesh.h): the default domain box is the bounding box of
//! the input's vertices with every side pushed out by this fraction of its diagonal, so that the
//! surface lies well inside it and the clipped Voronoi cells of the samples reach beyond it.
inline constexpr double input_mesh_box_margin = 0.1;
//! Remeshing a triangle mesh: the largest |coordinate| of a vertex accepted (the box, with its
//! margin, then stays within about 1.4 times this).  The mesh oracle's orientation tests and the
//! Voronoi constructions multiply three coordinate differences; below this their products stay far
//! inside double precision (about 1e308).
inline constexpr double input_mesh_max_coordinate = 1e100;
//! Remeshing a triangle mesh far from the origin (its largest |coordinate| at least
//! input_mesh_far_ratio times its bounding-box diagonal): the diagonal must span at least this
//! many units in the last place of that coordinate.  Below, the coordinates are a coarse lattice
//! across the mesh, on which the floating-point constructions of the oracle and the mesher
//! (Voronoi vertices, clipped segments, projections) are too coarse to separate nearby features;
//! a translation towards the origin removes the problem, and the refusal says so.
inline constexpr double input_mesh_min_resolution = 65536;
inline constexpr double input_mesh_far_ratio = 4;
//! Remeshing a triangle mesh: the default termination floor (delmesh mesh --min-spacing) is this
//! fraction of the input's median edge length.  A triangle mesh is not C², so Lemma 5.1's spacing
//! bound does not hold at its creases and cone vertices; below the floor a witness is recorded
//! instead of inserted.  A tenth of an input edge is far below the spacing the checks need on
//! the input's smooth parts at the sizes Theorem 6.1's λ gives.
inline constexpr double min_spacing_median_edge_fraction = 0.1;
//! The statistics list the locations of at most this many witnesses below the termination floor
//! (all are counted).
inline constexpr std::size_t floor_locations_listed = 10;
//! The termination floor of the topology checks (VorEdge, FacetContact, TopoDisk, FacetCycle,
//! Silhouette) and the seeds, as a fraction of the floor of Quality, Smooth and the size bound.
//! Smooth cannot be satisfied across a crease whose dihedral angle exceeds 2β(λ), so refinement
//! for the geometry stops at the floor there; the topology checks keep inserting down to this
//! fraction of it, so that their witnesses, which the floor would otherwise leave unsettled and
//! Tri S|Σ wrong, are still inserted.
inline constexpr double topology_floor_fraction = 0.01;
//! Opposite-sheet partners (meshing/driver/refinement.h).  After a witness w goes in at
//! distance d from its nearest sample, Σ is searched on the normal line through w within
//! opposite_sheet_reach·d of w; the nearest other point y found is inserted too if the normals at
//! w and y make |cos| ≥ opposite_sheet_min_cosine and y is at least opposite_sheet_spacing·|w − y|
//! from every sample.  The two numbers are what the termination argument there uses.
inline constexpr double opposite_sheet_reach = 1.0;
inline constexpr double opposite_sheet_min_cosine = 0.5;
inline constexpr double opposite_sheet_spacing = 0.5;
//! The mesh oracle (meshing/inputs/mesh_oracle.h): a point of a triangle mesh within this distance
//! (relative to the box diagonal) of a vertex or an edge of its face gets that vertex's or edge's
//! normal rather than the face's.
inline constexpr double mesh_feature_relative_distance = 1e-12;
//! The mesher reports progress at most this often (seconds).
inline constexpr double progress_interval_seconds = 0.5;

//! Subdivision: a box whose enclosure of f at its midpoint is wider than this fraction of the
//! mean-value enclosure over the whole box is limited by rounding, not by its size; it is
//! re-examined in MPFI before being bisected further.
inline constexpr double precision_limited_ratio = 0.25;

// ---- certified subdivision and univariate isolation, continued (solvers/{subdivision_solver,
// ---- univariate_isolator}.cpp) ----

//! Default maximum number of subintervals one univariate isolation may visit before it stops
//! with status box_limit (the remaining intervals are returned as undecided).
inline constexpr std::size_t default_univariate_box_budget = 100000;

//! Krawczyk refinement of a certified root's box (root_refinement_iterations) stops once a step
//! shrinks the widest side to no less than this fraction of it.
inline constexpr double root_refinement_shrink_ratio = 0.75;

//! Krawczyk steps in MPFI, per escalation precision, that try to separate a certified root from
//! a face of the polytope before it is reported as boundary_root.
inline constexpr int boundary_separation_iterations = 4;

//! Univariate isolator: safeguarded Newton refinement of an isolated root stops when a step or
//! the bracket is narrower than this (relative to t1 − t0), or after
//! univariate_newton_iterations steps.
inline constexpr double univariate_newton_relative_tolerance = 1e-15;
inline constexpr int univariate_newton_iterations = 100;

//! Univariate isolator: the tight interval around a refined root grows by this factor, at most
//! univariate_certify_attempts times, until a sign change certifies it.
inline constexpr double univariate_certify_growth = 8;
inline constexpr int univariate_certify_attempts = 16;

//! Univariate isolator, MPFI escalation (at each of escalation_precisions) of an interval that
//! rounding left undecided: the interval is subdivided in MPFI, depth first, and the attempt at
//! that precision is abandoned (the interval stays undecided with its reason) as soon as a piece
//! narrower than univariate_escalation_min_relative_width (relative to t1 − t0; the pieces' ends
//! are doubles, so this is a few ulps) — or, if E' may vanish on it, narrower than
//! singular_box_relative_width — can be neither excluded nor certified, or after
//! univariate_escalation_box_budget pieces.
inline constexpr double univariate_escalation_min_relative_width = 1e-15;
inline constexpr std::size_t univariate_escalation_box_budget = 512;

//! Univariate isolator: a subinterval is limited by rounding, not by its width, when
//!  - (Bernstein path) its widest Bernstein coefficient enclosure exceeds this fraction of the
//!    largest coefficient magnitude (the enclosures do not shrink under subdivision): it is
//!    handed to the interval Newton path (the compiled expression), or
//!  - (interval Newton path) the enclosure of E at its midpoint is wider than this fraction of
//!    the mean-value enclosure of E over the whole subinterval: it is escalated to MPFI at once
//!    instead of being subdivided down to min_box_relative_width.
inline constexpr double univariate_precision_limited_ratio = 0.25;

//! A plane section of a box whose polygon has area below this times the squared box diagonal is
//! an edge or a corner, not a polygon (solvers/query_geometry.cpp: plane_box_section): rounding
//! noise at the box's size.
inline constexpr double degenerate_section_relative_area = std::numeric_limits<double>::epsilon();
//! A query's direction whose part orthogonal to another (the plane normal of curve_critical, the
//! other direction of silhouette_critical) is at most this relative to its length is taken as
//! parallel to it, and the query is refused: its frame would rest on rounding noise.
inline constexpr double query_parallel_directions = 1e-12;

// ---- Taylor forms of polynomial systems (symbolic/polynomial_form.h, subdivision_solver.cpp) ----
//! A system polynomial in its unknowns gets a monomial form (PolynomialForm) only if its expanded
//! equations have at most this many terms in all: beyond it, evaluating the coefficient program
//! on every solve would cost more than the tighter Taylor ranges save.
inline constexpr std::size_t polynomial_form_max_terms = 4000;
//! TaylorForms::automatic: Taylor forms are used when the compiled values+Jacobian program has at
//! least this many instructions per Taylor coefficient.  The ratio separates dense expanded
//! polynomials (the critical systems of Kostlan polynomials: about 7 instructions per coefficient),
//! which Taylor forms solve faster, from the catalog's factored surfaces (about 0.2 to 1.6), which
//! their compiled expressions solve as fast or faster (experiments/benchmarks/bench_homotopy.cpp
//! compares the two).  (A second condition, the coefficient program no longer than the compiled
//! program, keeps the plane primitives — E(o + u a + v b) expanded in nine parameters — on the
//! compiled path.)
inline constexpr double taylor_form_instruction_ratio = 2;

// ---- the gradient-flow certificate (meshing/verify/gradient_flow_certificate.h) ----

//! The tube T = {|E| ≤ ε′} of the flow certificate has ε′ = this factor times ε, the largest bound
//! of |E| on the mesh, so that the mesh lies in T's interior.
inline constexpr double flow_tube_factor = 1.25;
//! A triangle whose transversality a piece cannot decide is cut in four, down to this depth
//! (4^depth pieces at most).
inline constexpr int flow_triangle_max_depth = 7;
//! A piece whose bound of |E| exceeds this factor times the largest |E| met so far at a piece's
//! centre (a value E takes on the mesh) is cut in four as well, down to the same depth, so that ε
//! comes within about this factor of max |E| on the mesh instead of carrying the overestimate
//! of whole-triangle enclosures.
inline constexpr double flow_epsilon_slack = 1.25;
//! A box of the gradient proof is kept once its certified lower bound of |∇E| is at least this
//! fraction of |∇E| at its centre (the bound G then loses at most this factor), or once it is
//! narrower than flow_min_box_relative_width of the domain.
inline constexpr double flow_gradient_quality = 0.9;
inline constexpr double flow_min_box_relative_width = 1e-7;
//! Boxes and rectangles the proofs of (a) and (b) may examine, in all.
inline constexpr std::size_t flow_box_budget = 8000000;
//! The normalised function of the gradient-flow certificate, F = E / sqrt(|∇E|² + η²)
//! (meshing/verify/gradient_flow_certificate.h): η is this times the median of |∇E| over the mesh's
//! vertices, small enough that F is close to the signed distance where |∇E| is typical and large
//! enough that F's interval enclosures stay tight; its tube proofs get flow_normalized_box_budget
//! more boxes per round, and a round that leaves less unexplored volume than it began with earns
//! the next, up to flow_normalized_box_rounds rounds (F's enclosures are looser than E's: delmesh's
//! chair needs 4 rounds, about 5 s; a proof that stops deciding volume stops after one round).
inline constexpr double flow_normalized_eta_relative = 0.1;
inline constexpr std::size_t flow_normalized_box_budget = 1000000;
inline constexpr std::size_t flow_normalized_box_rounds = 8;
//! First directions tried for a critical point's counting path (along ∇E, then perturbed) when
//! the path passes through an edge or vertex of the mesh or cannot be proved monotone; and the
//! steps (proved or halved) each half of a path may take.
inline constexpr int flow_segment_attempts = 8;
inline constexpr int flow_path_steps = 256;
//! The flow distance bound of one triangle (meshing/inputs/flow_distance.h) bisects the grown box of the
//! triangle down to this many levels (8^depth boxes at most) while a box's lower bound of |∇E| is
//! not positive.
inline constexpr int flow_distance_gradient_depth = 2;

}  // namespace delmesh::tolerances
