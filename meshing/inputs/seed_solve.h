#pragma once
//! \file seed_solve.h
//! The seed solve of SampleTopology (§5.4, step 1): SurfaceCritical(Σ) in a generic height
//! direction, through a SurfaceOracle.  The mesher's seeds (meshing/driver/sample_topology.h)
//! and the gradient-flow certificate's critical points (meshing/verify/gradient_flow_certificate.h)
//! both come from it.

#include <cstdint>

#include "common/vec3.h"
#include "meshing/core/surface_oracle.h"
#include "solvers/domain.h"
#include "solvers/solve_result.h"

namespace delmesh {

//! The k-th seeded generic unit direction (k = 0, 1, …).
Vec3 generic_direction(std::uint64_t seed, int k);

//! SurfaceCritical in direction d over `domain` (the seed solve of step 1), then over every region
//! the box budget left unexplored, each with a budget of its own, round after round while the last
//! round certified a root, within tolerances::seed_solve_budget_factor budgets in all.  The
//! regions tile the part of the domain that was not excluded, so the roots and regions returned
//! cover every critical point as one solve would.  Stops at once on time_limit or non_isolated,
//! which it returns; status complete when no region is left undecided.
SolveResult seed_solve(SurfaceOracle& oracle, const Vec3& d, const Domain& domain);

}  // namespace delmesh
