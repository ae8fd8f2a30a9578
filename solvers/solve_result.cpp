#include "solvers/solve_result.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, SolveStatus status) {
  switch (status) {
    case SolveStatus::complete: return out << "complete";
    case SolveStatus::undecided: return out << "undecided";
    case SolveStatus::non_isolated: return out << "non_isolated";
    case SolveStatus::box_limit: return out << "box_limit";
    case SolveStatus::time_limit: return out << "time_limit";
  }
  return out << "SolveStatus(" << static_cast<int>(status) << ")";
}

std::ostream& operator<<(std::ostream& out, UndecidedReason reason) {
  switch (reason) {
    case UndecidedReason::singular_root: return out << "singular_root";
    case UndecidedReason::boundary_root: return out << "boundary_root";
    case UndecidedReason::cluster: return out << "cluster";
    case UndecidedReason::non_isolated: return out << "non_isolated";
    case UndecidedReason::precision: return out << "precision";
    case UndecidedReason::budget: return out << "budget";
  }
  return out << "UndecidedReason(" << static_cast<int>(reason) << ")";
}

SolverCounters& SolverCounters::operator+=(const SolverCounters& other) {
  boxes += other.boxes;
  exclusions += other.exclusions;
  krawczyk_successes += other.krawczyk_successes;
  precision_escalations += other.precision_escalations;
  paths += other.paths;
  roots_outside += other.roots_outside;
  seconds += other.seconds;
  return *this;
}

}  // namespace delmesh
