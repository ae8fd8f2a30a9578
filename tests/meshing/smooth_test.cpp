#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "meshing/detail/vec3.h"
#include "meshing/smooth.h"
#include "meshing/theorem_bounds.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(smooth)

// The octahedron: every edge has roughness π − arccos(−1/3) ≈ 1.23 rad > 2β(0.06) ≈ 0.77.
BOOST_AUTO_TEST_CASE(octahedron_edges_are_too_rough) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  const auto n = outward_normal(f.restricted, make_triangle_key(0, 2, 4));
  BOOST_TEST(detail::dot(n, {1, 1, 1}) > 0);  // outward
  const auto w = smooth_witness(f.restricted, {0, 2}, 2 * beta(0.06));
  BOOST_TEST_REQUIRE(w.has_value());
  BOOST_TEST(std::abs(f.oracle.E(w->point)) < 1e-9);
  BOOST_TEST(!smooth_witness(f.restricted, {0, 2}, 1.25).has_value());
  BOOST_TEST(!smooth_witness(f.restricted, {0, 1}, 0.1).has_value());  // not an edge of Tri S|Σ
}

BOOST_AUTO_TEST_SUITE_END()
