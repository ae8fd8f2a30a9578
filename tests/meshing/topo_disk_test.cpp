#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "meshing/checks/topo_disk.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(topo_disk)

BOOST_AUTO_TEST_CASE(disk_criterion) {
  // A fan of four triangles around 0 closing up: a disk.
  const std::vector<TriangleKey> fan{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 1, 4}};
  BOOST_TEST(is_topological_disk(fan, 0));
  // An open fan (boundary edge 0-1 in one triangle only): not a disk.
  BOOST_TEST(!is_topological_disk({{0, 1, 2}, {0, 2, 3}}, 0));
  // Two cycles pinched at 0 (a bow-tie of two closed fans): not a disk.
  BOOST_TEST(!is_topological_disk({{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {0, 4, 5}, {0, 5, 6}, {0, 4, 6}}, 0));
  // An edge in three triangles: not a disk.
  BOOST_TEST(!is_topological_disk({{0, 1, 2}, {0, 1, 3}, {0, 1, 4}, {0, 2, 3}}, 0));
  BOOST_TEST(!is_topological_disk({}, 0));
}

// Three samples on the equator: each has one restricted triangle (not a disk); the witness is
// the furthest crossing of the edges of V_p with Σ, a pole.
BOOST_AUTO_TEST_CASE(single_triangle_star_fires) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}});
  const auto w = topo_disk_witness(f.restricted, 0);
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(std::abs(std::abs(w.witnesses.front().point[2]) - 1) < 1e-9);
}

// The octahedron's vertices on the unit sphere: every star is a closed fan of four triangles.
BOOST_AUTO_TEST_CASE(octahedron_stars_do_not_fire) {
  CheckFixture f(test::unit_sphere, 1.5, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  for (VertexId p = 0; p < 6; ++p) {
    BOOST_TEST(f.restricted.star(p).size() == 4u);
    BOOST_TEST(topo_disk_witness(f.restricted, p).clean());
  }
}

BOOST_AUTO_TEST_SUITE_END()
