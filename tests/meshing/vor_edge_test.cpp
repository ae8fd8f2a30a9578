#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "meshing/checks/vor_edge.h"
#include "meshing/core/detail/vec3.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(vor_edge)

// Three points on the equator: the Voronoi edge is the z-axis, crossing the sphere twice.
BOOST_AUTO_TEST_CASE(edge_crossing_twice_fires_with_the_furthest_crossing) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}});
  const auto& rec = f.restricted.voronoi_edge_record({0, 1, 2});
  BOOST_TEST(rec.crossings().size() == 2u);
  const auto w = vor_edge_witness(f.restricted, {0, 1, 2});
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(w.witnesses.front().kind == CheckKind::vor_edge);
  BOOST_TEST(std::abs(std::abs(w.witnesses.front().point[2]) - 1) < 1e-9);
  BOOST_TEST(std::abs(f.oracle.E(w.witnesses.front().point)) < 1e-9);
}

// Adding the south pole makes the edge a ray from the centre upwards: one crossing, no witness.
BOOST_AUTO_TEST_CASE(ray_crossing_once_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, -1}});
  const auto& rec = f.restricted.voronoi_edge_record({0, 1, 2});
  BOOST_TEST(rec.crossings().size() == 1u);
  BOOST_TEST(rec.restricted);
  BOOST_TEST(vor_edge_witness(f.restricted, {0, 1, 2}).clean());
}

// A vertical Voronoi edge tangent to the sphere at (1, 0, 0) (Lemma 4.7(ii)).  The sites are
// chosen so that the circumcentre (1, 0, 0) is computed exactly: the edge as constructed touches Σ.
BOOST_AUTO_TEST_CASE(tangent_edge_fires_at_the_tangency) {
  CheckFixture f(test::unit_sphere, 1.5, {{1.5, 0, 0}, {1, 0.5, 0}, {0.5, 0, 0}});
  BOOST_TEST(f.restricted.voronoi_edge_record({0, 1, 2}).edge(f.del, {0, 1, 2}).point == (Vec3{1, 0, 0}));
  const auto w = vor_edge_witness(f.restricted, {0, 1, 2});
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(detail::distance(w.witnesses.front().point, {1, 0, 0}) < 1e-5);
}

BOOST_AUTO_TEST_SUITE_END()
