// The homotopy backend of the mesher (surface_oracle.h, del_mesh.h with SolverBackend::homotopy):
// the run's deadline reaches every solve, fallbacks to subdivision are counted, and DelMesh with
// the homotopy backend meets Theorem 6.1 on catalog surfaces.
#include <chrono>
#include <string>

#include <boost/test/unit_test.hpp>

#include "check_fixture.h"
#include "common/tolerances.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/implicit_oracle.h"
#include "solvers/query_geometry.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

ImplicitOracle homotopy_oracle(const std::string& name) {
  const auto& entry = catalog_entry(name);
  return ImplicitOracle(entry.surface(), entry.box, SolverBackend::homotopy);
}

// SilhouetteCritical over the whole box: a 3-D homotopy solve with many paths (60 for the torus,
// 616 for genus2).
SolveResult whole_box_silhouette_critical(ImplicitOracle& oracle) {
  return oracle.silhouette_critical(unit_vector({3, -5, 8}), unit_vector({1, 2, -2}), box_domain(oracle.box()));
}

// DelMesh with the homotopy backend on a catalog surface.  Every homotopy solve either proves its
// answer complete (solvers/homotopy_certificate.h) or returns its domain undecided, so every answer
// is certified ("solver_certified"), and the run is `complete` exactly when nothing is unsettled;
// then Theorem 6.1 holds on the output (the independent checker against the catalog's topology).
nlohmann::json homotopy_run(const std::string& name, double lambda, const std::string& status) {
  const auto& entry = catalog_entry(name);
  DelMeshOptions options;
  options.lambda = lambda;
  options.solver = SolverBackend::homotopy;
  const auto start = Clock::now();
  const auto result = del_mesh(entry.surface(), entry.box, options);
  BOOST_TEST_MESSAGE(name << " (homotopy): " << seconds_since(start) << " s, " << result.statistics.at("status"));
  BOOST_TEST(result.statistics.at("solver_certified").get<bool>());
  BOOST_TEST(result.statistics.at("status").get<std::string>() == status);
  if (status == "complete")
    test::check_theorem_6_1(entry, result, lambda);
  else  // never uncertified without a finding that says why
    BOOST_TEST(result.statistics.at("unsettled").at("count").get<std::size_t>() > 0u);
  const auto& solver = result.statistics.at("solver");
  BOOST_TEST(solver.at("backend") == "homotopy");
  BOOST_TEST(solver.at("time_limited") == 0u);
  return solver;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(homotopy_mesh)

BOOST_AUTO_TEST_CASE(a_deadline_in_the_past_stops_a_homotopy_solve_at_once) {
  auto oracle = homotopy_oracle("torus");
  oracle.set_run_controls(1, Clock::now() - std::chrono::seconds(1));
  const auto start = Clock::now();
  const SolveResult r = whole_box_silhouette_critical(oracle);
  const double seconds = seconds_since(start);
  BOOST_TEST(seconds < 0.5);
  BOOST_TEST(r.status == SolveStatus::time_limit);
  BOOST_TEST(r.roots.empty());
  BOOST_REQUIRE(!r.undecided.empty());
  BOOST_TEST(r.undecided.back().reason == UndecidedReason::budget);
  const auto stats = oracle.statistics_json();
  BOOST_TEST(stats["per_primitive"]["silhouette_critical"]["time_limited"] == 1u);
  BOOST_TEST(stats["per_primitive"]["silhouette_critical"]["homotopy_fallbacks"] == 0u);
  BOOST_TEST(stats["time_limited"] == 1u);
}

BOOST_AUTO_TEST_CASE(a_near_deadline_cuts_one_long_homotopy_solve) {
  // The same solve without a deadline, then with a deadline a tenth of its time away: the solve
  // stops there (its paths read the clock before every step) and says so.
  auto oracle = homotopy_oracle("genus2");
  auto start = Clock::now();
  const SolveResult full = whole_box_silhouette_critical(oracle);
  const double full_seconds = seconds_since(start);
  BOOST_TEST(full.status != SolveStatus::time_limit);

  start = Clock::now();
  oracle.set_run_controls(1, start + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(full_seconds / 10)));
  const SolveResult cut = whole_box_silhouette_critical(oracle);
  const double seconds = seconds_since(start);
  BOOST_TEST_MESSAGE("genus2 silhouette_critical: " << full_seconds << " s, " << full.counters.paths
                                                   << " paths; with the deadline " << seconds << " s, "
                                                   << cut.counters.paths << " paths");
  BOOST_TEST(cut.status == SolveStatus::time_limit);
  BOOST_TEST(cut.counters.paths < full.counters.paths);
  BOOST_REQUIRE(!cut.undecided.empty());
  BOOST_TEST(cut.undecided.back().reason == UndecidedReason::budget);
  BOOST_TEST(seconds < full_seconds / 2);
  BOOST_TEST(oracle.statistics_json()["per_primitive"]["silhouette_critical"]["time_limited"] == 1u);
}

BOOST_AUTO_TEST_CASE(the_deadline_reaches_the_subdivision_fallback) {
  // two_blobs is not polynomial: the homotopy backend falls back to subdivision, counted, and the
  // deadline stops that solve too.
  auto oracle = homotopy_oracle("two_blobs");
  oracle.set_run_controls(1, Clock::now() - std::chrono::seconds(1));
  const SolveResult r =
      oracle.surface_critical(unit_vector({3, -5, 8}), box_domain(oracle.box()), tolerances::mesher_box_budget_global);
  BOOST_TEST(r.status == SolveStatus::time_limit);
  const auto stats = oracle.statistics_json();
  BOOST_TEST(stats["per_primitive"]["surface_critical"]["homotopy_fallbacks"] == 1u);
  BOOST_TEST(stats["per_primitive"]["surface_critical"]["time_limited"] == 1u);
  BOOST_TEST(stats["homotopy_paths"] == 0u);
}

BOOST_AUTO_TEST_CASE(fallbacks_are_counted_per_primitive) {
  // Sphere, homotopy backend: SurfaceCritical by homotopy (no fallback), SurfacePlaneContact (not
  // square) by subdivision (a fallback), SurfaceLine by the univariate isolator (none).
  auto oracle = homotopy_oracle("sphere");
  const SolveResult critical =
      oracle.surface_critical(unit_vector({0, 0, 1}), box_domain(oracle.box()), tolerances::mesher_box_budget_global);
  BOOST_TEST(critical.roots.size() == 2u);
  (void)oracle.surface_plane_contact({0, 0, 0.5}, {1, 0, 0}, {0, 1, 0},
                                     Domain::from_box({{{-0.1, 0.1}}, {{-0.1, 0.1}}}));
  (void)oracle.surface_line({0, 0, 0}, {1, 0, 0}, 0.5, 2);
  const auto stats = oracle.statistics_json();
  BOOST_TEST(stats["backend"] == "homotopy");
  BOOST_TEST(stats["per_primitive"]["surface_critical"]["homotopy_fallbacks"] == 0u);
  BOOST_TEST(stats["per_primitive"]["surface_critical"]["homotopy_paths"].get<std::size_t>() >= 1u);
  BOOST_TEST(stats["per_primitive"]["surface_plane_contact"]["homotopy_fallbacks"] == 1u);
  BOOST_TEST(stats["per_primitive"]["surface_line"]["homotopy_fallbacks"] == 0u);
  BOOST_TEST(stats["homotopy_fallbacks"] == 1u);

  // The subdivision backend counts none.
  const auto& entry = catalog_entry("sphere");
  ImplicitOracle subdivision(entry.surface(), entry.box, SolverBackend::subdivision);
  (void)subdivision.surface_plane_contact({0, 0, 0.5}, {1, 0, 0}, {0, 1, 0},
                                          Domain::from_box({{{-0.1, 0.1}}, {{-0.1, 0.1}}}));
  BOOST_TEST(subdivision.statistics_json()["backend"] == "subdivision");
  BOOST_TEST(subdivision.statistics_json()["homotopy_fallbacks"] == 0u);
}

BOOST_AUTO_TEST_CASE(sphere_meets_theorem_6_1) {
  // every homotopy solve but those with a curve of zeros (a Voronoi facet through the centre,
  // normal to the silhouette direction) is proved; those come back undecided and are settled
  const auto solver = homotopy_run("sphere", 0.06, "complete");
  BOOST_TEST(solver.at("homotopy_paths").get<std::size_t>() > 0u);
  BOOST_TEST(solver.at("homotopy_certified").get<std::size_t>() > 0u);
}

BOOST_AUTO_TEST_CASE(two_blobs_meets_theorem_6_1_by_fallbacks) {
  // Not polynomial: every square system falls back to subdivision, and the statistics say so.
  const auto solver = homotopy_run("two_blobs", 0.06, "complete");
  BOOST_TEST(solver.at("homotopy_paths") == 0u);
  BOOST_TEST(solver.at("homotopy_fallbacks").get<std::size_t>() ==
             solver.at("systems").get<std::size_t>() - solver.at("per_primitive").at("surface_line").at("calls").get<std::size_t>());
}

BOOST_AUTO_TEST_CASE(torus_meets_theorem_6_1, *boost::unit_test::label("slow")) {
  // The seeds' whole-box SurfaceCritical solve cannot be proved near the centre, where the
  // complexified torus is singular: that piece is answered by subdivision, the rest by the
  // certificate, and the run is complete.
  const auto solver = homotopy_run("torus", 0.06, "complete");
  BOOST_TEST(solver.at("homotopy_certified").get<std::size_t>() > 0u);
  BOOST_TEST(solver.at("homotopy_pieces_by_subdivision").get<std::size_t>() > 0u);
}

BOOST_AUTO_TEST_SUITE_END()
