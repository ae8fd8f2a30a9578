#include "meshing/witness.h"

#include "meshing/check_registry.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, CheckKind kind) { return out << check_kind_name(kind); }

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
