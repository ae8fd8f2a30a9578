#include <boost/test/unit_test.hpp>

#include <cmath>

#include "common/errors.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/inputs/implicit_oracle.h"
#include "solvers/domain.h"
#include "solvers/query_geometry.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(surface_oracle)

BOOST_AUTO_TEST_CASE(line_through_the_centre_meets_the_sphere_at_distance_one) {
  ImplicitOracle oracle(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.5), SolverBackend::subdivision);
  const auto r = oracle.surface_line({0, 0, 0}, {0.6, 0.8, 0}, -1.4, 1.4);
  BOOST_TEST_REQUIRE(r.roots.size() == 2u);
  for (const auto& root : r.roots) BOOST_TEST(std::abs(detail::norm(root.world) - 1) < 1e-12);
  const auto& s = oracle.statistics("surface_line");
  BOOST_TEST(s.calls == 1u);
  BOOST_TEST(s.certified_roots == 2u);
  BOOST_TEST(oracle.statistics_json()["systems"] == 1);
}

BOOST_AUTO_TEST_CASE(critical_points_of_the_sphere_are_plus_minus_d) {
  ImplicitOracle oracle(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.5), SolverBackend::subdivision);
  const Vec3 d = detail::normalized(Vec3{0.3, -0.5, 0.8});
  const auto r = oracle.surface_critical(
      d, Domain::from_box({{-1.5, 1.5}, {-1.5, 1.5}, {-1.5, 1.5}}), 100000);
  BOOST_TEST_REQUIRE(r.roots.size() == 2u);
  for (const auto& root : r.roots) BOOST_TEST(std::abs(std::abs(detail::dot(root.world, d)) - 1) < 1e-9);
}

BOOST_AUTO_TEST_CASE(a_primitive_solved_by_name_is_the_same_solve) {
  // solve("surface_critical", (a, b), …) is the method surface_critical(d) for the frame (a, b) of d.
  ImplicitOracle oracle(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.5), SolverBackend::subdivision);
  const Domain box = Domain::from_box({{-1.5, 1.5}, {-1.5, 1.5}, {-1.5, 1.5}});
  const Vec3 d{0.3, -0.5, 0.8};
  const OrthonormalFrame f = orthonormal_frame(d);
  const auto by_method = oracle.surface_critical(d, box, 100000);
  const auto by_name = oracle.solve("surface_critical", {f.a[0], f.a[1], f.a[2], f.b[0], f.b[1], f.b[2]}, box, 100000);
  BOOST_TEST_REQUIRE(by_name.roots.size() == 2u);
  BOOST_TEST_REQUIRE(by_method.roots.size() == 2u);
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k) BOOST_TEST(by_name.roots[i].world[k] == by_method.roots[i].world[k]);
  BOOST_TEST(oracle.statistics("surface_critical").calls == 2u);
  // An over-determined system runs in exclusion mode: the plane z = 1/2 has no contact.
  const auto contact = oracle.solve("surface_plane_contact", {0, 0, 0.5, 1, 0, 0, 0, 1, 0},
                                    Domain::from_box({{-1, 1}, {-1, 1}}), 4000);
  BOOST_TEST(contact.is_complete());
  BOOST_TEST(contact.roots.empty());
  BOOST_CHECK_THROW((void)oracle.solve("no_such_primitive", {}, box, 1), InvalidInput);
  BOOST_CHECK_THROW((void)oracle.solve("surface_critical", {1, 0, 0}, box, 1), PreconditionViolation);
  BOOST_CHECK_THROW((void)oracle.solve("surface_line", {0, 0, 0, 1, 0, 0}, box, 1), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(projection_lands_on_the_surface) {
  ImplicitOracle oracle(Surface::parse("(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)"), Box3::cube(1.65), SolverBackend::subdivision);
  const auto x = oracle.project({1.3, 0.2, 0.1});
  BOOST_TEST_REQUIRE(x.has_value());
  BOOST_TEST(std::abs(oracle.E(*x)) < 1e-12);
  const auto n = oracle.normal({1.4, 0, 0});
  BOOST_TEST(std::abs(n[0] - 1) < 1e-12);  // outward where E > 0 outside
  BOOST_TEST(!oracle.project({0, 0, 0}).has_value());  // ∇E = 0 at the centre: no projection
}

BOOST_AUTO_TEST_SUITE_END()
