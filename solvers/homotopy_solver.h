#pragma once
//! \file homotopy_solver.h
//! Total-degree homotopy continuation for square polynomial systems: start system
//! g_i = x_i^{d_i} − 1, H(x, s) = (1 − s) γ g(x) + s f(x) with a random complex γ (the gamma
//! trick), predictor–corrector tracking over complex<double> with adaptive steps, an endgame for
//! paths diverging or reaching singular endpoints, then Krawczyk certification of each real
//! endpoint inside the domain.  Independent oracle for the subdivision solver and a backend
//! (--solver homotopy).  Roots not certified (singular, diverging near the domain) come back
//! undecided; a path failure is reported, never dropped.

#include <cstdint>
#include <vector>

#include "solvers/domain.h"
#include "solvers/solve_result.h"
#include "symbolic/compiled_system.h"
#include "symbolic/primitive_system.h"

namespace delmesh {

struct HomotopyOptions {
  std::uint64_t seed = 1;  //!< for γ; fixed seed → reproducible
  double time_limit_seconds = 0;
};

//! Total degree of each equation of `system` in its unknowns (parameters treated as constants).
//! Throws InvalidInput if an equation is not polynomial in the unknowns.
std::vector<int> equation_degrees(const PrimitiveSystem& system);

//! Precondition: square system, polynomial in the unknowns, degrees from equation_degrees().
SolveResult solve_homotopy(const CompiledSystem& system, const std::vector<int>& degrees,
                           const std::vector<double>& parameters, const Domain& domain,
                           const HomotopyOptions& options = {});

}  // namespace delmesh
