#include "meshing/solver_backend.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, SolverBackend backend) {
  return out << (backend == SolverBackend::subdivision ? "subdivision" : "homotopy");
}

}  // namespace delmesh
