#include "meshing/inputs/sharp_features.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "meshing/driver/mesh_options.h"
#include "meshing/inputs/folded_vertices.h"
#include "tests/meshing/feature_meshes.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;

namespace {

// Every feature edge lies on exactly one curve, each curve is a connected polyline whose
// interior vertices are not corners and whose ends are corners (or it is closed without one).
void require_consistent(const SurfaceMesh& mesh, const FeatureSet& set) {
  std::multiset<SurfaceMesh::Edge_index> on_curves;
  for (const FeatureCurve& curve : set.curves) {
    BOOST_REQUIRE_EQUAL(curve.vertices.size(), curve.edges.size() + 1);
    for (std::size_t i = 0; i < curve.edges.size(); ++i) {
      const auto e = curve.edges[i];
      const auto a = mesh.vertex(e, 0), b = mesh.vertex(e, 1);
      BOOST_TEST(((a == curve.vertices[i] && b == curve.vertices[i + 1]) ||
                  (b == curve.vertices[i] && a == curve.vertices[i + 1])));
      on_curves.insert(e);
      if (i > 0) BOOST_TEST(!set.is_corner(curve.vertices[i]));
    }
    BOOST_TEST(curve.closed == (curve.vertices.front() == curve.vertices.back()));
    if (curve.without_corner) {
      BOOST_TEST(curve.closed);
      BOOST_TEST(!set.is_corner(curve.vertices.front()));
    } else {
      BOOST_TEST(set.is_corner(curve.vertices.front()));
      BOOST_TEST(set.is_corner(curve.vertices.back()));
    }
  }
  BOOST_TEST(on_curves.size() == set.feature_edges.size());
  for (auto e : set.feature_edges) BOOST_TEST(on_curves.count(e) == 1u);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(sharp_features_suite)

BOOST_AUTO_TEST_CASE(the_normal_angle_test_is_exact_at_sixty_degrees) {
  // Normals (1, 1, 0) and (1, 0, 1): exactly 60° apart.
  const Point3 o(0, 0, 0), a(-1, 1, 0), b(0, 0, 1), c(1, 0, -1), d(0, 1, 0);
  BOOST_TEST(!normals_differ_by_more_than(o, a, b, o, c, d, 60));
  BOOST_TEST(normals_differ_by_more_than(o, a, b, o, c, d, 59.999999));
  BOOST_TEST(!normals_differ_by_more_than(o, a, b, o, c, d, 60.000001));
  // Opposite normals differ by 180°, equal ones by 0°; a degenerate triangle is sharp.
  BOOST_TEST(normals_differ_by_more_than(o, a, b, o, b, a, 179));
  BOOST_TEST(!normals_differ_by_more_than(o, a, b, o, a, b, 1));
  BOOST_TEST(normals_differ_by_more_than(o, a, b, o, o, a, 179));
  // Normals (1, 1, 0) and (−1, 0, −1): cos = −1/2, exactly 120°.
  BOOST_TEST(!normals_differ_by_more_than(o, a, b, o, d, c, 120));
  BOOST_TEST(normals_differ_by_more_than(o, a, b, o, d, c, 119.9999));
  BOOST_CHECK_THROW(normals_differ_by_more_than(o, a, b, o, c, d, 0), PreconditionViolation);
  BOOST_CHECK_THROW(normals_differ_by_more_than(o, a, b, o, c, d, 180), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(a_cube_has_twelve_curves_between_eight_corners) {
  for (int n : {1, 4}) {
    const SurfaceMesh mesh = test::grid_cube(n).to_surface_mesh();
    const FeatureSet set = detect_features(mesh);
    BOOST_TEST(set.angle_deg == 60);
    BOOST_TEST(set.sharp_edges == std::size_t(12 * n));
    BOOST_TEST(set.border_edges == 0u);
    BOOST_TEST(set.feature_edges.size() == std::size_t(12 * n));
    BOOST_TEST(set.corners.size() == 8u);
    BOOST_TEST(set.folded_corners == 0u);
    BOOST_REQUIRE(set.curves.size() == 12u);
    BOOST_TEST(set.closed_curves == 0u);
    for (const FeatureCurve& curve : set.curves) {
      BOOST_TEST(curve.edges.size() == std::size_t(n));
      // A cube edge: the ends differ in one coordinate by 1, the curve is straight.
      const Point3 &p = mesh.point(curve.vertices.front()), &q = mesh.point(curve.vertices.back());
      BOOST_TEST(CGAL::squared_distance(p, q) == 1.0);
    }
    for (auto v : set.corners) {
      const Point3& p = mesh.point(v);
      for (double x : {p.x(), p.y(), p.z()}) BOOST_TEST((x == 0 || x == 1));
    }
    require_consistent(mesh, set);
    // Curves leave the corners in ascending order.
    for (std::size_t k = 1; k < set.curves.size(); ++k)
      BOOST_TEST(set.curves[k - 1].vertices.front() <= set.curves[k].vertices.front());
    // Above 90° nothing on a cube is sharp.
    BOOST_TEST(detect_features(mesh, 91).feature_edges.empty());
  }
}

BOOST_AUTO_TEST_CASE(a_crease_and_its_border) {
  const int n = 3;
  // 90° between the strips' normals: the crease (n edges) is sharp; the border is a feature.
  const SurfaceMesh mesh = test::crease(90, n).to_surface_mesh();
  const FeatureSet set = detect_features(mesh);
  BOOST_TEST(set.sharp_edges == std::size_t(n));
  BOOST_TEST(set.border_edges == std::size_t(2 * (2 * n) + 2 * n));
  // The crease's ends have three feature edges: the two corners; the border splits there.
  BOOST_REQUIRE(set.corners.size() == 2u);
  for (auto v : set.corners) BOOST_TEST(std::abs(mesh.point(v).x()) < 1e-15);
  BOOST_REQUIRE(set.curves.size() == 3u);
  std::vector<std::size_t> lengths;
  for (const FeatureCurve& c : set.curves) lengths.push_back(c.edges.size());
  std::sort(lengths.begin(), lengths.end());
  BOOST_TEST(lengths == (std::vector<std::size_t>{std::size_t(n), std::size_t(3 * n), std::size_t(3 * n)}),
             boost::test_tools::per_element());
  require_consistent(mesh, set);

  // 30° between the normals: only the border, one closed curve without corner, starting at its
  // smallest vertex.
  const SurfaceMesh gentle = test::crease(30, n).to_surface_mesh();
  const FeatureSet border = detect_features(gentle);
  BOOST_TEST(border.sharp_edges == 0u);
  BOOST_TEST(border.corners.empty());
  BOOST_REQUIRE(border.curves.size() == 1u);
  const FeatureCurve& loop = border.curves.front();
  BOOST_TEST(loop.closed);
  BOOST_TEST(loop.without_corner);
  BOOST_TEST(loop.edges.size() == std::size_t(6 * n));
  BOOST_TEST(loop.vertices.front() == *std::min_element(loop.vertices.begin(), loop.vertices.end()));
  BOOST_TEST(loop.vertices[1] < loop.vertices[loop.vertices.size() - 2]);
  require_consistent(gentle, border);
}

BOOST_AUTO_TEST_CASE(folded_vertices_are_corners_and_split_curves) {
  const int n = 4;
  const SurfaceMesh mesh = test::crease(90, n).to_surface_mesh();
  // A vertex inside the crease declared folded splits the crease in two.
  SurfaceMesh::Vertex_index middle;
  for (auto v : mesh.vertices())
    if (mesh.point(v) == Point3(0, 0.5, 0)) middle = v;
  BOOST_REQUIRE(mesh.is_valid(middle));
  const FeatureSet set = detect_features(mesh, 60, {middle, middle});
  BOOST_TEST(set.folded_corners == 1u);
  BOOST_TEST(set.corners.size() == 3u);
  BOOST_TEST(set.is_corner(middle));
  BOOST_TEST(set.curves.size() == 4u);
  require_consistent(mesh, set);
  // A folded vertex away from every feature is an isolated corner.
  SurfaceMesh::Vertex_index inside;
  for (auto v : mesh.vertices())
    if (mesh.point(v) == Point3(-0.5, 0.5, 0)) inside = v;
  const FeatureSet isolated = detect_features(mesh, 60, {inside});
  BOOST_TEST(isolated.corners.size() == 3u);
  BOOST_TEST(isolated.curves.size() == 3u);
  // The fan of folded_vertices_test: its centre is folded, and a corner of detect_features.
  const test::Soup fan{{Point3(0, 0, 0), Point3(-0.3, -0.3, 1), Point3(0.3, -0.3, -1), Point3(-0.3, -0.3, -1),
                        Point3(0.3, -0.3, 1)},
                       {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}};
  const SurfaceMesh fan_mesh = fan.to_surface_mesh();
  const FeatureSet fan_set = detect_features(fan_mesh);
  BOOST_TEST(fan_set.folded_corners == 1u);
  BOOST_TEST(fan_set.is_corner(SurfaceMesh::Vertex_index(0)));
  BOOST_CHECK_THROW(detect_features(mesh, 60, {SurfaceMesh::Vertex_index(100000)}), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(smooth_closed_meshes_have_no_features) {
  const SurfaceMesh sphere = test::icosphere(2).to_surface_mesh();
  const FeatureSet set = detect_features(sphere);
  BOOST_TEST(set.feature_edges.empty());
  BOOST_TEST(set.corners.empty());
  BOOST_TEST(set.curves.empty());
  // The regular tetrahedron: normals 109.5° apart, four corners, six curves.
  const FeatureSet tet = detect_features(test::tetrahedron().to_surface_mesh());
  BOOST_TEST(tet.sharp_edges == 6u);
  BOOST_TEST(tet.corners.size() == 4u);
  BOOST_TEST(tet.curves.size() == 6u);
}

// The unit cube's feature edges (its 12 edges) against the facet of p and q, whose bisector is the
// plane z = 1/2: it crosses the four vertical edges at (x, y, 1/2), x, y ∈ {0, 1}, and no other
// edge (the horizontal ones lie in z = 0 and z = 1).
BOOST_AUTO_TEST_CASE(a_facet_meets_a_feature_edge_exactly_when_a_cut_lies_in_its_cell) {
  const SurfaceMesh cube = test::grid_cube(1).to_surface_mesh();
  const FeatureEdges edges(cube, detect_features(cube));
  BOOST_TEST(edges.size() == 12u);
  BOOST_TEST(edges.angle_deg() == default_feature_angle_deg);
  const Point3 p(0.5, 0.5, 0.7), q(0.5, 0.5, 0.3);
  // Alone, V_p is the half-space z ≥ 1/2: all four cuts lie in it.
  BOOST_TEST(edges.facet_meets_feature_edge(p, q, {}));
  BOOST_TEST(edges.facet_meets_feature_edge(q, p, {}));
  // A sample at each cut takes it out of V_p; three of them leave the fourth cut in.
  const std::vector<Point3> at_cuts{Point3(0, 0, 0.5), Point3(1, 0, 0.5), Point3(0, 1, 0.5), Point3(1, 1, 0.5)};
  BOOST_TEST(!edges.facet_meets_feature_edge(p, q, at_cuts));
  BOOST_TEST(edges.facet_meets_feature_edge(p, q, {at_cuts[0], at_cuts[1], at_cuts[2]}));
  // The cell is closed: with p2 = (½, 0, 1) and q2 = (½, 0, 0), the cut (0, 0, ½) is at squared
  // distance ½ from p2 and from s = (−½, 0, 0), a tie that keeps it (the other three cuts are
  // taken out by samples on them); moving s nearer to the cut takes it out.
  const Point3 p2(0.5, 0, 1), q2(0.5, 0, 0);
  const std::vector<Point3> tie{Point3(-0.5, 0, 0), at_cuts[1], at_cuts[2], at_cuts[3]};
  BOOST_TEST(edges.facet_meets_feature_edge(p2, q2, tie));
  const std::vector<Point3> nearer{Point3(-0.5, 0, 0.25), at_cuts[1], at_cuts[2], at_cuts[3]};
  BOOST_TEST(!edges.facet_meets_feature_edge(p2, q2, nearer));
  // An endpoint on the bisector is not a strict crossing: B(p3, q3) is the plane z = 1, which
  // holds the top face's edges and the vertical edges' upper ends.
  BOOST_TEST(!edges.facet_meets_feature_edge(Point3(0.5, 0.5, 1.5), Point3(0.5, 0.5, 0.5), {}));
  // No feature edges (features off, or a cube at a feature angle above 90°): no facet meets one.
  BOOST_TEST(!FeatureEdges().facet_meets_feature_edge(p, q, {}));
  BOOST_TEST(FeatureEdges(cube, detect_features(cube, 91)).empty());
}

// A run's feature angle defaults to the one stated here.
BOOST_AUTO_TEST_CASE(the_run_options_default_to_the_default_feature_angle) {
  BOOST_TEST(DelMeshOptions{}.feature_angle_deg.has_value());
  BOOST_TEST(*DelMeshOptions{}.feature_angle_deg == default_feature_angle_deg);
}

BOOST_AUTO_TEST_SUITE_END()
