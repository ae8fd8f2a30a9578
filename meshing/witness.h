#pragma once
//! \file witness.h
//! A witness: a point of Σ returned by one of the checks of §5.3 (or by Quality, Smooth, size
//! control), to be inserted into S.

#include <array>
#include <ostream>

#include "meshing/delaunay.h"

namespace delmesh {

//! Which procedure produced a sample point.
enum class CheckKind { seed, vor_edge, facet_contact, topo_disk, facet_cycle, silhouette, quality, smooth, size };
std::ostream& operator<<(std::ostream& out, CheckKind kind);
inline constexpr int check_kind_count = 9;

struct Witness {
  std::array<double, 3> point{};
  CheckKind kind = CheckKind::vor_edge;
  VertexId measured_from = -1;  //!< the sample p the paper measures the witness from
  bool from_undecided = false;  //!< obtained from an undecided solver region (candidate)
};

}  // namespace delmesh
