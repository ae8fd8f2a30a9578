#include "meshing/witness.h"

#include "meshing/check_registry.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, CheckKind kind) { return out << check_kind_name(kind); }

}  // namespace delmesh
