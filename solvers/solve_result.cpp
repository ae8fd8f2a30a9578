#include "solvers/solve_result.h"

namespace delmesh {

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
