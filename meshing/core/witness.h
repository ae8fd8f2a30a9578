#pragma once
//! \file witness.h
//! A witness: a point of Σ returned by one of the checks of §5.3 (or by Quality, Smooth, size
//! control), to be inserted into S; and what a check says about its face: the witnesses it found
//! and what it could not settle.

#include <array>
#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "meshing/core/simplex_keys.h"

namespace delmesh {

//! Which procedure produced a sample point: a seed, a check of the paper, the size and distance
//! controls of the Quality row (quality.h), or (the values after distance) a check registered by the program (meshing/checks/check_registry.h: CheckRegistration, which
//! also gives the number of kinds, check_kind_count()).
enum class CheckKind : int { seed, vor_edge, facet_contact, topo_disk, facet_cycle, silhouette, quality, smooth, size, distance };
//! The names of the paper's kinds; a registered kind is named by its registry row (check_kind_name).
constexpr auto enum_names(CheckKind) {
  return name_table<CheckKind>("CheckKind", {{CheckKind::seed, "seed"}, {CheckKind::vor_edge, "vor_edge"},
                                             {CheckKind::facet_contact, "facet_contact"},
                                             {CheckKind::topo_disk, "topo_disk"},
                                             {CheckKind::facet_cycle, "facet_cycle"},
                                             {CheckKind::silhouette, "silhouette"}, {CheckKind::quality, "quality"},
                                             {CheckKind::smooth, "smooth"}, {CheckKind::size, "size"},
                                             {CheckKind::distance, "distance"}});
}
//! The kind's name in the statistics (check_kind_name; defined with the registry,
//! meshing/checks/check_registry.cpp).
std::ostream& operator<<(std::ostream& out, CheckKind kind);

struct Witness {
  std::array<double, 3> point{};
  CheckKind kind = CheckKind::vor_edge;
  VertexId measured_from = -1;  //!< the sample p the paper measures the witness from
  bool from_undecided = false;  //!< obtained from an undecided solver region (candidate)
};

//! Why a check could not show its face clean.  Each one keeps the run from ending `complete`
//! while the face is part of the final Vor S.
enum class UnsettledReason {
  unprojectable_region,  //!< an undecided solver region whose Newton projection onto Σ failed
  region_outside_face,   //!< an undecided region whose projection left the face by more than its diameter
  degenerate_face,       //!< the Voronoi face is numerically degenerate and Σ may meet it
  rejected_witness,      //!< every witness found lies within the duplicate tolerance of a sample
  no_witness,            //!< the check's condition fails but it found no point of Σ to insert
  unresolved_crossing,   //!< an undecided region on a Voronoi edge that is neither a crossing nor a candidate
  record_count_mismatch,  //!< the Voronoi-edge records are not one per Delaunay triangle (no location)
  //! an undecided CurveCritical region whose line gave no witness: a closed curve of Σ ∩ F may lie in it
  undecided_critical_region,
  //! a final Voronoi-edge record holds a tangency candidate or two crossings (VorEdge's condition fails)
  vor_edge_fires
};
constexpr auto enum_names(UnsettledReason) {
  return name_table<UnsettledReason>("UnsettledReason", {{UnsettledReason::unprojectable_region, "unprojectable_region"},
                                                         {UnsettledReason::region_outside_face, "region_outside_face"},
                                                         {UnsettledReason::degenerate_face, "degenerate_face"},
                                                         {UnsettledReason::rejected_witness, "rejected_witness"},
                                                         {UnsettledReason::no_witness, "no_witness"},
                                                         {UnsettledReason::unresolved_crossing, "unresolved_crossing"},
                                                         {UnsettledReason::record_count_mismatch, "record_count_mismatch"},
                                                         {UnsettledReason::undecided_critical_region, "undecided_critical_region"},
                                                         {UnsettledReason::vor_edge_fires, "vor_edge_fires"}});
}
inline std::ostream& operator<<(std::ostream& out, UnsettledReason reason) { return write_enum(out, reason); }

//! One thing a check left unsettled, where it was.
struct Unsettled {
  CheckKind check = CheckKind::vor_edge;
  UnsettledReason reason = UnsettledReason::unprojectable_region;
  std::array<double, 3> location{};
};

//! The outcome of one check on one face: the witnesses (points of Σ), the one the paper asks
//! for first and the others as fall-backs in order of preference, and what was left unsettled.
//! The face is clean only if both are empty.
struct CheckResult {
  std::vector<Witness> witnesses;
  std::vector<Unsettled> unsettled;
  bool clean() const { return witnesses.empty() && unsettled.empty(); }
};

}  // namespace delmesh
