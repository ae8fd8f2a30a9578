#pragma once
//! \file homotopy_tracker.h
//! Internal: predictor–corrector tracking of one path of the total-degree homotopy
//! H(u, s) = (1 − s) γ g(u) + s f(u), g_i = u_i^{d_i} − 1, from s = 0 to s = 1, and the
//! classification of its endpoint.  f and its Jacobian come from a CompiledSystem over Complex.
//! Tracking is projective: homogeneous coordinates on a random affine patch ⟨c, X⟩ = 1, so paths
//! going to infinity stay bounded.

#include <cstddef>
#include <ostream>
#include <vector>

#include "symbolic/compiled_system.h"
#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! How a path ended.
enum class PathOutcome {
  finite,     //!< reached s = 1 at a regular (well-conditioned) zero of f
  singular,   //!< reached (or approached) s = 1 at a zero of f with an ill-conditioned Jacobian
  diverging,  //!< ‖u‖ grew without bound as s → 1: a solution at infinity
  failed      //!< the step underflowed (or the step budget ran out) before the endgame
};
std::ostream& operator<<(std::ostream& out, PathOutcome outcome);

//! Step-size control and endgame thresholds (defaults from common/tolerances.h).
struct TrackerSettings {
  double initial_step;
  double max_step;
  double min_step;
  double corrector_tolerance;
  double corrector_trust;
  int corrector_iterations;
  double divergence_norm;
  double endgame_start;
  double singular_condition;
  std::size_t max_steps;
  static TrackerSettings defaults();
  //! Smaller steps and a tighter trust region, for re-tracking paths suspected of jumping.
  TrackerSettings stricter() const;
};

struct PathEndpoint {
  PathOutcome outcome = PathOutcome::failed;
  std::vector<Complex> point;  //!< last point of the path in u (after the endgame's Newton refinement)
  double s = 0;                //!< path parameter reached
  double condition = 0;        //!< 2-norm condition number of J_f at point
  double last_correction = 0;  //!< size of the last Newton correction at s = 1 (accuracy estimate)
  std::size_t steps = 0;       //!< accepted steps
  std::size_t rejections = 0;  //!< rejected steps
};

class HomotopyTracker {
 public:
  //! Precondition: f is square with n unknowns, degrees.size() == n, every degree ≥ 1,
  //! parameters.size() == f.n_parameters(), |gamma| = 1, patch.size() == n + 1 (a generic
  //! complex vector: the patch ⟨patch, (X_0, …, X_n)⟩ = 1).
  HomotopyTracker(const CompiledSystem& f, std::vector<int> degrees, std::vector<Complex> parameters,
                  Complex gamma, std::vector<Complex> patch);

  //! Tracks the path starting at the start solution `start` (g(start) = 0).
  PathEndpoint track(const std::vector<Complex>& start, const TrackerSettings& settings) const;

 private:
  const CompiledSystem& f_;
  std::vector<int> degrees_;
  std::vector<Complex> parameters_;
  Complex gamma_;
  std::vector<Complex> patch_;
};

}  // namespace delmesh::detail
