#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "meshing/facet_cycle.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(facet_cycle)

// The facet x = 0.4 contains the whole circle Σ ∩ {x = 0.4}: a closed curve (Lemma 4.9).
BOOST_AUTO_TEST_CASE(facet_containing_a_closed_curve_fires) {
  CheckFixture f(test::unit_sphere, 1.6, {{0.2, 0, 0}, {0.6, 0, 0}});
  const auto w = facet_cycle_witness(f.restricted, {0, 1});
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(w.witnesses.front().kind == CheckKind::facet_cycle);
  BOOST_TEST(std::abs(w.witnesses.front().point[0] - 0.4) < 1e-9);
  BOOST_TEST(std::abs(f.oracle.E(w.witnesses.front().point)) < 1e-9);
}

// The facet x = 1.2 misses the sphere.
BOOST_AUTO_TEST_CASE(facet_missing_the_surface_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.6, {{1.0, 0, 0}, {1.4, 0, 0}});
  BOOST_TEST(facet_cycle_witness(f.restricted, {0, 1}).clean());
}

// Four samples around the x-axis cut the facet x = 0 down to a small square around the origin
// that meets the sphere nowhere... and eight around it make F ∩ Σ open arcs only: the facet
// between (−0.1,0,0) and (0.1,0,0) limited by samples at (0,±1.4,0), (0,0,±1.4) is the square
// |y|, |z| ≤ 0.7 which lies inside the ball: no curve at all.
BOOST_AUTO_TEST_CASE(facet_inside_the_ball_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.6,
                 {{-0.1, 0, 0}, {0.1, 0, 0}, {0, 1.4, 0}, {0, -1.4, 0}, {0, 0, 1.4}, {0, 0, -1.4}});
  BOOST_TEST(facet_cycle_witness(f.restricted, {0, 1}).clean());
}

BOOST_AUTO_TEST_SUITE_END()
