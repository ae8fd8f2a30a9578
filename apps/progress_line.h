#pragma once
//! \file progress_line.h
//! The progress of `delmesh mesh` on standard error, from the mesher's reports
//! (meshing/core/progress_report.h): the refinement's every tolerances::progress_interval_seconds and
//! one when the distance certificate starts.  On a terminal each report rewrites one line in
//! place: the phase, the points, the points per second since the previous refinement report and
//! the seconds since the run started.  Elsewhere (a file, a pipe) the same text is written as
//! plain lines, the refinement's at most one every progress_plain_interval_seconds, so a log stays
//! short.  The first report is preceded by the run's header line.

#include <cstddef>
#include <iosfwd>
#include <string>

#include "meshing/core/progress_report.h"

namespace delmesh::app {

//! The least time between two plain progress lines (not on a terminal).
inline constexpr double progress_plain_interval_seconds = 5;

class ProgressLine {
 public:
  //! Writes to `out`; `terminal` chooses the line rewritten in place.
  ProgressLine(std::ostream& out, std::string header, bool terminal);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  //! Ends the line on a terminal (finish()).
  ~ProgressLine();

  //! One report of the mesher, shown as the file comment says.
  void report(const ProgressReport& report);
  //! Ends a line being rewritten with a newline, so that what follows starts on its own line.
  void finish();

  //! The text shown for `report` (without the "delmesh: " prefix): for a refinement report
  //! "<phase>: N points, R points/s, T s", the rate over the time since the previous refinement
  //! report given here (since the run's start for the first) and left out when that time is not
  //! positive or the points went down; for another report its text() and ", T s".  T is the
  //! report's elapsed seconds, R and T fixed-point with 0 and 1 decimals.
  std::string text(const ProgressReport& report);

 private:
  std::ostream& out_;
  std::string header_;
  bool terminal_;
  double last_shown_ = -1;    //!< seconds of the last plain refinement line (−1: none yet)
  double last_report_ = 0;    //!< seconds of the previous refinement report
  std::size_t last_points_ = 0;
  bool pending_ = false;      //!< a line is open on the terminal
};

}  // namespace delmesh::app
