#include "meshing/facet_contact.h"

#include "meshing/detail/candidates.h"

namespace delmesh {

std::optional<Witness> facet_contact_witness(RestrictedDelaunay& restricted, const EdgeKey& pq) {
  const VoronoiFacet& f = restricted.facet(pq);
  if (!f.valid || restricted.facet_section_certified(pq)) return std::nullopt;
  auto& oracle = restricted.oracle();
  const auto result = oracle.surface_plane_contact(f.origin, f.a, f.b, f.domain);
  std::vector<Vec3> points;
  for (const auto& u : result.undecided)
    if (auto x = detail::facet_candidate(oracle, f, u)) points.push_back(*x);
  // A solver that certifies contacts (not in exclusion mode) would report them as roots.
  for (const auto& root : result.roots) points.push_back(root.world);
  if (points.empty()) return std::nullopt;
  const Vec3& p = restricted.delaunay().point(pq[0]);
  return Witness{points[detail::furthest_index(points, p)], CheckKind::facet_contact, pq[0], true};
}

}  // namespace delmesh
