// The progress line (progress_line.h): parse a refinement report, format it, and either rewrite
// the terminal's line or write a throttled plain line.
#include "apps/progress_line.h"

#include <cstdio>
#include <iomanip>
#include <ostream>
#include <regex>
#include <sstream>
#include <utility>

namespace delmesh::app {

ProgressLine::ProgressLine(std::ostream& out, std::string header, bool terminal)
    : out_(out), header_(std::move(header)), terminal_(terminal), start_(std::chrono::steady_clock::now()) {}

ProgressLine::~ProgressLine() { finish(); }

std::string ProgressLine::text(const std::string& message, double elapsed) {
  static const std::regex refinement(R"(^(\w+): points (\d+)\b.*)");
  std::smatch m;
  std::ostringstream s;
  s << std::fixed;
  refinement_report_ = std::regex_match(message, m, refinement);
  if (refinement_report_) {
    const std::size_t points = std::stoull(m[2].str());
    s << m[1].str() << ": " << points << " points";
    const double interval = elapsed - last_report_;
    if (interval > 0 && points >= last_points_)
      s << ", " << std::setprecision(0) << static_cast<double>(points - last_points_) / interval << " points/s";
    last_report_ = elapsed;
    last_points_ = points;
  } else {
    s << message;
  }
  s << ", " << std::setprecision(1) << elapsed << " s";
  return s.str();
}

void ProgressLine::report(const std::string& message) {
  if (!header_.empty()) {
    out_ << header_ << std::endl;
    header_.clear();
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string line = "delmesh: " + text(message, elapsed);
  if (terminal_) {
    // Carriage return, then erase to the end of the line (ECMA-48 EL).
    out_ << "\r\033[K" << line << std::flush;
    pending_ = true;
    return;
  }
  if (refinement_report_) {
    if (last_shown_ >= 0 && elapsed - last_shown_ < progress_plain_interval_seconds) return;
    last_shown_ = elapsed;
  }
  out_ << line << std::endl;
}

void ProgressLine::finish() {
  if (!pending_) return;
  out_ << std::endl;
  pending_ = false;
}

}  // namespace delmesh::app
