#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "check_fixture.h"
#include "meshing/checks/smooth.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/core/theorem_bounds.h"

using namespace delmesh;
using namespace delmesh::detail;  // the Vec3 operators
using delmesh::test::CheckFixture;

namespace {

// The icosahedron with every edge split at its midpoint, pushed onto the unit sphere: 42 points,
// 80 nearly equilateral triangles.
std::vector<Vec3> icosphere_points() {
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> corners;
  for (double a : {-1.0, 1.0})
    for (double b : {-phi, phi}) {
      corners.push_back({0, a, b});
      corners.push_back({a, b, 0});
      corners.push_back({b, 0, a});
    }
  std::vector<Vec3> points;
  for (const auto& c : corners) points.push_back(detail::normalized(c));
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (std::size_t j = i + 1; j < corners.size(); ++j)
      if (std::abs(detail::distance(corners[i], corners[j]) - 2) < 1e-9)  // an edge
        points.push_back(detail::normalized(corners[i] + corners[j]));
  return points;
}

// The unit normal of t pointing away from the centre of the sphere.
Vec3 normal_away_from_centre(const Delaunay& del, const TriangleKey& t) {
  const Vec3 &p = del.point(t[0]), &q = del.point(t[1]), &r = del.point(t[2]);
  const Vec3 n = detail::normalized(detail::cross(q - p, r - p));
  return detail::dot(n, p + q + r) > 0 ? n : (-1.0) * n;
}

}  // namespace

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

// The subdivided icosahedron on the sphere: all samples on the sphere, so Tri S|Σ is the convex
// hull (80 triangles) and the dual ray of each triangle meets Σ at its outward unit normal.  Its
// roughness, measured here from normals pointing away from the centre, is below 0.4 rad on every
// edge, well under 2β(0.06) ≈ 0.77: Smooth must not fire on any edge.  With a threshold under an
// edge's roughness it must fire, at the one of the two normals' points on Σ further from p.
BOOST_AUTO_TEST_CASE(icosphere_edges_are_smooth) {
  const auto points = icosphere_points();
  BOOST_TEST_REQUIRE(points.size() == 42u);
  CheckFixture f(test::unit_sphere, 1.5, points);
  const auto triangles = f.restricted.triangles();
  BOOST_TEST_REQUIRE(triangles.size() == 80u);
  std::map<EdgeKey, std::vector<TriangleKey>> edges;
  for (const auto& t : triangles)
    for (const EdgeKey& e : {EdgeKey{t[0], t[1]}, EdgeKey{t[0], t[2]}, EdgeKey{t[1], t[2]}}) edges[e].push_back(t);
  BOOST_TEST_REQUIRE(edges.size() == 120u);
  const double threshold = 2 * beta(0.06);
  double roughest = 0;
  for (const auto& [e, pair] : edges) {
    BOOST_TEST_REQUIRE(pair.size() == 2u);
    const Vec3 n0 = normal_away_from_centre(f.del, pair[0]), n1 = normal_away_from_centre(f.del, pair[1]);
    const double g = std::acos(std::clamp(detail::dot(n0, n1), -1.0, 1.0));
    roughest = std::max(roughest, g);
    BOOST_TEST(!smooth_witness(f.restricted, e, threshold).has_value(), "edge " << e[0] << "-" << e[1]);
    const auto w = smooth_witness(f.restricted, e, 0.9 * g);
    BOOST_TEST_REQUIRE(w.has_value(), "edge " << e[0] << "-" << e[1] << " roughness " << g);
    BOOST_TEST((w->kind == CheckKind::smooth));
    BOOST_TEST(w->measured_from == e[0]);
    // One of the two points, and the further one from p (up to rounding: many pairs are tied).
    const Vec3& p = f.del.point(e[0]);
    BOOST_TEST(std::min(detail::distance(w->point, n0), detail::distance(w->point, n1)) < 1e-9);
    BOOST_TEST(detail::distance(w->point, p) >=
               std::max(detail::distance(n0, p), detail::distance(n1, p)) - 1e-9);
  }
  BOOST_TEST(roughest > 0.1);
  BOOST_TEST(roughest < 0.4);
}

BOOST_AUTO_TEST_SUITE_END()
