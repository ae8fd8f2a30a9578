#include <boost/test/unit_test.hpp>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include "meshing/checks/closed_ball.h"
#include "tests/meshing/feature_meshes.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;

namespace {

using Triangles = std::vector<std::array<std::size_t, 3>>;

// V − E + F of a set of triangles on `vertices` vertices, and whether every edge has two.
struct Closed {
  long euler = 0;
  bool every_edge_twice = true;
};
Closed closed_surface(const Triangles& triangles, std::size_t vertices) {
  std::map<std::array<std::size_t, 2>, int> edges;
  for (const auto& t : triangles) {
    ++edges[{t[0], t[1]}];
    ++edges[{t[0], t[2]}];
    ++edges[{t[1], t[2]}];
  }
  Closed c;
  for (const auto& [e, n] : edges) c.every_edge_twice &= n == 2;
  c.euler = long(vertices) - long(edges.size()) + long(triangles.size());
  return c;
}

// A surface mesh with these triangles (oriented consistently) on vertices 0..vertices−1.
SurfaceMesh mesh_of(const Triangles& triangles, std::size_t vertices) {
  std::vector<Point3> points;
  for (std::size_t i = 0; i < vertices; ++i) points.emplace_back(double(i), double(i * i), 0);
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : triangles) polygons.push_back({t[0], t[1], t[2]});
  BOOST_TEST_REQUIRE(CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons));
  BOOST_TEST_REQUIRE(points.size() == vertices);
  SurfaceMesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  return mesh;
}

std::vector<Point3> cube_corner_samples() {
  const double d[8][3] = {{0.011, 0.023, 0.005},  {-0.017, 0.008, 0.013}, {0.004, -0.019, 0.021},
                          {-0.009, -0.003, -0.014}, {0.015, 0.006, -0.022}, {-0.012, 0.018, -0.007},
                          {0.02, -0.011, 0.016},   {-0.006, -0.016, -0.01}};
  std::vector<Point3> s;
  for (int i = 0; i < 8; ++i) s.emplace_back((i & 1) + d[i][0], ((i >> 1) & 1) + d[i][1], ((i >> 2) & 1) + d[i][2]);
  return s;
}

std::size_t count(const ClosedBallResult& r, ClosedBallDefect defect) {
  std::size_t n = 0;
  for (const ClosedBallViolation& v : r.violations) n += v.defect == defect;
  return n;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(closed_ball)

// Samples near the cube's eight corners (cube_corner_samples: no four cocircular on a side):
// each cell is a disk of three corner pieces; the facets are the 12 arcs across the cube's edges
// and the 6 across the sides' centres (there two of the side's four samples are Delaunay
// neighbours); each side's centre region holds two Voronoi-edge crossings, so Del S|Σ has 12
// triangles on 8 vertices, every edge in two of them: a sphere (V − E + F = 8 − 18 + 12 = 2).
BOOST_AUTO_TEST_CASE(cube_corners_hold) {
  const SurfaceMesh cube = test::grid_cube(1).to_surface_mesh();
  const ClosedBallResult r = closed_ball_check(cube_corner_samples(), cube);
  BOOST_TEST(r.status == ClosedBallStatus::holds);
  BOOST_TEST(r.violations.empty());
  BOOST_TEST(r.contacts.empty());
  BOOST_TEST(r.cells_checked == 8u);
  BOOST_TEST(r.facets_checked == 18u);
  BOOST_TEST(r.edges_checked == 12u);
  BOOST_TEST_REQUIRE(r.restricted_delaunay.size() == 12u);
  const Closed c = closed_surface(r.restricted_delaunay, 8);
  BOOST_TEST(c.every_edge_twice);
  BOOST_TEST(c.euler == 2);
  BOOST_TEST(compare_with_restricted_delaunay(r, mesh_of(r.restricted_delaunay, 8)).equal);
  Triangles fewer(r.restricted_delaunay.begin() + 1, r.restricted_delaunay.end());
  const RestrictedDelaunayComparison c1 = compare_with_restricted_delaunay(r, mesh_of(fewer, 8));
  BOOST_TEST(!c1.equal);
  BOOST_TEST(c1.only_restricted_delaunay == 1u);
  BOOST_TEST(c1.only_mesh == 0u);
  const nlohmann::json j = closed_ball_json(r, 3);
  BOOST_TEST(j["status"] == "holds");
  BOOST_TEST(j["violations"]["count"] == 0);
}

// Six samples on the torus's outer equator (R = 2, r = 1; all in one plane): every cell is a
// slice of the tube around it, an annulus, and every facet a closed loop around the tube.  The
// witness is the cell's farthest point, on the inner side of the tube.
BOOST_AUTO_TEST_CASE(torus_ring_gives_annuli) {
  const SurfaceMesh torus = test::torus(24, 12).to_surface_mesh();
  std::vector<Point3> s;
  for (int i = 0; i < 6; ++i) {
    const double u = 2 * M_PI * (i + 0.1234) / 6;
    s.emplace_back(2.9 * std::cos(u) + 0.001 * i, 2.9 * std::sin(u), 0.0123);
  }
  const ClosedBallResult r = closed_ball_check(s, torus);
  BOOST_TEST(r.status == ClosedBallStatus::violated);
  BOOST_TEST(count(r, ClosedBallDefect::cell_annulus) == 6u);
  BOOST_TEST(count(r, ClosedBallDefect::facet_closed_loop) == 6u);
  BOOST_TEST(r.restricted_delaunay.empty());
  for (const ClosedBallViolation& v : r.violations)
    if (v.defect == ClosedBallDefect::cell_annulus) {
      BOOST_TEST(v.euler_characteristic == 0);
      BOOST_TEST(v.boundary_cycles == 2u);
      BOOST_TEST(std::hypot(v.witness[0], v.witness[1]) < 1.1);  // inner side: radius 1
      BOOST_TEST(v.witness_distance > 1.8);
    }
}

// 128 jittered samples of the torus against a 48 × 24 torus mesh: the property holds and Del S|Σ
// is a closed surface with V − E + F = 0, i.e. genus 1 (it is connected: every sample has a
// triangle and the triangles' edge graph joins them all).
BOOST_AUTO_TEST_CASE(dense_torus_holds_with_genus_one) {
  const SurfaceMesh torus = test::torus(48, 24).to_surface_mesh();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  std::vector<Point3> s;
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 8; ++k) {
      const double u = 2 * M_PI * (i + jitter(random)) / 16, v = 2 * M_PI * (k + jitter(random)) / 8;
      s.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  const ClosedBallResult r = closed_ball_check(s, torus);
  BOOST_TEST(r.status == ClosedBallStatus::holds);
  BOOST_TEST(r.cells_checked == s.size());
  const Closed c = closed_surface(r.restricted_delaunay, s.size());
  BOOST_TEST(c.every_edge_twice);
  BOOST_TEST(c.euler == 0);
  std::vector<std::size_t> parent(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) parent[i] = i;
  const auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  for (const auto& t : r.restricted_delaunay) {
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  std::set<std::size_t> roots;
  for (std::size_t i = 0; i < s.size(); ++i) roots.insert(find(i));
  BOOST_TEST(roots.size() == 1u);
}

// Two unit spheres at x = ±3 and two samples far above and below them: each cell meets both
// spheres (two disks), and the facet z ≈ 0 cuts both equators (two closed loops).
BOOST_AUTO_TEST_CASE(cell_of_two_pieces) {
  test::Soup spheres = test::icosphere(2).translated(3, 0, 0);
  spheres.append(test::icosphere(2).translated(-3, 0, 0));
  const ClosedBallResult r = closed_ball_check({Point3(0.01, 0.02, 5), Point3(-0.03, 0.01, -5)}, spheres.to_surface_mesh());
  BOOST_TEST(r.status == ClosedBallStatus::violated);
  BOOST_TEST_REQUIRE(count(r, ClosedBallDefect::cell_components) == 2u);
  BOOST_TEST(r.violations[0].components == 2u);
  BOOST_TEST(r.violations[0].euler_characteristic == 2);  // two disks
  BOOST_TEST_REQUIRE(count(r, ClosedBallDefect::facet_components) == 1u);
  BOOST_TEST(r.violations[2].components == 2u);
}

// Three samples on a sphere's equator, 120° apart: the cells are lunes (disks) and the facets
// meridian arcs, but their Voronoi edge, near the z axis, meets the sphere at both poles.
BOOST_AUTO_TEST_CASE(voronoi_edge_meeting_twice) {
  std::vector<Point3> s;
  for (int i = 0; i < 3; ++i) {
    const double u = 2 * M_PI * i / 3 + 0.01 * i;
    s.emplace_back(std::cos(u), std::sin(u), 0.001 * i);
  }
  const ClosedBallResult r = closed_ball_check(s, test::icosphere(3).to_surface_mesh());
  BOOST_TEST(r.status == ClosedBallStatus::violated);
  BOOST_TEST_REQUIRE(r.violations.size() == 1u);
  const ClosedBallViolation& v = r.violations.front();
  BOOST_TEST(v.defect == ClosedBallDefect::edge_points);
  BOOST_TEST(v.points == 2u);
  BOOST_TEST((v.sites == std::vector<std::size_t>{0, 1, 2}));
  BOOST_TEST(std::abs(std::abs(v.witness[2]) - 1) < 0.01);  // a pole
}

// The octahedron ±e_i with samples (0, 0, ±2): the bisector z = 0 holds four input vertices,
// so the property is not claimed: non_generic, with the contacts at the equator's vertices.
BOOST_AUTO_TEST_CASE(bisector_through_vertex_is_non_generic) {
  const ClosedBallResult r =
      closed_ball_check({Point3(0, 0, 2), Point3(0, 0, -2)}, test::octahedron().to_surface_mesh());
  BOOST_TEST(r.status == ClosedBallStatus::non_generic);
  BOOST_TEST_REQUIRE(r.contacts.size() == 4u);
  for (const RvdContact& c : r.contacts) BOOST_TEST(c.kind == RvdContactKind::input_vertex_on_bisector);
  const nlohmann::json j = closed_ball_json(r, 2);
  BOOST_TEST(j["status"] == "non_generic");
  BOOST_TEST(j["non_generic"]["count"] == 4);
  BOOST_TEST(j["non_generic"]["first"].size() == 2u);
  BOOST_TEST(j["non_generic"]["by_kind"]["input_vertex_on_bisector"] == 4);
}

// The same samples moved off the axis by a generic amount: the bisector misses the vertices; the
// two cells are caps (disks), but their facet meets Σ in a closed loop around the waist.
BOOST_AUTO_TEST_CASE(two_samples_give_a_closed_facet) {
  const ClosedBallResult r =
      closed_ball_check({Point3(0.013, 0.021, 2), Point3(-0.017, 0.005, -1.9)}, test::octahedron().to_surface_mesh());
  BOOST_TEST(r.status == ClosedBallStatus::violated);
  BOOST_TEST_REQUIRE(r.violations.size() == 1u);
  BOOST_TEST(r.violations[0].defect == ClosedBallDefect::facet_closed_loop);
  BOOST_TEST(r.cells_checked == 2u);
}

BOOST_AUTO_TEST_SUITE_END()
