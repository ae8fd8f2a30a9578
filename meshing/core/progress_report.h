#pragma once
//! \file progress_report.h
//! What a run of the mesher reports while it runs (DelMeshOptions::progress,
//! RefinementLimits::progress): the phase, the samples so far, the refinement's queue sizes and
//! the seconds since the run started, and the same as one line of text (text()).  The refinement
//! reports at most every tolerances::progress_interval_seconds, at its clock readings; del_mesh
//! reports once when the distance certificate starts.

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "common/enum_names.h"

namespace delmesh {

//! The phases that report progress: SampleTopology's refinement (topology rows only), the
//! refinement with the geometry rows (Quality, Smooth and the registered geometry checks), and
//! the gradient-flow certificate of the finished mesh.
enum class ProgressPhase { topology, geometry, certifying };
constexpr auto enum_names(ProgressPhase) {
  return name_table<ProgressPhase>("ProgressPhase", {{ProgressPhase::topology, "topology"},
                                                     {ProgressPhase::geometry, "geometry"},
                                                     {ProgressPhase::certifying, "certifying"}});
}
inline std::ostream& operator<<(std::ostream& out, ProgressPhase phase) { return write_enum(out, phase); }

//! The size of one refinement queue: the row's name in the check table and its queued simplices.
struct QueueSize {
  std::string name;
  std::size_t size = 0;
};

//! One progress report.  Within a run the reports come in order of time: elapsed_seconds and
//! points do not decrease, and the phases come in the order of ProgressPhase.
struct ProgressReport {
  ProgressPhase phase = ProgressPhase::topology;
  //! The samples so far (the refinement's Delaunay vertices); when certifying, the samples the
  //! refinement ended with.
  std::size_t points = 0;
  //! The refinement's enabled rows in table order with their queue sizes; empty when certifying.
  std::vector<QueueSize> queued;
  double elapsed_seconds = 0;  //!< since the run's clock started (the clock of its time limit)

  //! The report as one line: "topology: points 1234, queued vor_edge=5 …" for the refinement,
  //! "certifying the distance to the surface (gradient flow)" for the certificate.
  std::string text() const;
};

}  // namespace delmesh
