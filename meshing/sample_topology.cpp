#include "meshing/sample_topology.h"

#include <cmath>

#include "common/errors.h"
#include "common/seeded_uniform.h"
#include "common/tolerances.h"
#include "meshing/detail/vec3.h"

namespace delmesh {

using namespace detail;

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

SeedReport insert_seeds(Refinement& refinement) {
  auto& oracle = refinement.oracle();
  const Box3& box = oracle.clip_box();
  const Domain domain =
      Domain::from_box({{box.lo[0], box.hi[0]}, {box.lo[1], box.hi[1]}, {box.lo[2], box.hi[2]}});
  SeedReport report;
  for (int k = 0; k < tolerances::mesher_height_direction_retries; ++k) {
    const Vec3 d = generic_direction(refinement.seed(), k);
    ++report.attempts;
    const auto result = seed_solve(oracle, d, domain);
    if (result.status == SolveStatus::time_limit) {
      report.time_limited = true;
      return report;
    }
    if (result.status == SolveStatus::non_isolated) continue;
    report.height_direction = d;
    std::vector<Vec3> points;
    for (const auto& root : result.roots) points.push_back(root.world);
    report.undecided = result.undecided.size();
    for (const auto& u : result.undecided) {
      if (auto x = oracle.project(u.world))
        points.push_back(*x);
      else
        refinement.report_unsettled({CheckKind::seed, UnsettledReason::unprojectable_region, u.world});
    }
    // No critical point and no undecided region: Σ is empty in the box.  Undecided regions that
    // could not be projected are not a proof of emptiness: they stay unsettled (reported above)
    // and the run goes on without seeds, to end uncertified.
    if (points.empty() && result.undecided.empty())
      throw InvalidInput("the surface is empty in the box: no critical point of E = 0 was found");
    for (const auto& x : points) {
      // A stop here leaves run() to report the limit.
      if (refinement.limit_passed()) break;
      if (refinement.insert(Witness{x, CheckKind::seed, -1, false})) ++report.seeds;
    }
    return report;
  }
  throw InvalidInput("cannot find a generic height direction: every direction tried gave non-isolated critical points");
}

SampleTopologyResult sample_topology(Refinement& refinement) {
  SampleTopologyResult result{insert_seeds(refinement)};
  if (result.seeds.time_limited) {
    result.status = MeshStatus::time_limit;
    return result;
  }
  result.status = refinement.run();
  for (VertexId id : refinement.delaunay().vertices()) {
    if (result.status != MeshStatus::complete) break;
    if (!refinement.delaunay().contains(id) || !refinement.delaunay().is_seed(id)) continue;
    refinement.remove(id);
    result.status = refinement.run();
  }
  return result;
}

}  // namespace delmesh
