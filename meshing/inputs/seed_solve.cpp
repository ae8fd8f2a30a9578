#include "meshing/inputs/seed_solve.h"

#include <algorithm>
#include <cmath>

#include "common/seeded_uniform.h"
#include "common/tolerances.h"

namespace delmesh {

Vec3 generic_direction(std::uint64_t seed, int k) {
  // A uniform point of the unit sphere: z uniform in [-1, 1], the azimuth uniform.
  const double z = 2 * seeded_uniform(seed, k, 1, generic_stream::height_direction) - 1;
  const double phi = 2 * M_PI * seeded_uniform(seed, k, 2, generic_stream::height_direction);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

SolveResult seed_solve(SurfaceOracle& oracle, const Vec3& d, const Domain& domain) {
  const std::size_t budget = tolerances::mesher_box_budget_global;
  SolveResult all = oracle.surface_critical(d, domain, budget);
  std::size_t boxes = all.counters.boxes;
  std::size_t roots_before = 0;
  while (all.status == SolveStatus::box_limit && all.roots.size() > roots_before &&
         boxes < tolerances::seed_solve_budget_factor * budget) {
    roots_before = all.roots.size();
    std::vector<UndecidedBox> unexplored;
    std::vector<UndecidedBox> kept;
    for (auto& u : all.undecided) (u.reason == UndecidedReason::budget ? unexplored : kept).push_back(std::move(u));
    all.undecided = std::move(kept);
    all.status = SolveStatus::undecided;
    for (std::size_t i = 0; i < unexplored.size(); ++i) {
      if (boxes >= tolerances::seed_solve_budget_factor * budget) {
        // Out of budget: what is left stays unexplored.
        all.undecided.insert(all.undecided.end(), unexplored.begin() + static_cast<std::ptrdiff_t>(i), unexplored.end());
        all.status = SolveStatus::box_limit;
        break;
      }
      SolveResult part = oracle.surface_critical(d, Domain{unexplored[i].box, domain.half_spaces}, budget);
      boxes += part.counters.boxes;
      all.counters += part.counters;
      if (part.status == SolveStatus::time_limit || part.status == SolveStatus::non_isolated) {
        part.counters = all.counters;
        return part;
      }
      if (part.status == SolveStatus::box_limit) all.status = SolveStatus::box_limit;
      all.roots.insert(all.roots.end(), part.roots.begin(), part.roots.end());
      all.undecided.insert(all.undecided.end(), part.undecided.begin(), part.undecided.end());
    }
  }
  if (all.status != SolveStatus::box_limit && all.undecided.empty()) all.status = SolveStatus::complete;
  return all;
}

}  // namespace delmesh
