#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>

#include "check_fixture.h"
#include "meshing/checks/quality.h"
#include "meshing/core/detail/vec3.h"

using namespace delmesh;
using namespace delmesh::detail;  // the Vec3 operators
using delmesh::test::CheckFixture;

namespace {

const std::vector<Vec3> octahedron{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// Samples on the unit sphere have every Voronoi vertex at the centre, so the dual Voronoi edge of
// a face of their convex hull is a ray from the centre: Tri S|Σ is the hull, with F = 2V − 4.
std::vector<TriangleKey> hull_triangles(CheckFixture& f, std::size_t vertices) {
  auto triangles = f.restricted.triangles();
  BOOST_TEST_REQUIRE(triangles.size() == 2 * vertices - 4);
  return triangles;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(quality)

BOOST_AUTO_TEST_CASE(radius_edge_ratio_known_values) {
  // Equilateral: R = a/√3, ratio 1/√3.
  BOOST_TEST(std::abs(radius_edge_ratio({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}) - 1 / std::sqrt(3.0)) < 1e-12);
  // Right isoceles with legs 1: R = √2/2, shortest edge 1.
  BOOST_TEST(std::abs(radius_edge_ratio({0, 0, 0}, {1, 0, 0}, {0, 1, 0}) - std::sqrt(2.0) / 2) < 1e-12);
  BOOST_TEST(std::abs(circumradius({0, 0, 0}, {2, 0, 0}, {0, 2, 0}) - std::sqrt(2.0)) < 1e-12);
  BOOST_TEST(std::isinf(radius_edge_ratio({0, 0, 0}, {1, 0, 0}, {2, 0, 0})));
}

// Scale-free: the triangle scaled by 1e200 or 1e-300 (whose squared lengths overflow or
// underflow) has the ratio of the unscaled one and the circumradius times the scale.
BOOST_AUTO_TEST_CASE(radius_edge_ratio_at_extreme_scales) {
  const Vec3 p{0.1, 0.2, 0.3}, q{1.3, -0.4, 0.2}, r{0.5, 0.9, -0.7};
  const double ratio = radius_edge_ratio(p, q, r), radius = circumradius(p, q, r);
  for (const double s : {1e200, 1e-300}) {
    BOOST_TEST(std::abs(radius_edge_ratio(s * p, s * q, s * r) - ratio) < 1e-12 * ratio, "scale " << s);
    BOOST_TEST(std::abs(circumradius(s * p, s * q, s * r) / s - radius) < 1e-12 * radius, "scale " << s);
  }
}

// The octahedron with a seventh sample 0.2 away from its vertex (1, 0, 0): the hull faces at that
// short edge are needles (ratio ≈ 3), the faces away from it equilateral (ratio 1/√3).  Quality
// fires exactly on the triangles with ratio > 1 + λ, with the point where their dual edge meets
// Σ, measured from the later vertex of the shortest edge; the threshold is sharp.
BOOST_AUTO_TEST_CASE(quality_witness_fires_iff_the_ratio_exceeds_1_plus_lambda) {
  auto points = octahedron;
  points.push_back(detail::normalized(Vec3{1, 0.2, 0.05}));
  CheckFixture f(test::unit_sphere, 1.5, points);
  const double lambda = 0.06;
  int fired = 0, clean = 0;
  for (const auto& t : hull_triangles(f, points.size())) {
    const Vec3 &p = f.del.point(t[0]), &q = f.del.point(t[1]), &r = f.del.point(t[2]);
    const double rho = radius_edge_ratio(p, q, r);
    const auto w = quality_witness(f.restricted, t, lambda);
    BOOST_TEST(w.has_value() == (rho > 1 + lambda), "triangle " << t[0] << t[1] << t[2] << " ratio " << rho);
    if (!w) {
      ++clean;
      continue;
    }
    ++fired;
    BOOST_TEST((w->kind == CheckKind::quality));
    BOOST_TEST(std::abs(f.oracle.E(w->point)) < 1e-9);
    // On the dual Voronoi edge: equidistant from the three vertices, no sample closer.
    const double radius = detail::distance(w->point, p);
    BOOST_TEST(detail::distance(w->point, q) == radius, boost::test_tools::tolerance(1e-9));
    BOOST_TEST(detail::distance(w->point, r) == radius, boost::test_tools::tolerance(1e-9));
    for (const auto& s : points) BOOST_TEST(detail::distance(w->point, s) >= radius - 1e-9);
    const std::array<std::array<VertexId, 2>, 3> edges{{{t[0], t[1]}, {t[0], t[2]}, {t[1], t[2]}}};
    const auto shortest = *std::min_element(edges.begin(), edges.end(), [&](const auto& a, const auto& b) {
      return detail::distance(f.del.point(a[0]), f.del.point(a[1])) <
             detail::distance(f.del.point(b[0]), f.del.point(b[1]));
    });
    BOOST_TEST(w->measured_from == std::max(shortest[0], shortest[1]));
    BOOST_TEST(!quality_witness(f.restricted, t, rho - 1 + 1e-9).has_value());
    BOOST_TEST(quality_witness(f.restricted, t, rho - 1 - 1e-9).has_value());
  }
  BOOST_TEST(fired > 0);
  BOOST_TEST(clean > 0);
}

// Each face of the octahedron has its dual ray through its centroid direction c = (±1, ±1, ±1)/√3,
// so its surface Delaunay ball has centre c and radius |c − (1, 0, 0)| = √(2 − 2/√3) ≈ 0.919.
// Size control fires exactly when that radius exceeds H, with c; never on a Delaunay triangle
// outside Tri S|Σ (the octahedron's inner triangles, whose dual edges stay at the centre).
BOOST_AUTO_TEST_CASE(size_witness_fires_iff_the_surface_delaunay_ball_is_wider_than_H) {
  CheckFixture f(test::unit_sphere, 1.5, octahedron);
  const double radius = std::sqrt(2 - 2 / std::sqrt(3.0));
  const auto triangles = hull_triangles(f, octahedron.size());
  for (const auto& t : triangles) {
    BOOST_TEST(!size_witness(f.restricted, t, radius * (1 + 1e-9)).has_value());
    const auto w = size_witness(f.restricted, t, radius * (1 - 1e-9));
    BOOST_TEST_REQUIRE(w.has_value());
    BOOST_TEST((w->kind == CheckKind::size));
    const Vec3 centre =
        detail::normalized(f.del.point(t[0]) + f.del.point(t[1]) + f.del.point(t[2]));
    BOOST_TEST(detail::distance(w->point, centre) < 1e-9);
  }
  int inner = 0;
  for (const auto& t : f.del.triangles()) {
    if (std::find(triangles.begin(), triangles.end(), t) != triangles.end()) continue;
    ++inner;
    BOOST_TEST(!size_witness(f.restricted, t, 1e-3).has_value());
  }
  BOOST_TEST(inner > 0);
}

BOOST_AUTO_TEST_SUITE_END()
