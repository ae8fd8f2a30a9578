#include <boost/test/unit_test.hpp>

#include <cmath>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/driver/sample_topology.h"
#include "meshing/inputs/implicit_oracle.h"
#include "symbolic/catalog.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(sample_topology_suite)

BOOST_AUTO_TEST_CASE(generic_directions_are_unit_seeded_and_distinct) {
  const Vec3 a = generic_direction(1, 0), b = generic_direction(1, 1), c = generic_direction(2, 0);
  BOOST_TEST(std::abs(detail::norm(a) - 1) < 1e-12);
  BOOST_TEST((a == generic_direction(1, 0)));
  BOOST_TEST(detail::distance(a, b) > 1e-3);
  BOOST_TEST(detail::distance(a, c) > 1e-3);
}

// The seeds of the sphere are ±d; of the torus, four points (max, min, two saddles).
BOOST_AUTO_TEST_CASE(seeds_are_the_critical_points) {
  for (const auto& [name, count] : std::vector<std::pair<std::string, std::size_t>>{{"sphere", 2}, {"torus", 4}}) {
    const auto& entry = catalog_entry(name);
    ImplicitOracle oracle(entry.surface(), entry.box, SolverBackend::subdivision);
    Refinement topology(oracle, 5, RefinementLimits{});
    const auto report = insert_seeds(topology);
    BOOST_TEST(report.seeds == count, name);
    BOOST_TEST(topology.insertions(CheckKind::seed) == count);
    for (auto v : topology.delaunay().vertices()) BOOST_TEST(topology.delaunay().is_seed(v));
  }
}

BOOST_AUTO_TEST_CASE(empty_surface_throws) {
  Box3 box;
  box.lo = {-1, -1, -1};
  box.hi = {1, 1, 1};
  ImplicitOracle oracle(Surface::parse("x^2+y^2+z^2+1"), box, SolverBackend::subdivision);
  Refinement topology(oracle, 1, RefinementLimits{});
  BOOST_CHECK_THROW(insert_seeds(topology), InvalidInput);
}

// E's values overflow double precision in the box (and no constant factor can be divided out of
// the sum), so the seed solve leaves regions it can neither decide nor project onto Σ: they are
// unsettled, no seed is inserted, and nothing claims that Σ is empty.
BOOST_AUTO_TEST_CASE(unprojectable_seed_regions_are_unsettled_not_empty) {
  const Box3 box = Box3::cube(2);
  ImplicitOracle oracle(Surface::parse("1e200*(x^2+y^2+z^2-1)+1e-300*sin(x)"), box, SolverBackend::subdivision);
  Refinement topology(oracle, 1, RefinementLimits{});
  SeedReport report;
  BOOST_REQUIRE_NO_THROW(report = insert_seeds(topology));
  BOOST_TEST(report.seeds == 0u);
  BOOST_TEST(report.undecided > 0u);
  const auto unsettled = topology.unsettled();
  BOOST_TEST(unsettled.size() == report.undecided);
  for (const auto& u : unsettled) {
    BOOST_TEST((u.check == CheckKind::seed));
    BOOST_TEST((u.reason == UnsettledReason::unprojectable_region));
  }
}

// Chmutov's octic T8(x) + T8(y) + T8(z) = 0 (T8 the Chebyshev polynomial; genus 81, box ±1.1):
// one budget of the seed solve leaves regions unexplored, and the solve goes on there until every
// critical point of the height is certified, so no region is left to project or report.
const char* chmutov8 =
    "(128*x^8-256*x^6+160*x^4-32*x^2+1)+(128*y^8-256*y^6+160*y^4-32*y^2+1)+(128*z^8-256*z^6+160*z^4-32*z^2+1)";

BOOST_AUTO_TEST_CASE(seed_solve_goes_on_where_its_budget_ran_out) {
  ImplicitOracle oracle(Surface::parse(chmutov8), Box3::cube(1.1), SolverBackend::subdivision);
  const Box3& box = oracle.clip_box();  // where the seed solve runs
  const Vec3 d = generic_direction(1, 0);
  const Domain domain = Domain::from_box({{box.lo[0], box.hi[0]}, {box.lo[1], box.hi[1]}, {box.lo[2], box.hi[2]}});
  BOOST_TEST_REQUIRE((oracle.surface_critical(d, domain, tolerances::mesher_box_budget_global).status ==
                      SolveStatus::box_limit));
  Refinement topology(oracle, 1, RefinementLimits{});
  const SeedReport report = insert_seeds(topology);
  BOOST_TEST(report.undecided == 0u);
  BOOST_TEST(report.seeds > 0u);
  BOOST_TEST(topology.unsettled().empty());
}

// The whole run on the octic ends complete, with the genus of Σ.
BOOST_AUTO_TEST_CASE(chmutov8_meshes_complete_with_genus_81, *boost::unit_test::label("slow")) {
  DelMeshOptions options;
  const DelMeshResult result = del_mesh(Surface::parse(chmutov8), Box3::cube(1.1), options);
  BOOST_TEST(result.statistics.at("status").get<std::string>() == "complete");
  BOOST_TEST(result.statistics.at("unsettled").at("count").get<std::size_t>() == 0u);
  const MeshReport r = check_mesh(result.mesh);
  BOOST_TEST(r.closed);
  BOOST_TEST(r.manifold);
  BOOST_TEST(r.components == 1u);
  BOOST_TEST(r.genus_per_component == std::vector<int>{81}, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_SUITE_END()
