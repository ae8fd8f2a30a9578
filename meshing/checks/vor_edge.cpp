#include "meshing/checks/vor_edge.h"

#include "meshing/checks/detail/candidates.h"

namespace delmesh {

CheckResult vor_edge_witness(RestrictedDelaunay& restricted, const TriangleKey& t) {
  const VoronoiEdgeRecord& r = restricted.voronoi_edge_record(t);
  const VertexId p = t[0];
  const Vec3& pp = restricted.delaunay().point(p);
  // Tangency candidates first; the crossings (when there are two or more) after them.
  detail::WitnessCollector candidates(CheckKind::vor_edge, p, pp), crossings(CheckKind::vor_edge, p, pp);
  for (const auto& x : r.candidates()) candidates.add(x, true);
  if (r.crossings().size() >= 2)
    for (const auto& x : r.crossings()) crossings.add(x);
  CheckResult result = candidates.take();
  for (auto& w : crossings.take().witnesses) result.witnesses.push_back(w);
  return result;
}

}  // namespace delmesh
