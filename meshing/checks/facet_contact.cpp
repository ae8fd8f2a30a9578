#include "meshing/checks/facet_contact.h"

#include "meshing/checks/detail/candidates.h"

namespace delmesh {

CheckResult facet_contact_witness(RestrictedDelaunay& restricted, const EdgeKey& pq) {
  // A certified section settles the facet, whatever its geometry (the cell's proof needs none).
  if (restricted.facet_section_certified(pq)) return {};
  const VoronoiFacet& f = restricted.facet(pq);
  auto& oracle = restricted.oracle();
  detail::WitnessCollector collector(CheckKind::facet_contact, pq[0], restricted.delaunay().point(pq[0]));
  if (!f.valid) {
    // The facet checks of a degenerate facet are reported here, once.
    collector.add_degenerate_facet(oracle, f);
    return collector.take();
  }
  // A solver in exclusion mode (the implicit oracle) answers with undecided regions only; one
  // that certifies contacts (the mesh oracle) with roots only.
  collector.add_result(oracle, f, oracle.surface_plane_contact(f.origin, f.a, f.b, f.domain));
  return collector.take();
}

}  // namespace delmesh
