// Tests of the progress line (apps/progress_line.h) from constructed reports: the text (phase,
// points, rate, elapsed seconds), the line rewritten in place on a terminal, and the throttled
// plain lines elsewhere.
#include <boost/test/unit_test.hpp>

#include <sstream>
#include <string>

#include "apps/progress_line.h"

using namespace delmesh;
using delmesh::app::ProgressLine;

namespace {

ProgressReport refinement(ProgressPhase phase, std::size_t points, double elapsed) {
  ProgressReport r;
  r.phase = phase;
  r.points = points;
  r.queued = {{"vor_edge", 3}};
  r.elapsed_seconds = elapsed;
  return r;
}

ProgressReport certifying(std::size_t points, double elapsed) {
  ProgressReport r;
  r.phase = ProgressPhase::certifying;
  r.points = points;
  r.elapsed_seconds = elapsed;
  return r;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(progress_line_test)

BOOST_AUTO_TEST_CASE(text_has_phase_points_rate_and_elapsed_seconds) {
  std::ostringstream out;
  ProgressLine line(out, "", false);
  // The first rate counts from the run's start; the next from the previous refinement report.
  BOOST_TEST(line.text(refinement(ProgressPhase::topology, 1000, 0.5)) == "topology: 1000 points, 2000 points/s, 0.5 s");
  BOOST_TEST(line.text(refinement(ProgressPhase::geometry, 4000, 2.0)) == "geometry: 4000 points, 2000 points/s, 2.0 s");
  // No time between two reports, or fewer points: no rate.
  BOOST_TEST(line.text(refinement(ProgressPhase::geometry, 4100, 2.0)) == "geometry: 4100 points, 2.0 s");
  BOOST_TEST(line.text(refinement(ProgressPhase::geometry, 50, 3.0)) == "geometry: 50 points, 3.0 s");
  // Not a refinement report: its own text, with the seconds; the queue names never show.
  const std::string announced = line.text(certifying(4100, 3.3));
  BOOST_TEST(announced == "certifying the distance to the surface (gradient flow), 3.3 s");
  BOOST_TEST(line.text(refinement(ProgressPhase::geometry, 60, 4.0)).find("vor_edge") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_terminal_line_is_rewritten_in_place_after_the_header) {
  std::ostringstream out;
  {
    ProgressLine line(out, "delmesh: meshing torus", true);
    line.report(refinement(ProgressPhase::topology, 100, 0.5));
    line.report(refinement(ProgressPhase::topology, 300, 1.0));
    line.report(certifying(300, 1.5));
  }  // the destructor ends the line
  BOOST_TEST(out.str() ==
             "delmesh: meshing torus\n"
             "\r\033[Kdelmesh: topology: 100 points, 200 points/s, 0.5 s"
             "\r\033[Kdelmesh: topology: 300 points, 400 points/s, 1.0 s"
             "\r\033[Kdelmesh: certifying the distance to the surface (gradient flow), 1.5 s\n");
}

BOOST_AUTO_TEST_CASE(plain_lines_show_a_refinement_report_at_most_every_five_seconds) {
  std::ostringstream out;
  ProgressLine line(out, "delmesh: meshing torus", false);
  for (int k = 1; k <= 24; ++k) line.report(refinement(ProgressPhase::geometry, 100 * k, 0.5 * k));
  line.report(certifying(2400, 12.2));
  line.finish();  // nothing open: no extra newline
  // Reports at 0.5, 5.5 and 10.5 s are shown (the 0.5 s rate is over the half second before each).
  BOOST_TEST(out.str() ==
             "delmesh: meshing torus\n"
             "delmesh: geometry: 100 points, 200 points/s, 0.5 s\n"
             "delmesh: geometry: 1100 points, 200 points/s, 5.5 s\n"
             "delmesh: geometry: 2100 points, 200 points/s, 10.5 s\n"
             "delmesh: certifying the distance to the surface (gradient flow), 12.2 s\n");
}

BOOST_AUTO_TEST_CASE(nothing_is_written_without_a_report) {
  std::ostringstream out;
  { ProgressLine line(out, "delmesh: meshing torus", true); }
  BOOST_TEST(out.str().empty());
}

BOOST_AUTO_TEST_SUITE_END()
