#pragma once
//! \file mesh_status.h
//! How a run of the mesher ended (DelMeshResult::status, Refinement::run()).

#include <ostream>

#include "common/enum_names.h"

namespace delmesh {

//! complete: every check of §5.3 (and, with phase all, Quality, size and Smooth) ran clean on
//! every face of the final Vor S, every solver region was decided or became a witness, every
//! answer of the oracle was certified (SurfaceOracle::gave_uncertified_answers() is false; the
//! homotopy backend's path tracking is not certified, so a run that tracked a path is never
//! complete), and Tri S|Σ is a closed, consistently oriented 2-manifold.  uncertified: the run
//! ended but something of that was not settled (listed under "unsettled" in the statistics, or
//! "solver_certified": false); the mesh is written, without the guarantee.  point_limit / time_limit: stopped by a limit;
//! interrupted: stopped by DelMeshOptions::interrupt (e.g. Ctrl-C).
enum class MeshStatus { complete, point_limit, time_limit, uncertified, interrupted };
constexpr auto enum_names(MeshStatus) {
  return name_table<MeshStatus>("MeshStatus", {{MeshStatus::complete, "complete"},
                                               {MeshStatus::point_limit, "point_limit"},
                                               {MeshStatus::time_limit, "time_limit"},
                                               {MeshStatus::uncertified, "uncertified"},
                                               {MeshStatus::interrupted, "interrupted"}});
}
inline std::ostream& operator<<(std::ostream& out, MeshStatus status) { return write_enum(out, status); }

}  // namespace delmesh
