#include "meshing/witness.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, CheckKind kind) {
  switch (kind) {
    case CheckKind::seed: return out << "seed";
    case CheckKind::vor_edge: return out << "vor_edge";
    case CheckKind::facet_contact: return out << "facet_contact";
    case CheckKind::topo_disk: return out << "topo_disk";
    case CheckKind::facet_cycle: return out << "facet_cycle";
    case CheckKind::silhouette: return out << "silhouette";
    case CheckKind::quality: return out << "quality";
    case CheckKind::smooth: return out << "smooth";
    case CheckKind::size: return out << "size";
  }
  return out << "unknown";
}

std::ostream& operator<<(std::ostream& out, UnsettledReason reason) {
  switch (reason) {
    case UnsettledReason::unprojectable_region: return out << "unprojectable_region";
    case UnsettledReason::region_outside_face: return out << "region_outside_face";
    case UnsettledReason::degenerate_face: return out << "degenerate_face";
    case UnsettledReason::rejected_witness: return out << "rejected_witness";
    case UnsettledReason::no_witness: return out << "no_witness";
    case UnsettledReason::unresolved_crossing: return out << "unresolved_crossing";
  }
  return out << "unknown";
}

}  // namespace delmesh
