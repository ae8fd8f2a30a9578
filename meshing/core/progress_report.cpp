// The text of a progress report (progress_report.h).
#include "meshing/core/progress_report.h"

#include <sstream>

namespace delmesh {

std::string ProgressReport::text() const {
  if (phase == ProgressPhase::certifying) return "certifying the distance to the surface (gradient flow)";
  std::ostringstream s;
  s << phase << ": points " << points << ", queued";
  for (const QueueSize& q : queued) s << ' ' << q.name << '=' << q.size;
  return s.str();
}

}  // namespace delmesh
