// Closed-ball refinement and the status rule of a PL run.  See closed_ball_refinement.h.
#include "meshing/driver/closed_ball_refinement.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <set>
#include <utility>

#include "common/tolerances.h"
#include "meshing/checks/check_registry.h"
#include "meshing/checks/smooth.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/voronoi/restricted_voronoi_mesh.h"
#include "meshing/voronoi/voronoi_geometry.h"

namespace delmesh {

namespace {

using namespace detail;

using Seconds = std::chrono::duration<double>;

// The check on the current samples (ascending ids); record.sample_ids maps back.
void check_now(Refinement& refinement, const SurfaceMesh& sigma, ClosedBallRefinement& record) {
  const auto& del = refinement.delaunay();
  record.sample_ids = del.vertices();
  std::vector<Point3> samples;
  samples.reserve(record.sample_ids.size());
  for (VertexId v : record.sample_ids) {
    const auto& p = del.point(v);
    samples.emplace_back(p[0], p[1], p[2]);
  }
  record.last = closed_ball_check(samples, sigma);
  record.last_is_current = true;
  ++record.checks;
}

// The row whose floor and counts a closed-ball witness takes: the topology row of the face's
// dimension (cells TopoDisk, facets FacetCycle, Voronoi edges VorEdge).
CheckKind witness_kind(int dimension) {
  return dimension == 3 ? CheckKind::topo_disk : dimension == 2 ? CheckKind::facet_cycle : CheckKind::vor_edge;
}

bool is_topology_row(CheckKind kind) {
  switch (kind) {
    case CheckKind::seed:
    case CheckKind::vor_edge:
    case CheckKind::facet_contact:
    case CheckKind::topo_disk:
    case CheckKind::facet_cycle:
    case CheckKind::silhouette:
      return true;
    default:
      return false;
  }
}

// Where Tri S|Σ and Del S|Σ differ at t (PlStatusDecision's mismatch counts).
void classify_mismatch(Refinement& refinement, const TriangleKey& t, PlStatusDecision& d) {
  const Delaunay& del = refinement.delaunay();
  const auto apexes = del.triangle_apexes(t);
  if (!apexes) {
    ++d.mismatch_not_delaunay;
    return;
  }
  for (VertexId a : *apexes) {
    if (a < 0) continue;
    std::array<VertexId, 4> cell{t[0], t[1], t[2], a};
    std::sort(cell.begin(), cell.end());
    const Vec3 c = voronoi_vertex(del, cell);
    const auto x = refinement.oracle().project(c);
    if (!x) continue;
    const double radius = norm(c - del.point(t[0]));
    if (norm(c - *x) <= mismatch_vertex_relative_distance * radius) {
      ++d.mismatch_at_voronoi_vertex;
      return;
    }
  }
  ++d.mismatch_elsewhere;
}

}  // namespace

MeshStatus refine_closed_ball(Refinement& refinement, const SurfaceMesh& sigma, MeshStatus status,
                              ClosedBallRefinement& record) {
  const auto start = std::chrono::steady_clock::now();
  while (status == MeshStatus::complete) {
    if (refinement.limit_passed()) break;
    check_now(refinement, sigma, record);
    if (record.last.status != ClosedBallStatus::violated) break;
    std::size_t inserted = 0;
    for (const auto& v : record.last.violations) {
      if (refinement.limit_passed()) break;
      const Witness w{v.witness, witness_kind(v.dimension), record.sample_ids[v.sites.front()], false};
      if (refinement.insert(w)) {
        ++inserted;
      } else {
        ++record.witnesses_rejected;
      }
    }
    record.witnesses_inserted += inserted;
    if (inserted == 0) break;
    record.last_is_current = false;
    ++record.rounds;
    status = refinement.run();
  }
  record.seconds += Seconds(std::chrono::steady_clock::now() - start).count();
  return status;
}

PlStatusDecision decide_pl_status(Refinement& refinement, const ClosedBallRefinement& record, MeshStatus run_status,
                                  const Certification& certification, bool output_defective,
                                  bool solver_certified, double lambda, bool geometry) {
  PlStatusDecision d;
  d.status = certification.status;
  if (!solver_certified && d.status == MeshStatus::complete) d.status = MeshStatus::uncertified;
  // The check speaks of the final S only if no sample was inserted or removed since (a later
  // phase's run() may have inserted many).
  d.check_current = record.last_is_current && refinement.delaunay().vertices() == record.sample_ids;
  if (!d.check_current) {
    d.blocking = certification.unsettled.size();
    return d;
  }
  // (b): Tri S|Σ against Del S|Σ, as sets of id triples.
  std::vector<TriangleKey> tri = refinement.restricted().triangles();
  for (auto& t : tri) std::sort(t.begin(), t.end());
  std::sort(tri.begin(), tri.end());
  std::vector<TriangleKey> del;
  del.reserve(record.last.restricted_delaunay.size());
  for (const auto& s : record.last.restricted_delaunay) {
    TriangleKey t{record.sample_ids[s[0]], record.sample_ids[s[1]], record.sample_ids[s[2]]};
    std::sort(t.begin(), t.end());
    del.push_back(t);
  }
  std::sort(del.begin(), del.end());
  std::vector<TriangleKey> only;
  std::set_difference(del.begin(), del.end(), tri.begin(), tri.end(), std::back_inserter(only));
  d.only_restricted_delaunay = only.size();
  std::set_difference(tri.begin(), tri.end(), del.begin(), del.end(), std::back_inserter(only));
  d.only_output = only.size() - d.only_restricted_delaunay;
  for (const auto& t : only) classify_mismatch(refinement, t, d);
  const bool repeated = std::adjacent_find(tri.begin(), tri.end()) != tri.end();
  d.output_equals_restricted_delaunay = d.only_restricted_delaunay == 0 && d.only_output == 0 && !repeated;
  d.proves_homeomorphism = record.last.status == ClosedBallStatus::holds && d.output_equals_restricted_delaunay;
  if (!d.proves_homeomorphism) {
    d.blocking = certification.unsettled.size();
    return d;
  }

  // Smooth findings: the edges giving each location, each with whether it is a crease edge
  // (smooth_exempt_edge, the rule the Smooth check applied during the refinement).
  std::map<std::array<double, 3>, std::vector<bool>> smooth_edges;
  const bool any_smooth = std::any_of(certification.unsettled.begin(), certification.unsettled.end(),
                                      [](const Unsettled& u) { return u.check == CheckKind::smooth; });
  if (any_smooth && geometry && lambda < beta_lambda_bound) {
    const double threshold = 2 * beta(lambda);
    std::set<EdgeKey> edges;
    for (const auto& t : tri)
      for (const auto& e : {make_edge_key(t[0], t[1]), make_edge_key(t[0], t[2]), make_edge_key(t[1], t[2])})
        edges.insert(e);
    for (const auto& e : edges)
      if (auto w = smooth_witness(refinement.restricted(), e, threshold))
        smooth_edges[w->point].push_back(smooth_exempt_edge(refinement.restricted(), e));
  }
  const auto crease_smooth = [&](const Unsettled& u) {
    if (u.check != CheckKind::smooth) return false;
    const auto it = smooth_edges.find(u.location);
    if (it == smooth_edges.end()) return false;
    return std::all_of(it->second.begin(), it->second.end(), [](bool crease) { return crease; });
  };
  for (const auto& u : certification.unsettled) {
    const bool integrity = u.reason == UnsettledReason::record_count_mismatch;
    if (!integrity && is_topology_row(u.check)) {
      d.exempt[check_kind_name(u.check)][std::string(enum_name(u.reason))] += 1;
      ++d.exempt_count;
    } else if (crease_smooth(u)) {
      d.exempt[check_kind_name(u.check)][std::string(enum_name(u.reason)) + " (crease)"] += 1;
      ++d.exempt_count;
    } else {
      ++d.blocking;
    }
  }
  if (run_status == MeshStatus::complete && d.blocking == 0 && !output_defective && solver_certified)
    d.status = MeshStatus::complete;
  return d;
}

nlohmann::json closed_ball_refinement_json(const ClosedBallRefinement& record, const PlStatusDecision& decision) {
  nlohmann::json j = record.checks > 0 ? closed_ball_json(record.last, tolerances::floor_locations_listed)
                                       : nlohmann::json{{"status", "not attempted"}};
  j["current"] = decision.check_current;
  j["checks"] = record.checks;
  j["rounds"] = record.rounds;
  j["witnesses_inserted"] = record.witnesses_inserted;
  j["witnesses_rejected"] = record.witnesses_rejected;
  j["seconds_refinement"] = record.seconds;
  j["output_equals_restricted_delaunay"] = decision.output_equals_restricted_delaunay;
  j["only_restricted_delaunay"] = decision.only_restricted_delaunay;
  j["only_output"] = decision.only_output;
  j["mismatch"] = {{"at_voronoi_vertex", decision.mismatch_at_voronoi_vertex},
                   {"not_delaunay", decision.mismatch_not_delaunay},
                   {"elsewhere", decision.mismatch_elsewhere},
                   {"vertex_relative_distance", mismatch_vertex_relative_distance}};
  j["proves_homeomorphism"] = decision.proves_homeomorphism;
  j["exempt"] = {{"count", decision.exempt_count},
                 {"by_kind", decision.exempt},
                 {"blocking", decision.blocking},
                 {"rule",
                  "closed-ball property holds and Tri S|Σ = Del S|Σ (Edelsbrunner-Shah): topology-row findings, "
                  "and Smooth findings on edges whose Voronoi facet meets a sharp input edge at the run's feature "
                  "angle (input_mesh.features), do not block complete"}};
  return j;
}

}  // namespace delmesh
