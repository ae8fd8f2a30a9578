#pragma once
//! \file subdivision_solver.h
//! Certified subdivision solver for n = 2 or 3 unknowns over a convex polytope (Domain):
//! interval exclusion (natural and mean-value forms), exclusion of boxes outside the polytope,
//! Krawczyk contraction and uniqueness, bisection, de-duplication through uniqueness boxes,
//! inside/outside classification of each root, escalation to MPFI for boxes double intervals
//! cannot decide.  See solve_result.h for what "certified" means.

#include <vector>

#include "solvers/domain.h"
#include "solvers/solve_result.h"
#include "symbolic/compiled_system.h"

namespace delmesh {

struct SubdivisionOptions {
  std::size_t box_budget = 200000;
  double time_limit_seconds = 0;  //!< 0: none
  //! Over-determined systems (m > n, SurfacePlaneContact): prove that there is no solution, or
  //! return as undecided the boxes that could not be excluded.  Never certifies roots.
  bool exclusion_mode = false;
};

//! Precondition: system.n_unknowns() == domain.dimension() ∈ {2, 3};
//! parameters.size() == system.n_parameters(); m == n unless exclusion_mode.
SolveResult solve_subdivision(const CompiledSystem& system, const std::vector<double>& parameters,
                              const Domain& domain, const SubdivisionOptions& options = {});

}  // namespace delmesh
