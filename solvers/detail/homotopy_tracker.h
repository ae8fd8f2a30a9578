#pragma once
//! \file homotopy_tracker.h
//! Internal: predictor–corrector tracking of one path of the total-degree homotopy
//!   H(u, t) = t γ g(u) + (1 − t) f(u),   g_i = u_i^{d_i} − 1,
//! from t = 1 (s = 1 − t = 0) towards t = 0, and the Cauchy endgame that computes its endpoint.
//! f and its Jacobian come from a CompiledSystem over Complex.
//!
//! Tracking is projective: homogeneous coordinates X = (X_0, …, X_n), u = (X_1, …, X_n) / X_0, on a
//! random affine patch ⟨c, X⟩ = 1, so paths going to infinity stay bounded (X_0 → 0).
//!
//! Main phase: t real from 1 down to t_0 = 1 − TrackerSettings::endgame_start (RK4 predictor,
//! Newton corrector with a trust bound, step halving on failure and doubling after two successes).
//!
//! Endgame: the Cauchy endgame of Morgan, Sommese and Wampler ("Computing singular solutions to
//! nonlinear analytic systems", Numer. Math. 58, 1991).  It rests on this fact: near t = 0 a
//! path of an algebraic homotopy is a Puiseux series, X(t) = Σ_k a_k τ^k with t = τ^c, analytic in
//! τ, where the winding number c ≥ 1 is the number of loops t ↦ t e^{iθ}, θ ∈ [0, 2π], the path
//! needs around t = 0 to come back to itself (c = 1 at a regular endpoint; c > 1 only at a
//! singular one).  In the patch chart X stays analytic in τ whether the endpoint is finite or at
//! infinity, so the Cauchy integral formula gives the endpoint as the mean of X over the circle
//! |τ| = t_k^{1/c}, i.e. over c loops of |t| = t_k, and the trapezoid rule with M equally spaced
//! samples per loop converges geometrically (error O(t_k^M) for fixed c).
//!
//! The endgame tracks t_k = t_0 q^k (k = 0, 1, …) along the real axis in log t.  At each t_k it
//! estimates the valuations ν_j = Re(t X_j'/X_j) → ord_t X_j of the homogeneous coordinates (from
//! the path's velocity, shifted so that the smallest is 0), and then:
//!  - a point with |X_0| ≤ ‖X‖ / divergence_norm, or a ν_0 ≥ endgame_valuation_infinity whose
//!    estimates changed by at most endgame_valuation_stable at each of the last three steps
//!    t_{k−1} → t_k, at t_k ≤ endgame_valuation_max_t, and whose
//!    Aitken-extrapolated limit is also ≥ endgame_valuation_infinity, goes to infinity (diverging:
//!    X_0 → 0 like t^{ν_0}).  Aitken's Δ² maps a ν_0 that decays like t^{1/c} (a finite endpoint)
//!    to about 0, or declines (ratio of differences above homotopy_aitken_max_ratio), so a slowly
//!    settling finite endpoint is not taken for one at infinity;
//!  - otherwise, if ν_0 < endgame_valuation_infinity, at t_0 or once the valuations have settled
//!    (a change ≤ endgame_valuation_stable),
//!    the loops around t_k are tracked until the path closes up (that count is c; at most
//!    endgame_max_winding loops — if they do not close, the path is not in its Puiseux regime yet
//!    and the endgame moves on to t_{k+1}); the mean of the samples is the estimate, and the
//!    endgame stops when two successive estimates agree to endgame_tolerance (for c > 1, also with
//!    the spread of the samples shrinking and J_f ill conditioned at the estimate, condition ≥
//!    cluster_condition: loops around a branch point away from 0, where two paths to distinct
//!    regular zeros swap, close after 2 loops too, and their mean is then the zeros' centroid).
//!    Shortcut at regular endpoints: at t_0 (if ν_0 < endgame_valuation_infinity), and after the
//!    first loop that closes with c = 1, the segment from t_k to 0 is tracked directly (at most
//!    endgame_direct_steps steps) and its end accepted if Newton on f converges there to a zero
//!    with a well-conditioned Jacobian — the same test as for a Cauchy estimate with c = 1 (and
//!    what this tracker did for every path before it had an endgame).
//! The loops stay at |t| = t_k, away from the singular endpoint, so the estimate is accurate even
//! where the Jacobian at t = 0 is singular.  The estimate is then classified: at infinity →
//! diverging; c = 1 → Newton on f in the affine chart, regular if the Jacobian there is well
//! conditioned and the Newton correction there is below tolerances::homotopy_endpoint_newton_step
//! (the point is a zero of f), failed if it is well conditioned and not a zero; c > 1, or c = 1
//! with an ill-conditioned Jacobian → singular if the estimate passes the residual test of
//! TrackerSettings::singular_residual (‖f‖ against ‖J_f‖: it is a zero of f), failed
//! otherwise.  So every finite or singular endpoint is an approximate zero of f, and an endgame
//! estimate that is not one is never taken for a root, real or not.  An endgame that does not conclude before t_k
//! falls below endgame_min_t, or runs out of the step budget, or whose steps underflow, makes the
//! path failed: it is reported, never dropped.
//!
//! Nothing here is certified: path tracking in double precision may jump between paths, and the
//! endgame's closure, agreement and valuation tests are numerical (so is the test |u| > 1e8).
//! Certification happens afterwards (Krawczyk on the regular real endpoints, homotopy_solver.cpp).

#include <chrono>
#include <cstddef>
#include <optional>
#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! How a path ended.
enum class PathOutcome {
  finite,     //!< the endgame converged to a regular (well-conditioned) zero of f
  singular,   //!< the endgame converged to a zero of f with an ill-conditioned Jacobian (or c > 1)
  diverging,  //!< the path goes to a solution at infinity (X_0 → 0)
  failed      //!< tracking or the endgame broke down (step underflow, step budget, no convergence,
              //!< or an endpoint estimate that is not a zero of f)
};
constexpr auto enum_names(PathOutcome) {
  return name_table<PathOutcome>("PathOutcome", {{PathOutcome::finite, "finite"},
                                                 {PathOutcome::singular, "singular"},
                                                 {PathOutcome::diverging, "diverging"},
                                                 {PathOutcome::failed, "failed"}});
}
inline std::ostream& operator<<(std::ostream& out, PathOutcome outcome) { return write_enum(out, outcome); }

//! Step-size control and endgame thresholds (defaults from common/tolerances.h).
struct TrackerSettings {
  double initial_step;
  double max_step;
  double min_step;
  double corrector_tolerance;
  double corrector_trust;
  int corrector_iterations;
  double divergence_norm;
  double endgame_start;        //!< the endgame starts at t_0 = 1 − endgame_start
  double singular_condition;
  std::size_t max_steps;       //!< accepted plus rejected steps per path, endgame included
  int endgame_samples;         //!< M: samples per loop
  double endgame_ratio;        //!< q: t_{k+1} = q t_k
  double endgame_tolerance;    //!< successive Cauchy estimates agree: ‖ΔX‖∞ ≤ this · ‖X‖∞
  int endgame_max_winding;     //!< the largest winding number c tried
  double endgame_min_t;        //!< no convergence before t_k < this: the path failed
  double endgame_closure;      //!< a loop closes: back to its start up to this · sample spacing
  double endgame_valuation_stable;    //!< valuation estimates stable: change per level ≤ this
  double endgame_valuation_infinity;  //!< stable valuation of X_0 ≥ this: the path diverges
  std::size_t endgame_direct_steps;  //!< steps allowed to finish directly from t_k to 0
  double endgame_valuation_max_t;    //!< the valuation test for infinity only at t_k ≤ this
  double cluster_condition;          //!< c > 1 estimate accepted only where cond J_f ≥ this (or at ∞)
  double singular_residual;          //!< singular endpoint only if ‖f‖∞ ≤ this (1 + ‖u‖∞) ‖J_f‖∞ there
  //! If set: no step is attempted once the clock has reached it; the path then ends failed with
  //! PathEndpoint::stopped (the clock is read before every predictor–corrector step).
  std::optional<std::chrono::steady_clock::time_point> deadline{};
  static TrackerSettings defaults();
  //! Smaller steps and a tighter trust region, for re-tracking paths suspected of jumping.
  TrackerSettings stricter() const;
};

struct PathEndpoint {
  PathOutcome outcome = PathOutcome::failed;
  //! The endpoint in u: the Newton-refined point for a regular endpoint, the Cauchy estimate for
  //! a singular one (where Newton converges only linearly); for a failed path, the last point.
  std::vector<Complex> point;
  double s = 0;                //!< s = 1 − |t| of the last point tracked (1 − t_k for the endgame)
  double condition = 0;        //!< 2-norm condition number of J_f at point
  //! Accuracy estimate of point in u: the last Newton correction (regular), or the change between
  //! the last two Cauchy estimates (singular).
  double last_correction = 0;
  int winding = 0;             //!< winding number c found by the endgame loops (0: no loop closed)
  std::size_t steps = 0;       //!< accepted steps (endgame included)
  std::size_t rejections = 0;  //!< rejected steps
  bool stopped = false;        //!< TrackerSettings::deadline passed before the path ended (outcome failed)
};

class HomotopyTracker {
 public:
  //! Precondition: f is square with n unknowns, degrees.size() == n, every degree ≥ 1,
  //! parameters.size() == f.n_parameters(), |gamma| = 1, patch.size() == n + 1 (a generic
  //! complex vector: the patch ⟨patch, (X_0, …, X_n)⟩ = 1).
  HomotopyTracker(const CompiledSystem& f, std::vector<int> degrees, std::vector<Complex> parameters,
                  Complex gamma, std::vector<Complex> patch);

  //! Tracks the path starting at the start solution `start` (g(start) = 0) and runs the endgame.
  PathEndpoint track(const std::vector<Complex>& start, const TrackerSettings& settings) const;

  //! Tracks the path starting at `start` from t = 1 down the real axis to t = t_stop (no endgame)
  //! and returns its point u there, in affine coordinates.  Nothing if the tracking failed (step
  //! budget, step underflow, settings.deadline passed) or the point is at infinity to working
  //! precision (X_0 = 0).  Not certified: the caller certifies the point (homotopy_certificate.h).
  //! Throws PreconditionViolation unless 0 < t_stop < 1.
  std::optional<std::vector<Complex>> point_at(const std::vector<Complex>& start, double t_stop,
                                               const TrackerSettings& settings) const;

 private:
  const CompiledSystem& f_;
  std::vector<int> degrees_;
  std::vector<Complex> parameters_;
  Complex gamma_;
  std::vector<Complex> patch_;
};

}  // namespace delmesh::detail
