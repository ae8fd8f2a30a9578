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
//! (--solver homotopy).  Roots not certified (singular, diverging near the domain) come back
//! undecided; a path failure (tracking or endgame) is reported, never dropped.

#include <cstdint>
#include <vector>

#include "symbolic/scalar_types.h"

#include "common/tolerances.h"
#include "solvers/domain.h"
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
};

struct HomotopyOptions {
  std::uint64_t seed = 1;  //!< for γ and the projective patch; fixed seed → reproducible
  double time_limit_seconds = 0;  //!< 0: none
  //! Predictor–corrector steps one path may take before it is declared failed (a failed path
  //! makes the solve undecided: the whole domain box is returned as undecided).
  std::size_t max_steps_per_path = tolerances::homotopy_max_steps_per_path;
  //! If set, receives the path statistics of the solve (overwritten).
  HomotopyStatistics* statistics = nullptr;
};


//! Total degree of each equation of `system` in its unknowns (parameters treated as constants).
//! Throws InvalidInput if an equation is not polynomial in the unknowns.
std::vector<int> equation_degrees(const PrimitiveSystem& system);

//! The Bézout number ∏ d_i: the number of paths of the total-degree homotopy.
//! Throws InvalidInput if degrees is empty or some d_i < 1.
std::size_t bezout_number(const std::vector<int>& degrees);

//! The ∏ d_i solutions of the start system g_i(u) = u_i^{d_i} − 1 = 0 (tuples of roots of unity),
//! in a fixed order.  Throws InvalidInput like bezout_number().
std::vector<std::vector<Complex>> total_degree_start_solutions(const std::vector<int>& degrees);

//! All roots of the square polynomial system f(u; parameters) = 0 inside the domain, by the
//! total-degree homotopy.  Every path is tracked and run through the Cauchy endgame; endpoints are
//! classified as finite, singular, diverging (at infinity) or failed.  Each finite endpoint that is real (max |Im u_i| below
//! tolerances::homotopy_real_candidate) and in (or within a margin of) the domain box is
//! Newton-polished over the reals and certified by the Krawczyk test (krawczyk.h) on a small box
//! around it; the certified box is contracted by Krawczyk iteration and classified against the
//! box and the half-spaces of the domain.  Returned:
//!  - roots: certified roots inside the domain (one per root; inside_domain = true), sorted;
//!  - undecided: real singular endpoints in the domain (singular_root), real endpoints that could
//!    not be certified (precision), certified roots whose box straddles a face (boundary_root),
//!    and, when a path failed or two paths reached the same regular root even after re-tracking
//!    with smaller steps (a root may have been missed), the whole domain box (precision);
//!    when the time limit stops the solve, the whole domain box (budget) and status time_limit;
//!  - counters.paths (paths tracked, re-tracks included) and counters.seconds.
//! Status complete iff nothing is undecided.  Fixed options.seed → identical output.
//! Not a proof of completeness: path tracking and the endgame are not certified (a path jump that
//! lands on a different root is detected only when two paths end at the same regular root; the
//! endgame's loop-closure and agreement tests are numerical).  What is certified is each root
//! returned: its box holds exactly one root of f (Krawczyk, in interval arithmetic).
//! Preconditions (InvalidInput otherwise): system square with n = domain.dimension() unknowns,
//! degrees.size() == n with d_i ≥ 1 the total degree of equation i (equation_degrees()),
//! parameters.size() == system.n_parameters().
SolveResult solve_homotopy(const CompiledSystem& system, const std::vector<int>& degrees,
                           const std::vector<double>& parameters, const Domain& domain,
                           const HomotopyOptions& options = {});

}  // namespace delmesh
