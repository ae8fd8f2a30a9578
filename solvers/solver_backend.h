#pragma once
//! \file solver_backend.h
//! Which certified solver answers a primitive's system: a query of `delmesh solve`
//! (solvers/primitive_query.h: QuerySolveOptions::solver) and the square systems of an implicit
//! surface's oracle (meshing/inputs/implicit_oracle.h; DelMeshOptions::solver), in a header of its own so
//! that the mesher's option header need not include the oracle's.

#include <ostream>

#include "common/enum_names.h"

namespace delmesh {

//! subdivision: the certified subdivision solver (solvers/subdivision_solver.h; exclusion mode for
//! over-determined systems), or the univariate isolator for a line (solvers/univariate_isolator.h).
//! homotopy: solve_homotopy() (solvers/homotopy_solver.h), for square systems polynomial in their
//! unknowns only; the oracle falls back to subdivision otherwise (see implicit_oracle.h).
enum class SolverBackend { subdivision, homotopy };
constexpr auto enum_names(SolverBackend) {
  return name_table<SolverBackend>("SolverBackend", {{SolverBackend::subdivision, "subdivision"},
                                                     {SolverBackend::homotopy, "homotopy"}});
}
inline std::ostream& operator<<(std::ostream& out, SolverBackend backend) { return write_enum(out, backend); }

}  // namespace delmesh
