#include "meshing/vor_edge.h"

#include "meshing/detail/candidates.h"

namespace delmesh {

std::optional<Witness> vor_edge_witness(RestrictedDelaunay& restricted, const TriangleKey& t) {
  const EdgeRecord& r = restricted.edge_record(t);
  const VertexId p = t[0];
  const Vec3& pp = restricted.delaunay().point(p);
  if (!r.candidates.empty())
    return Witness{r.candidates[detail::furthest_index(r.candidates, pp)], CheckKind::vor_edge, p, true};
  if (r.crossings.size() >= 2)
    return Witness{r.crossings[detail::furthest_index(r.crossings, pp)], CheckKind::vor_edge, p, false};
  return std::nullopt;
}

}  // namespace delmesh
