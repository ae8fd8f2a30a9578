#pragma once
//! \file homotopy_solver.h
//! Total-degree homotopy continuation for square polynomial systems: start system
//! g_i = x_i^{d_i} − 1, H(x, t) = t γ g(x) + (1 − t) f(x) with a random complex γ (the gamma
//! trick), predictor–corrector tracking over complex<double> from t = 1 with adaptive steps (RK4
//! predictor, Newton corrector with a trust bound, step halving on failure and doubling after two
//! successes), in homogeneous coordinates on a random affine patch so that paths going to infinity
//! stay bounded; the Cauchy endgame near t = 0 (loops around t = 0 at geometrically shrinking |t|,
//! endpoint = mean of the loop samples; detail/homotopy_tracker.h), which computes singular
//! endpoints (and points at infinity) as accurately as regular ones and finds each path's winding
//! number, with valuation estimates (X_0 ~ t^{ν_0}, ν_0 > 0) to recognise paths to infinity that
//! the loops cannot resolve cheaply, and a direct finish for regular endpoints; classification of
//! each endpoint as at infinity (diverging), singular (winding number > 1, or ill-conditioned
//! Jacobian) or regular; then Krawczyk certification of each real regular endpoint inside the
//! domain.  Independent oracle for the subdivision solver and a backend
//! (--solver homotopy).  Roots not certified (singular, near-real, diverging near the domain)
//! come back undecided; a path failure (tracking or endgame) is reported, never dropped; the
//! exact rules are at solve_homotopy().

#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "symbolic/scalar_types.h"

#include "common/tolerances.h"
#include "solvers/domain.h"
#include "solvers/homotopy_certificate.h"
#include "solvers/solve_result.h"
#include "symbolic/compiled_system.h"
#include "symbolic/primitive_system.h"

namespace delmesh {

//! What the paths of one solve did (for tests and benchmarks).
struct HomotopyStatistics {
  //! Final classification of the Bézout-many paths (after re-tracking): finite (regular),
  //! singular, diverging (at infinity), failed.  Sums to the number of paths tracked unless the
  //! time limit stopped the solve; re-tracked paths count once, with their final outcome.
  std::size_t finite = 0, singular = 0, diverging = 0, failed = 0;
  //! Accepted and rejected predictor–corrector steps, summed over every path tracked (re-tracks
  //! included), endgame included.
  std::size_t steps = 0, rejections = 0;
  //! The largest winding number the Cauchy endgame found (0: no endgame completed).
  int max_winding = 0;
  //! Singular or regular endpoints in the near-real bands of solve_homotopy() (rules 2 and 3:
  //! not real candidates, not certainly non-real) near the domain.
  std::size_t near_real = 0;
  //! Diverging paths whose last point was near the domain (solve_homotopy(), rule 4).
  std::size_t diverging_near_domain = 0;
  //! Unproved pieces answered by the subdivision solver (HomotopyOptions::subdivision_budget_for_unproved).
  std::size_t pieces_by_subdivision = 0;
};

struct HomotopyOptions {
  std::uint64_t seed = 1;  //!< for γ and the projective patch; fixed seed → reproducible
  double time_limit_seconds = 0;  //!< from the call's start; 0: none
  //! Absolute end of the solve (none if empty); with time_limit_seconds the earlier one counts.
  //! The clock is read before every predictor–corrector step, so a single long path is cut off
  //! too (see solve_homotopy() for what is returned).
  std::optional<std::chrono::steady_clock::time_point> deadline;
  //! Predictor–corrector steps one path may take before it is declared failed (a failed path
  //! makes the solve undecided: the whole domain box is returned as undecided).
  std::size_t max_steps_per_path = tolerances::homotopy_max_steps_per_path;
  //! When set, each piece of the domain that the certificate leaves unproved is solved by the
  //! subdivision solver (solve_subdivision() on the piece, with the domain's half-spaces and this
  //! box budget) and takes its answer, certified roots and undecided boxes; when 0 the piece stays
  //! undecided, so the answer rests on the homotopy alone (the cross-check of the two solvers).
  std::size_t subdivision_budget_for_unproved = 0;
};

//! What solve_homotopy() returns: its roots and undecided regions, the statistics of its paths,
//! and the certificate of completeness (homotopy_certificate.h).
struct HomotopySolveResult : SolveResult {
  HomotopyStatistics statistics;
  HomotopyCertificate certificate;
  //! The roots and undecided boxes are proved to account for every root in the domain.
  bool completeness_certified() const { return certificate.status == HomotopyCertificateStatus::proved; }
};


//! Total degree of each equation of `system` in its unknowns (parameters treated as constants).
//! Throws InvalidInput if an equation is not polynomial in the unknowns.
std::vector<int> equation_degrees(const PrimitiveSystem& system);

//! The Bézout number ∏ d_i: the number of paths of the total-degree homotopy.
//! Throws PreconditionViolation if degrees is empty, and InvalidInput if some d_i < 1 (an equation
//! constant in the unknowns, which a primitive of a user's E can be).
std::size_t bezout_number(const std::vector<int>& degrees);

//! The ∏ d_i solutions of the start system g_i(u) = u_i^{d_i} − 1 = 0 (tuples of roots of unity),
//! in a fixed order.  Throws like bezout_number().
std::vector<std::vector<Complex>> total_degree_start_solutions(const std::vector<int>& degrees);

//! All roots of the square polynomial system f(u; parameters) = 0 inside the domain, by the
//! total-degree homotopy.  Every path is tracked and run through the Cauchy endgame; endpoints are
//! classified as finite (regular), singular, diverging (at infinity) or failed.  Below, u is an
//! endpoint (for a diverging path: its last tracked point, where it was declared at infinity),
//! s = 1 + ‖u‖∞, ι = ‖Im u‖∞, x = Re u; x is "near the domain with extra e" when every
//! coordinate is within homotopy_domain_margin · domain.scale() + e of the domain box (all
//! tolerances in tolerances::):
//!  1. real regular endpoint (ι ≤ homotopy_real_candidate · s), x near the domain: Newton-polished
//!     over the reals and certified by the Krawczyk test (krawczyk.h) on a small box around it,
//!     contracted by Krawczyk iteration and classified against the domain; not certified → the
//!     largest box tried undecided (precision), unless it is certainly outside the domain;
//!  2. singular endpoint (an approximate zero of f by the tracker's residual test, else the path
//!     failed: rule 5) with ι ≤ max(r, homotopy_near_real · s), r = max(homotopy_singular_box_radius
//!     · s, homotopy_correction_box_factor · its accuracy estimate), x near the domain with extra b: the box of half-width
//!     b = max(r, homotopy_near_real_box_ratio · ι) around x undecided (singular_root);
//!  3. near-real regular endpoint (homotopy_real_candidate · s < ι ≤ homotopy_near_real · s), x near
//!     the domain with extra b, B the box of half-width b = max(homotopy_certify_radius · s,
//!     homotopy_near_real_box_ratio · ι) around x: a root certified from x as in rule 1 is kept;
//!     unless its box meets B, B is dropped only if the Krawczyk test proves that f has no zero in
//!     B or B is certainly outside the domain, and is undecided (precision) else;
//!  4. diverging path with x near the domain with extra δ = homotopy_diverging_near_domain ·
//!     domain.scale() and ι ≤ δ (u finite): counted (statistics.diverging_near_domain); the
//!     certificate below decides whether a root can hide there;
//!  5. a failed path, or two paths at the same regular root after re-tracking with smaller steps
//!     (one jumped): counted; the certificate below trusts no path;
//!  6. the deadline (options.deadline, or options.time_limit_seconds from the call) reached while
//!     tracking: the path being tracked is abandoned (not counted as failed), no further path or
//!     re-track is started, the endpoints already tracked are classified as above, and the whole
//!     domain box comes back undecided (budget) with status time_limit;
//!  7. non-real endpoints (ι above the bands of rules 2 and 3) and endpoints not near the domain
//!     are not roots in the domain: dropped.
//! Returned:
//!  - roots: certified roots inside the domain (one per root; inside_domain = true), sorted;
//!    certified roots whose box straddles a face are undecided (boundary_root), certified boxes
//!    that meet without one unique root in their hull undecided (cluster);
//!  - undecided: as in "Certificate" below (rules 1–3 only propose);
//!  - statistics: how the paths ended (HomotopyStatistics);
//!  - counters.paths (paths tracked, re-tracks included) and counters.seconds.
//! Fixed options.seed → identical output (unless the deadline cuts the solve).
//! Certificate.  Unless the deadline cut the tracking, the solve then proves what it can of its
//! completeness (certify_homotopy(), homotopy_certificate.h: barrier boxes around pieces of the
//! domain, the Bézout count at an intermediate t_e with every zero there Krawczyk-certified, and
//! Krawczyk certificates of f's zeros; the path tracking is never trusted), and the result is
//! rebuilt from it: on the pieces proved, the certificate's real zeros placed against the domain
//! (inside: a root; on its boundary: undecided, boundary_root; outside: counted); each piece not
//! proved answered by the subdivision solver if options.subdivision_budget_for_unproved > 0 (its
//! roots outside the proved pieces, and its undecided boxes), else undecided (precision), with
//! the roots of rules 1–5 that lie in no proved piece kept; the
//! undecided boxes of rules 1–5 are replaced (a proved piece has no other zero, an unproved one is
//! undecided whole).  Status complete iff nothing is undecided, so a complete status is a proof,
//! as for the subdivision solver; completeness_certified() says every piece was proved.  The
//! deadline reached while tracking or certifying: the whole domain box undecided (budget), status
//! time_limit.  Each root returned is certified either way: its box holds exactly one root of f
//! (Krawczyk, in interval arithmetic).
//! Preconditions (PreconditionViolation otherwise): system square with n = domain.dimension()
//! unknowns, degrees.size() == n, parameters.size() == system.n_parameters(), domain valid
//! (Domain::validate).  Throws InvalidInput if some d_i < 1 (d_i is the total degree of equation
//! i, equation_degrees()).
HomotopySolveResult solve_homotopy(const CompiledSystem& system, const std::vector<int>& degrees,
                                   const std::vector<double>& parameters, const Domain& domain,
                                   const HomotopyOptions& options = {});

}  // namespace delmesh
