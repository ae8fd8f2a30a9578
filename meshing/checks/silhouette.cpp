#include "meshing/checks/silhouette.h"

#include <algorithm>
#include <cmath>

#include "common/seeded_uniform.h"
#include "meshing/checks/detail/candidates.h"
#include "meshing/core/detail/vec3.h"
#include "solvers/query_geometry.h"

namespace delmesh {

using namespace detail;

Vec3 silhouette_direction(const RestrictedDelaunay& restricted, VertexId p, const Vec3& n_p, int attempt) {
  const auto frame = orthonormal_frame(n_p);
  const double angle =
      2 * M_PI * seeded_uniform(attempt_seed(restricted.seed(), attempt), p, 0, generic_stream::silhouette_direction);
  return std::cos(angle) * frame.a + std::sin(angle) * frame.b;
}

CheckResult silhouette_witness(RestrictedDelaunay& restricted, VertexId p, bool facets_clean, int attempt) {
  const auto& del = restricted.delaunay();
  auto& oracle = restricted.oracle();
  // J_{n_p} ∩ V_p = ∅ proved by the kept or a new cell certificate: nothing to solve.
  if (restricted.cell_certified(p)) return {};
  const Vec3& pp = del.point(p);
  WitnessCollector collector(CheckKind::silhouette, p, pp);
  // The certificate failed on a proved point of J_{n_p} ∩ V_p: that point is the witness.
  if (attempt == 0) {
    if (const auto x = restricted.cell_silhouette_point(p)) {
      collector.add(*x);
      return collector.take();
    }
  }
  const Vec3 n_p = oracle.normal(pp);
  if (!(norm(n_p) > 0)) {
    // p is a sample of Σ, which is smooth: ∇E(p) = 0 means the evaluation failed.
    collector.add_unsettled(UnsettledReason::degenerate_face, pp);
    return collector.take();
  }
  const VoronoiCell cell = voronoi_cell(del, p, oracle.clip_box());
  if (!cell.valid) {
    // V_p ∋ p always has interior; an empty clipped cell is a numerical failure.
    collector.add_unsettled(UnsettledReason::degenerate_face, pp);
    return collector.take();
  }
  const Vec3 d2 = silhouette_direction(restricted, p, n_p, attempt);
  collector.add_result(oracle, cell, oracle.silhouette_critical(n_p, d2, cell.domain));
  if (collector.points() > 0) return collector.take();
  // Neighbours q such that a Voronoi edge of the facet pq meets Σ (see facets_clean).
  std::vector<VertexId> crossing;
  if (facets_clean) {
    for (const auto& t : del.incident_triangles(p)) {
      const auto& rec = restricted.voronoi_edge_record(t);
      if (rec.crossings().empty() && rec.candidates().empty() && rec.unresolved().empty()) continue;
      for (VertexId v : t)
        if (v != p) crossing.push_back(v);
    }
    std::sort(crossing.begin(), crossing.end());
  }
  for (VertexId q : cell.facet_neighbours) {
    if (facets_clean && !std::binary_search(crossing.begin(), crossing.end(), q)) continue;
    const VoronoiFacet& f = restricted.facet(make_edge_key(p, q));
    if (!f.valid) continue;
    // J_{n_p} ∩ F = ∅ proved by the gradient cone over F: nothing to solve on this facet.
    if (oracle.prove_gradient_cone(f.chart(), f.domain, n_p).proved) continue;
    collector.add_result(oracle, f, oracle.silhouette_plane(f.origin, f.a, f.b, n_p, f.domain));
    if (collector.points() > 0) return collector.take();
  }
  return collector.take();
}

}  // namespace delmesh
