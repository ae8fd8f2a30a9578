#pragma once
//! \file progress_line.h
//! The progress of `delmesh mesh` on standard error.  The mesher reports every
//! tolerances::progress_interval_seconds ("<phase>: points N, queued …", RefinementLimits::progress)
//! and announces its later steps ("certifying the distance …").  On a terminal each report
//! rewrites one line in place: the phase, the points, the points per second since the previous
//! report and the seconds since the start.  Elsewhere (a file, a pipe) the same text is written as
//! plain lines, the refinement's at most one every progress_plain_interval_seconds, so a log stays
//! short.  The first report is preceded by the run's header line.

#include <chrono>
#include <cstddef>
#include <iosfwd>
#include <string>

namespace delmesh::app {

//! The least time between two plain progress lines (not on a terminal).
inline constexpr double progress_plain_interval_seconds = 5;

class ProgressLine {
 public:
  //! Writes to `out`; `terminal` chooses the line rewritten in place.  The clock starts now.
  ProgressLine(std::ostream& out, std::string header, bool terminal);
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  //! Ends the line on a terminal (finish()).
  ~ProgressLine();

  //! One report of the mesher, shown as the file comment says.
  void report(const std::string& message);
  //! Ends a line being rewritten with a newline, so that what follows starts on its own line.
  void finish();

  //! The text shown for a report at `elapsed` seconds: "<phase>: N points, R points/s, T s" for a
  //! refinement report, the message itself otherwise (with the elapsed seconds).
  std::string text(const std::string& message, double elapsed);

 private:
  std::ostream& out_;
  std::string header_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_;
  double last_shown_ = -1;    //!< seconds of the last plain refinement line (−1: none yet)
  bool refinement_report_ = false;  //!< the last message given to text() was a refinement report
  double last_report_ = 0;    //!< seconds of the previous refinement report
  std::size_t last_points_ = 0;
  bool pending_ = false;      //!< a line is open on the terminal
};

}  // namespace delmesh::app
