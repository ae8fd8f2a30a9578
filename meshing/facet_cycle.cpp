#include "meshing/facet_cycle.h"

#include <cmath>
#include <limits>

#include "meshing/detail/candidates.h"
#include "meshing/detail/vec3.h"

namespace delmesh {

using namespace detail;

std::optional<Witness> facet_cycle_witness(RestrictedDelaunay& restricted, const EdgeKey& pq) {
  const VoronoiFacet& f = restricted.facet(pq);
  if (!f.valid || restricted.facet_section_certified(pq)) return std::nullopt;
  auto& oracle = restricted.oracle();
  const auto critical = oracle.curve_critical(f.origin, f.a, f.b, f.domain);
  std::vector<std::array<double, 2>> starts;
  for (const auto& root : critical.roots) starts.push_back({root.midpoint[0], root.midpoint[1]});
  bool from_undecided = false;
  for (const auto& u : critical.undecided) {
    starts.push_back({0.5 * (u.box.bounds[0][0] + u.box.bounds[0][1]),
                      0.5 * (u.box.bounds[1][0] + u.box.bounds[1][1])});
    from_undecided = true;
  }
  const Vec3& p = restricted.delaunay().point(pq[0]);
  for (const auto& [ux, vx] : starts) {
    // ℓ_x ∩ F = {(ux + s, vx)} clipped by the polygon's half-planes and bounding box.
    double s0 = f.domain.box.bounds[0][0] - ux, s1 = f.domain.box.bounds[0][1] - ux;
    if (vx < f.domain.box.bounds[1][0] || vx > f.domain.box.bounds[1][1]) continue;
    bool empty = false;
    for (const auto& h : f.domain.half_spaces) {
      const double rhs = h.offset - h.normal[0] * ux - h.normal[1] * vx;
      if (std::abs(h.normal[0]) < 1e-300) {
        if (rhs < 0) empty = true;
        continue;
      }
      const double bound = rhs / h.normal[0];
      if (h.normal[0] > 0)
        s1 = std::min(s1, bound);
      else
        s0 = std::max(s0, bound);
    }
    if (empty || !(s0 < s1)) continue;
    const auto line = oracle.surface_line(f.world(ux, vx), f.a, s0, s1);
    std::vector<Vec3> points;
    for (const auto& root : line.roots) points.push_back(root.world);
    for (const auto& u : line.undecided) {
      const auto x = oracle.project(u.world);
      points.push_back(x ? *x : u.world);
      if (u.reason != UndecidedReason::boundary_root) from_undecided = true;
    }
    if (points.size() >= 2)
      return Witness{points[furthest_index(points, p)], CheckKind::facet_cycle, pq[0], from_undecided};
  }
  return std::nullopt;
}

}  // namespace delmesh
