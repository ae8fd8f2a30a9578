#include "meshing/driver/sample_topology.h"

#include <cmath>

#include "common/errors.h"
#include "common/seeded_uniform.h"
#include "common/tolerances.h"
#include "meshing/core/detail/vec3.h"

namespace delmesh {

using namespace detail;

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
