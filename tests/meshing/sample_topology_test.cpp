#include <boost/test/unit_test.hpp>

#include <cmath>

#include "common/errors.h"
#include "meshing/detail/vec3.h"
#include "meshing/implicit_oracle.h"
#include "meshing/sample_topology.h"
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

BOOST_AUTO_TEST_SUITE_END()
