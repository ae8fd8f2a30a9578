#include "meshing/checks/facet_cycle.h"

#include <cmath>
#include <limits>

#include "meshing/checks/detail/candidates.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/voronoi/detail/line_clip.h"

namespace delmesh {

using namespace detail;

namespace {

// The parameter interval [s0, s1] of {(ux + s, vx)} ∩ F, or nothing if it is empty.
std::optional<std::array<double, 2>> clip_line_to_facet(const VoronoiFacet& f, double ux, double vx) {
  if (vx < f.domain.box.bounds[1][0] || vx > f.domain.box.bounds[1][1]) return std::nullopt;
  LineClip line(f.domain.box.bounds[0][0] - ux, f.domain.box.bounds[0][1] - ux);
  for (const auto& h : f.domain.half_spaces)
    line.keep(h.normal[0], h.offset - h.normal[0] * ux - h.normal[1] * vx, std::hypot(h.normal[0], h.normal[1]));
  if (!line.nonempty()) return std::nullopt;
  return std::array<double, 2>{line.t0, line.t1};
}

}  // namespace

CheckResult facet_cycle_witness(RestrictedDelaunay& restricted, const EdgeKey& pq, int attempt) {
  if (restricted.facet_section_certified(pq)) return {};
  const VoronoiFacet& cached = restricted.facet(pq);
  if (!cached.valid) return {};
  // Another generic direction d: the same facet in another frame.
  const VoronoiFacet rotated = attempt > 0 ? restricted.rotated_facet(pq, attempt) : VoronoiFacet{};
  const VoronoiFacet& f = attempt > 0 ? rotated : cached;
  auto& oracle = restricted.oracle();
  const Vec3& p = restricted.delaunay().point(pq[0]);
  WitnessCollector collector(CheckKind::facet_cycle, pq[0], p);
  if (!f.valid) {
    // The cached facet is valid, so the same polygon in another frame is too, up to rounding.
    collector.add_unsettled(UnsettledReason::degenerate_face, p);
    return collector.take();
  }
  const auto critical = oracle.curve_critical(f.origin, f.a, f.b, f.domain);
  // (u, v) of each start, and whether it is the centre of an undecided region (then ℓ_x is not
  // known to pass through a critical point, and its points are candidate witnesses only).
  struct Start {
    double ux, vx;
    bool undecided;
  };
  std::vector<Start> starts;
  for (const auto& root : critical.roots) starts.push_back({root.midpoint[0], root.midpoint[1], false});
  for (const auto& u : critical.undecided)
    starts.push_back({0.5 * (u.box.bounds[0][0] + u.box.bounds[0][1]), 0.5 * (u.box.bounds[1][0] + u.box.bounds[1][1]),
                      true});
  for (const auto& [ux, vx, undecided_start] : starts) {
    // ℓ_x ∩ F = {(ux + s, vx)} clipped by the polygon's half-planes and bounding box.
    const auto range = clip_line_to_facet(f, ux, vx);
    if (range) {
      const auto line = oracle.surface_line(f.world(ux, vx), f.a, (*range)[0], (*range)[1]);
      for (const auto& root : line.roots) collector.add(root.world, undecided_start);
      for (const auto& u : line.undecided) collector.add_line_region(oracle, u);
      // Two points of Σ on ℓ_x ∩ F: a witness (the furthest from p first).  Fewer: the line's
      // points are no witness, but what it could not project stays unsettled.
      if (collector.points() >= 2) return collector.take();
      collector.drop_points();
    }
    // Lemma 4.9 speaks of lines through critical points.  A line through the centre of an
    // undecided region that meets Σ ∩ F in fewer than two points says nothing about a closed
    // curve elsewhere in the region, so the region stays unsettled.
    if (undecided_start) collector.add_unsettled(UnsettledReason::undecided_critical_region, f.world(ux, vx));
  }
  return collector.take();
}

}  // namespace delmesh
