// Tests of the progress reports (meshing/core/progress_report.h): their text, and the reports of a
// torus run through del_mesh — in order of time, with non-decreasing points, the phases in order.
#include <boost/test/unit_test.hpp>

#include <sstream>
#include <vector>

#include "meshing/core/progress_report.h"
#include "meshing/driver/del_mesh.h"
#include "symbolic/catalog.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(progress_report_test)

BOOST_AUTO_TEST_CASE(the_text_of_a_refinement_report_lists_the_queues) {
  ProgressReport report;
  report.phase = ProgressPhase::geometry;
  report.points = 1234;
  report.queued = {{"vor_edge", 5}, {"quality", 0}};
  report.elapsed_seconds = 2.5;
  BOOST_TEST(report.text() == "geometry: points 1234, queued vor_edge=5 quality=0");
  report.phase = ProgressPhase::topology;
  report.queued.clear();
  BOOST_TEST(report.text() == "topology: points 1234, queued");
}

BOOST_AUTO_TEST_CASE(the_text_of_the_certificate_report_names_it) {
  ProgressReport report;
  report.phase = ProgressPhase::certifying;
  report.points = 99;
  BOOST_TEST(report.text() == "certifying the distance to the surface (gradient flow)");
}

BOOST_AUTO_TEST_CASE(phases_have_names) {
  std::ostringstream s;
  s << ProgressPhase::topology << ' ' << ProgressPhase::geometry << ' ' << ProgressPhase::certifying;
  BOOST_TEST(s.str() == "topology geometry certifying");
}

// A torus run long enough (a size bound, one to two seconds) for refinement reports: the
// reports come in order of time with non-decreasing points and phases, the refinement's list the
// enabled rows of the check table, and the last announces the distance certificate with the
// run's final sample count.
BOOST_AUTO_TEST_CASE(a_torus_run_reports_in_order) {
  const auto& entry = catalog_entry("torus");
  DelMeshOptions options;
  options.size_bound = 0.03;
  std::vector<ProgressReport> reports;
  options.progress = [&](const ProgressReport& report) { reports.push_back(report); };
  const DelMeshResult result = del_mesh(entry.surface(), entry.box, options);
  BOOST_TEST_REQUIRE(result.status == MeshStatus::complete);
  BOOST_TEST_REQUIRE(reports.size() >= 2u);
  std::size_t geometry = 0;
  for (std::size_t k = 0; k < reports.size(); ++k) {
    const ProgressReport& r = reports[k];
    BOOST_TEST_CONTEXT("report " << k << ": " << r.text()) {
      BOOST_TEST(r.elapsed_seconds >= 0);
      BOOST_TEST(r.elapsed_seconds <= result.statistics["seconds"].get<double>());
      BOOST_TEST(r.points > 0u);
      if (k > 0) {
        BOOST_TEST(r.phase >= reports[k - 1].phase);
        BOOST_TEST(r.points >= reports[k - 1].points);
        BOOST_TEST(r.elapsed_seconds >= reports[k - 1].elapsed_seconds);
      }
      if (r.phase == ProgressPhase::certifying) {
        BOOST_TEST(k + 1 == reports.size());
        BOOST_TEST(r.queued.empty());
      } else {
        BOOST_TEST(!r.queued.empty());
      }
      if (r.phase == ProgressPhase::geometry) {
        ++geometry;
        // The geometry rows join the topology rows: more queues than a topology report has.
        if (reports.front().phase == ProgressPhase::topology)
          BOOST_TEST(r.queued.size() > reports.front().queued.size());
      }
    }
  }
  BOOST_TEST(geometry >= 1u);
  BOOST_TEST(reports.back().phase == ProgressPhase::certifying);
  BOOST_TEST(reports.back().points == result.statistics["points"].get<std::size_t>());
}

BOOST_AUTO_TEST_SUITE_END()
