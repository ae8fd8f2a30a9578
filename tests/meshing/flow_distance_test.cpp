#include "meshing/inputs/flow_distance.h"

#include <cmath>
#include <limits>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;

namespace {

const Surface unit_sphere = Surface::parse("x^2+y^2+z^2-1");

Vec3 scaled(const Vec3& v, double s) { return {s * v[0], s * v[1], s * v[2]}; }

// An equilateral triangle of circumradius ρ whose vertices lie at distance `radius` from the
// origin, around the direction (0, 0, 1): its point closest to the origin is its centroid, at
// sqrt(radius² − ρ²).
struct Cap {
  Vec3 a, b, c;
  double nearest;  // distance from the origin to the triangle
};
Cap cap(double radius, double rho) {
  const double h = std::sqrt(radius * radius - rho * rho);
  const double pi = std::acos(-1.0);
  Cap t;
  t.a = {rho, 0, h};
  t.b = {rho * std::cos(2 * pi / 3), rho * std::sin(2 * pi / 3), h};
  t.c = {rho * std::cos(4 * pi / 3), rho * std::sin(4 * pi / 3), h};
  t.nearest = h;
  return t;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(flow_distance)

// A small triangle inscribed in the unit sphere: its farthest point from the sphere is the
// centroid, at 1 − h.  The bound is proved, sound (≥ 1 − h) and within a small factor of it.
BOOST_AUTO_TEST_CASE(an_inscribed_triangle_is_bounded_soundly_and_tightly) {
  const FlowDistance distance(unit_sphere);
  const Cap t = cap(1, 0.05);
  const double exact = 1 - t.nearest;
  const TriangleDistance d = distance.bound(t.a, t.b, t.c, 0.01);
  BOOST_TEST_REQUIRE(d.proved);
  BOOST_TEST(d.distance >= exact);
  BOOST_TEST(d.distance <= 3 * exact, "bound " << d.distance << ", exact " << exact);
  BOOST_TEST(d.distance <= 0.01);
  BOOST_TEST(d.gradient_bound > 0);
  BOOST_TEST(d.value_bound >= 1 - t.nearest * t.nearest);  // |E| at the centroid
}

// The lemma needs the descent curve to stay within the radius: a triangle 0.05 away from the
// sphere is not proved within 0.01, and is within 0.1 (with a bound of at least 0.05).
BOOST_AUTO_TEST_CASE(the_radius_limits_what_is_proved) {
  const FlowDistance distance(unit_sphere);
  const Vec3 a{0, 0, 1.05}, b{0.01, 0, 1.05}, c{0, 0.01, 1.05};
  const TriangleDistance near = distance.bound(a, b, c, 0.01);
  BOOST_TEST(!near.proved);
  BOOST_TEST(near.distance == std::numeric_limits<double>::infinity());
  const TriangleDistance far = distance.bound(a, b, c, 0.1);
  BOOST_TEST_REQUIRE(far.proved);
  BOOST_TEST(far.distance >= 0.05);
  BOOST_TEST(far.distance <= 0.1);
}

// Around the centre the gradient vanishes: nothing is proved for a triangle near the origin,
// whatever the radius.
BOOST_AUTO_TEST_CASE(a_vanishing_gradient_proves_nothing) {
  const FlowDistance distance(unit_sphere);
  const TriangleDistance d = distance.bound({-0.1, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, 2);
  BOOST_TEST(!d.proved);
  BOOST_TEST(d.gradient_bound == 0);
}

// A scaled sphere: the bound scales with the length unit (E = |x|² − s², the distance 1 − h in
// units of s).
BOOST_AUTO_TEST_CASE(the_bound_follows_the_scale) {
  for (double s : {1e-3, 1e3}) {
    const FlowDistance distance(Surface::parse("x^2+y^2+z^2-" + std::to_string(s * s)));
    const Cap t = cap(1, 0.05);
    const TriangleDistance d = distance.bound(scaled(t.a, s), scaled(t.b, s), scaled(t.c, s), 0.01 * s);
    BOOST_TEST_REQUIRE(d.proved);
    BOOST_TEST(d.distance >= (1 - t.nearest) * s * (1 - 1e-9));
    BOOST_TEST(d.distance <= 3 * (1 - t.nearest) * s);
  }
}

BOOST_AUTO_TEST_CASE(a_radius_that_is_not_positive_is_a_precondition_violation) {
  const FlowDistance distance(unit_sphere);
  const Vec3 a{0, 0, 1}, b{0.01, 0, 1}, c{0, 0.01, 1};
  BOOST_CHECK_THROW((void)distance.bound(a, b, c, 0), PreconditionViolation);
  BOOST_CHECK_THROW((void)distance.bound(a, b, c, -1), PreconditionViolation);
  BOOST_CHECK_THROW((void)distance.bound(a, b, c, std::numeric_limits<double>::infinity()), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
