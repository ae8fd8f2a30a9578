#include "solvers/query_geometry.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;

namespace {

double dot(const Vec3& p, const Vec3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }

Box3 unit_cube() {
  Box3 box;
  box.lo = {-1, -1, -1};
  box.hi = {1, 1, 1};
  return box;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(query_geometry)

BOOST_AUTO_TEST_CASE(frame_is_orthonormal_right_handed_and_deterministic) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 d{normal(rng), normal(rng), normal(rng)};
    const OrthonormalFrame f = orthonormal_frame(d);
    BOOST_TEST(std::abs(dot(f.a, f.a) - 1) < 1e-14);
    BOOST_TEST(std::abs(dot(f.b, f.b) - 1) < 1e-14);
    BOOST_TEST(std::abs(dot(f.d, f.d) - 1) < 1e-14);
    BOOST_TEST(std::abs(dot(f.a, f.b)) < 1e-14);
    BOOST_TEST(std::abs(dot(f.a, f.d)) < 1e-14);
    BOOST_TEST(std::abs(dot(f.b, f.d)) < 1e-14);
    // a × b = d
    const Vec3 c{f.a[1] * f.b[2] - f.a[2] * f.b[1], f.a[2] * f.b[0] - f.a[0] * f.b[2],
                 f.a[0] * f.b[1] - f.a[1] * f.b[0]};
    for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs(c[i] - f.d[i]) < 1e-14);
    const OrthonormalFrame g = orthonormal_frame(d);
    BOOST_TEST((f.a == g.a && f.b == g.b && f.d == g.d));
  }
}

BOOST_AUTO_TEST_CASE(zero_direction_is_invalid) {
  BOOST_CHECK_THROW(orthonormal_frame({0, 0, 0}), InvalidInput);
  BOOST_CHECK_THROW(orthonormal_frame({NAN, 0, 1}), InvalidInput);
}

// A direction whose squared length overflows (1e308) or underflows (1e-320, subnormal) is a
// direction all the same; zero and non-finite ones are refused, named in shortest form.
BOOST_AUTO_TEST_CASE(directions_of_extreme_length) {
  const Vec3 huge = unit_vector({1e308, 1e308, 0});
  BOOST_TEST(std::abs(huge[0] - std::sqrt(0.5)) < 1e-15);
  BOOST_TEST(std::abs(huge[1] - std::sqrt(0.5)) < 1e-15);
  BOOST_TEST(huge[2] == 0.0);
  BOOST_TEST((unit_vector({1e-320, 0, 0}) == Vec3{1, 0, 0}));
  const Vec3 tiny = unit_vector({3e-170, -4e-170, 0});
  BOOST_TEST(std::abs(tiny[0] - 0.6) < 1e-15);
  BOOST_TEST(std::abs(tiny[1] + 0.8) < 1e-15);
  BOOST_TEST(clip_line_to_box({0, 0, 0}, {1e-320, 0, 0}, unit_cube()).has_value());
  try {
    (void)unit_vector({0, 0, 0});
    BOOST_ERROR("no exception");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()) == "direction (0, 0, 0) is zero");
  }
  try {
    (void)unit_vector({0.1, INFINITY, 0});
    BOOST_ERROR("no exception");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()) == "direction (0.1, inf, 0) is not finite");
  }
}

BOOST_AUTO_TEST_CASE(line_clipping) {
  const Box3 box = unit_cube();
  auto t = clip_line_to_box({0, 0, 0}, {1, 0, 0}, box);
  BOOST_REQUIRE(t);
  BOOST_TEST((*t)[0] == -1.0);
  BOOST_TEST((*t)[1] == 1.0);
  t = clip_line_to_box({0, 0, 0}, {1, 1, 1}, box);
  BOOST_REQUIRE(t);
  BOOST_TEST((*t)[0] == -1.0);
  BOOST_TEST((*t)[1] == 1.0);
  t = clip_line_to_box({5, 0, 0}, {0, 2, 0}, box);  // parallel to a face, outside
  BOOST_TEST(!t);
  t = clip_line_to_box({0, 3, 0}, {1, 0, 1}, box);  // misses
  BOOST_TEST(!t);
  t = clip_line_to_box({-3, 0.5, 0}, {2, 0, 0}, box);
  BOOST_REQUIRE(t);
  BOOST_TEST(std::abs((*t)[0] - 1.0) < 1e-15);
  BOOST_TEST(std::abs((*t)[1] - 2.0) < 1e-15);
}

BOOST_AUTO_TEST_CASE(plane_sections_of_a_cube) {
  const Box3 box = unit_cube();
  // z = 0: a square of side 2, area 4.
  auto s = plane_box_section(Vec3{0, 0, 0}, Vec3{0, 0, 1}, box);
  BOOST_REQUIRE(s);
  BOOST_TEST(s->polygon.size() == 4u);
  // x + y + z = 0: a regular hexagon of side √2, area 3√3.
  s = plane_box_section(Vec3{0, 0, 0}, Vec3{1, 1, 1}, box);
  BOOST_REQUIRE(s);
  BOOST_TEST(s->polygon.size() == 6u);
  double area = 0;
  for (std::size_t i = 0; i < s->polygon.size(); ++i) {
    const auto& p = s->polygon[i];
    const auto& q = s->polygon[(i + 1) % s->polygon.size()];
    area += p[0] * q[1] - p[1] * q[0];
  }
  BOOST_TEST(area / 2 > 0);  // counter-clockwise
  BOOST_TEST(std::abs(area / 2 - 3 * std::sqrt(3.0)) < 1e-12);
  // Every vertex maps back to a world point on the plane and on the box boundary.
  for (const auto& w : s->polygon) {
    Vec3 x;
    for (int i = 0; i < 3; ++i) x[i] = s->origin[i] + w[0] * s->frame.a[i] + w[1] * s->frame.b[i];
    BOOST_TEST(std::abs(x[0] + x[1] + x[2]) < 1e-12);
    double on_face = 1e9;
    for (int i = 0; i < 3; ++i) on_face = std::min(on_face, 1 - std::abs(x[i]));
    BOOST_TEST(std::abs(on_face) < 1e-12);
  }
  // Misses, or touches only along an edge or at a corner.
  BOOST_TEST(!plane_box_section(Vec3{0, 0, 2}, Vec3{0, 0, 1}, box));
  BOOST_TEST(!plane_box_section(Vec3{1, 1, 1}, Vec3{1, 1, 1}, box));
  BOOST_TEST(!plane_box_section(Vec3{1, 1, 0}, Vec3{1, 1, 0}, box));
}

// The plane x + y + z = 0 crosses 6 of the cube's 12 edges, at their midpoints (permutations of
// (1, −1, 0)); z = 1 contains 4 corners and crosses no edge; z = 2 misses the cube.
BOOST_AUTO_TEST_CASE(plane_meets_the_cube_edges_at_known_points) {
  const Box3 box = unit_cube();
  auto points = plane_box_edge_points(Vec3{0, 0, 0}, Vec3{1, 1, 1}, box);
  BOOST_TEST(points.size() == 6u);
  std::sort(points.begin(), points.end());
  const std::vector<Vec3> expected{{-1, 0, 1}, {-1, 1, 0}, {0, -1, 1}, {0, 1, -1}, {1, -1, 0}, {1, 0, -1}};
  BOOST_TEST((points == expected));
  points = plane_box_edge_points(Vec3{0, 0, 1}, Vec3{0, 0, 1}, box);
  BOOST_TEST(points.size() == 4u);
  for (const Vec3& x : points) BOOST_TEST((std::abs(x[0]) == 1 && std::abs(x[1]) == 1 && x[2] == 1));
  BOOST_TEST(plane_box_edge_points(Vec3{0, 0, 2}, Vec3{0, 0, 1}, box).empty());
}

BOOST_AUTO_TEST_CASE(polygon_domain_half_spaces_contain_exactly_the_polygon) {
  const std::vector<std::array<double, 2>> triangle{{0, 0}, {2, 0}, {0, 1}};
  const Domain d = polygon_domain(triangle);
  BOOST_TEST(d.dimension() == 2u);
  BOOST_TEST(d.box.bounds[0][0] == 0.0);
  BOOST_TEST(d.box.bounds[0][1] == 2.0);
  BOOST_TEST(d.box.bounds[1][1] == 1.0);
  BOOST_REQUIRE(d.half_spaces.size() == 3u);
  auto inside = [&](double u, double v) {
    for (const auto& h : d.half_spaces) {
      if (h.normal[0] * u + h.normal[1] * v > h.offset + 1e-15) return false;
    }
    return true;
  };
  BOOST_TEST(inside(0.5, 0.25));
  BOOST_TEST(inside(0, 0));
  BOOST_TEST(!inside(1.5, 0.5));  // in the bounding box, outside the triangle
  BOOST_TEST(!inside(-0.1, 0.5));
  BOOST_CHECK_THROW(polygon_domain({{0, 0}, {1, 0}}), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
