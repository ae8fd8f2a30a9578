// The progress line (progress_line.h): format a report of the mesher, and either rewrite the
// terminal's line or write a throttled plain line.
#include "apps/progress_line.h"

#include <iomanip>
#include <ostream>
#include <sstream>
#include <utility>

namespace delmesh::app {

namespace {

bool is_refinement(const ProgressReport& report) {
  return report.phase == ProgressPhase::topology || report.phase == ProgressPhase::geometry;
}

}  // namespace

ProgressLine::ProgressLine(std::ostream& out, std::string header, bool terminal)
    : out_(out), header_(std::move(header)), terminal_(terminal) {}

ProgressLine::~ProgressLine() { finish(); }

std::string ProgressLine::text(const ProgressReport& report) {
  std::ostringstream s;
  s << std::fixed;
  const double elapsed = report.elapsed_seconds;
  if (is_refinement(report)) {
    s << report.phase << ": " << report.points << " points";
    const double interval = elapsed - last_report_;
    if (interval > 0 && report.points >= last_points_)
      s << ", " << std::setprecision(0) << static_cast<double>(report.points - last_points_) / interval
        << " points/s";
    last_report_ = elapsed;
    last_points_ = report.points;
  } else {
    s << report.text();
  }
  s << ", " << std::setprecision(1) << elapsed << " s";
  return s.str();
}

void ProgressLine::report(const ProgressReport& report) {
  if (!header_.empty()) {
    out_ << header_ << std::endl;
    header_.clear();
  }
  const std::string line = "delmesh: " + text(report);
  if (terminal_) {
    // Carriage return, then erase to the end of the line (ECMA-48 EL).
    out_ << "\r\033[K" << line << std::flush;
    pending_ = true;
    return;
  }
  if (is_refinement(report)) {
    if (last_shown_ >= 0 && report.elapsed_seconds - last_shown_ < progress_plain_interval_seconds) return;
    last_shown_ = report.elapsed_seconds;
  }
  out_ << line << std::endl;
}

void ProgressLine::finish() {
  if (!pending_) return;
  out_ << std::endl;
  pending_ = false;
}

}  // namespace delmesh::app
