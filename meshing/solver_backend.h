#pragma once
//! \file solver_backend.h
//! Which certified solver an implicit surface's oracle (meshing/implicit_oracle.h) uses for the
//! square systems of its primitives.  An option of the mesher (DelMeshOptions::solver) and of the
//! oracle's constructor, kept apart from both so that neither header includes the other.

#include <ostream>

#include "common/enum_names.h"

namespace delmesh {

//! subdivision: the certified subdivision solver (solvers/subdivision_solver.h).  homotopy:
//! solve_homotopy() (solvers/homotopy_solver.h) for the square systems when E is polynomial; the
//! oracle falls back to subdivision otherwise (see implicit_oracle.h).
enum class SolverBackend { subdivision, homotopy };
constexpr auto enum_names(SolverBackend) {
  return name_table<SolverBackend>("SolverBackend", {{SolverBackend::subdivision, "subdivision"},
                                                     {SolverBackend::homotopy, "homotopy"}});
}
inline std::ostream& operator<<(std::ostream& out, SolverBackend backend) { return write_enum(out, backend); }

}  // namespace delmesh
