#include <boost/test/unit_test.hpp>

#include <cmath>

#include "check_fixture.h"
#include "meshing/checks/facet_contact.h"
#include "meshing/core/detail/vec3.h"

using namespace delmesh;
using delmesh::test::CheckFixture;

BOOST_AUTO_TEST_SUITE(facet_contact)

// The bisector plane x = 1 of (0.5,0,0) and (1.5,0,0) touches the unit sphere at (1,0,0).
BOOST_AUTO_TEST_CASE(facet_touching_the_sphere_fires_at_the_contact) {
  CheckFixture f(test::unit_sphere, 1.6, {{0.5, 0, 0}, {1.5, 0, 0}});
  const auto w = facet_contact_witness(f.restricted, {0, 1});
  BOOST_TEST_REQUIRE(!w.witnesses.empty());
  BOOST_TEST(w.witnesses.front().kind == CheckKind::facet_contact);
  BOOST_TEST(detail::distance(w.witnesses.front().point, {1, 0, 0}) < 1e-4);
}

// The plane x = 0.4 cuts the sphere transversally: no contact.
BOOST_AUTO_TEST_CASE(transversal_facet_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.6, {{0.2, 0, 0}, {0.6, 0, 0}});
  BOOST_TEST(facet_contact_witness(f.restricted, {0, 1}).clean());
}

// A facet whose plane is tangent to the sphere outside the facet: (1,0,0) is cut off by a third
// sample close to it, so there is no contact inside F.
BOOST_AUTO_TEST_CASE(contact_outside_the_facet_does_not_fire) {
  CheckFixture f(test::unit_sphere, 1.6, {{0.5, 0, 0}, {1.5, 0, 0}, {1.0, 0.4, 0}});
  const auto& facet = f.restricted.facet({0, 1});
  const auto uv = facet.plane_coordinates({1, 0, 0});
  BOOST_TEST_REQUIRE(!facet.contains(uv[0], uv[1], 1e-9));
  BOOST_TEST(facet_contact_witness(f.restricted, {0, 1}).clean());
}

// Six cospherical samples, the vertices of an octahedron about c: the Voronoi facet of the
// octahedron's diagonal in Del S is the single point c.  Returns that diagonal.
EdgeKey degenerate_diagonal(CheckFixture& f) {
  for (VertexId v : f.del.vertices())
    for (const auto& e : f.del.incident_edges(v))
      if (f.restricted.facet(e).degenerate) return e;
  BOOST_FAIL("no degenerate facet");
  return {};
}

std::vector<Vec3> octahedron_about(const Vec3& c) {
  return {{c[0] + 0.5, c[1], c[2]}, {c[0] - 0.5, c[1], c[2]}, {c[0], c[1] + 0.5, c[2]},
          {c[0], c[1] - 0.5, c[2]}, {c[0], c[1], c[2] + 0.5}, {c[0], c[1], c[2] - 0.5}};
}

// c on Σ: the degenerate facet {c} meets Σ.  Its plane (the bisector of the diagonal) is tangent
// to Σ at c when the diagonal is the normal ∥ c: then it is a contact and unsettled.  Otherwise
// the plane cuts Σ transversally at c, and the gradient cone over the hull of the facet's points
// proves both facet checks clean.  The triangulation picks the same diagonal for every
// translate of the octahedron, so of the three placements c = e_x, e_y, e_z exactly one is the
// tangent case.
BOOST_AUTO_TEST_CASE(degenerate_facet_on_the_surface_is_unsettled_only_where_tangent) {
  int unsettled = 0, clean = 0;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 c{0, 0, 0};
    c[axis] = 1;
    CheckFixture f(test::unit_sphere, 1.6, octahedron_about(c));
    const EdgeKey e = degenerate_diagonal(f);
    using detail::operator-;
    const Vec3 diagonal = f.del.point(e[1]) - f.del.point(e[0]);
    const bool tangent = std::abs(diagonal[axis]) == detail::norm(diagonal);
    const auto result = facet_contact_witness(f.restricted, e);
    BOOST_TEST(result.witnesses.empty());
    if (tangent) {
      ++unsettled;
      BOOST_TEST_REQUIRE(result.unsettled.size() == 1u);
      BOOST_TEST(result.unsettled[0].reason == UnsettledReason::degenerate_face);
      BOOST_TEST(detail::distance(result.unsettled[0].location, c) < 1e-6);
    } else {
      ++clean;
      BOOST_TEST(result.clean());
      BOOST_TEST(f.restricted.facet_section_certified(e));
    }
  }
  BOOST_TEST(unsettled == 1);
  BOOST_TEST(clean == 2);
}

// c = (0.5,0,0), inside the ball: Σ is proved to miss the degenerate facet.
BOOST_AUTO_TEST_CASE(degenerate_facet_off_the_surface_is_clean) {
  CheckFixture f(test::unit_sphere, 1.6, octahedron_about({0.5, 0, 0}));
  BOOST_TEST(facet_contact_witness(f.restricted, degenerate_diagonal(f)).clean());
}

BOOST_AUTO_TEST_SUITE_END()
