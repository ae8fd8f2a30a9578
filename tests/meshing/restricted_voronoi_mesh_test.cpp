#include <boost/test/unit_test.hpp>

#include <cmath>
#include <random>
#include <set>

#include <CGAL/boost/graph/Euler_operations.h>

#include "common/errors.h"
#include "meshing/voronoi/restricted_voronoi_mesh.h"
#include "tests/meshing/feature_meshes.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;

namespace {

double dist(const std::array<double, 3>& x, const Point3& p) {
  return std::sqrt(CGAL::squared_distance(Point3(x[0], x[1], x[2]), p));
}

double polygon_area(const RvdPolygon& polygon) {
  const auto& x = polygon.points;
  double n[3] = {0, 0, 0};
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    const double a[3] = {x[i][0] - x[0][0], x[i][1] - x[0][1], x[i][2] - x[0][2]};
    const double b[3] = {x[i + 1][0] - x[0][0], x[i + 1][1] - x[0][1], x[i + 1][2] - x[0][2]};
    n[0] += a[1] * b[2] - a[2] * b[1];
    n[1] += a[2] * b[0] - a[0] * b[2];
    n[2] += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

double mesh_area(const SurfaceMesh& mesh) {
  double area = 0;
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    area += std::sqrt(CGAL::squared_area(mesh.point(mesh.source(h)), mesh.point(mesh.target(h)),
                                         mesh.point(mesh.target(mesh.next(h)))));
  }
  return area;
}

// The cube [0, 1]³ (two triangles per side) with samples near its corners, each moved by a
// different small offset so that no four samples are cocircular on a side.
std::vector<Point3> cube_corner_samples() {
  const double d[8][3] = {{0.011, 0.023, 0.005},  {-0.017, 0.008, 0.013}, {0.004, -0.019, 0.021},
                          {-0.009, -0.003, -0.014}, {0.015, 0.006, -0.022}, {-0.012, 0.018, -0.007},
                          {0.02, -0.011, 0.016},   {-0.006, -0.016, -0.01}};
  std::vector<Point3> s;
  for (int i = 0; i < 8; ++i) s.emplace_back((i & 1) + d[i][0], ((i >> 1) & 1) + d[i][1], ((i >> 2) & 1) + d[i][2]);
  return s;
}

// Every polygon vertex of V_p is no farther from p than from any sample (up to rounding), its
// labels' sites are equidistant from it, and the pieces cover Σ: their areas add up to Σ's.
void check_diagram(const RestrictedVoronoiMesh& d, const std::vector<Point3>& samples, const SurfaceMesh& mesh) {
  double area = 0;
  const double tol = 1e-9;
  for (std::size_t p = 0; p < d.cells.size(); ++p)
    for (const RvdPolygon& polygon : d.cells[p]) {
      BOOST_TEST(polygon.site == p);
      BOOST_TEST_REQUIRE(polygon.vertices.size() >= 3u);
      BOOST_TEST(polygon.edges.size() == polygon.vertices.size());
      area += polygon_area(polygon);
      for (std::size_t i = 0; i < polygon.vertices.size(); ++i) {
        const auto& x = polygon.points[i];
        double nearest = dist(x, samples[p]);
        for (const Point3& q : samples) nearest = std::min(nearest, dist(x, q));
        BOOST_TEST(dist(x, samples[p]) <= nearest + tol);
        const RvdVertex& v = polygon.vertices[i];
        for (const std::size_t s : v.sites)
          if (s != rvd_none) BOOST_TEST(std::abs(dist(x, samples[s]) - dist(x, samples[p])) <= tol);
        // An edge on B(p, q) ends at vertices on B(p, q).
        const RvdEdgeSupport& e = polygon.edges[i];
        if (e.on_bisector) {
          const auto& y = polygon.points[(i + 1) % polygon.vertices.size()];
          BOOST_TEST(std::abs(dist(x, samples[e.a]) - dist(x, samples[p])) <= tol);
          BOOST_TEST(std::abs(dist(y, samples[e.a]) - dist(y, samples[p])) <= tol);
        }
      }
    }
  BOOST_TEST(std::abs(area - mesh_area(mesh)) <= 1e-9 * mesh_area(mesh));
}

}  // namespace

BOOST_AUTO_TEST_SUITE(restricted_voronoi_mesh_suite)

// Near-corner samples on the cube: each cell is the corner's three sides cut by bisectors, with
// its corner as an input vertex; face cuts lie on the sides.
BOOST_AUTO_TEST_CASE(cube_corners) {
  const SurfaceMesh cube = test::grid_cube(1).to_surface_mesh();
  const std::vector<Point3> s = cube_corner_samples();
  const RestrictedVoronoiMesh d = restricted_voronoi_mesh(s, cube);
  BOOST_TEST(d.contacts.empty());
  check_diagram(d, s, cube);
  for (std::size_t p = 0; p < 8; ++p) {
    std::set<std::size_t> corners;
    for (const RvdPolygon& polygon : d.cells[p])
      for (const RvdVertex& v : polygon.vertices)
        if (v.kind == RvdVertexKind::input_vertex) corners.insert(v.input[0]);
    // The only input vertex in V_p is the cube's corner i (grid_cube numbers its vertices in
    // another order; the corner is the one nearest to the sample).
    BOOST_TEST_REQUIRE(corners.size() == 1u);
    const Point3& corner = cube.point(SurfaceMesh::Vertex_index(static_cast<std::uint32_t>(*corners.begin())));
    BOOST_TEST(CGAL::squared_distance(corner, s[p]) < 0.01);
  }
}

// Jittered samples of the smooth torus against a fine torus mesh: the pieces cover Σ and every
// vertex lies in its own cell.
BOOST_AUTO_TEST_CASE(torus_pieces_cover_the_surface) {
  const SurfaceMesh torus = test::torus(48, 24).to_surface_mesh();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.25, 0.25);
  std::vector<Point3> s;
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 8; ++k) {
      const double u = 2 * M_PI * (i + jitter(random)) / 16, v = 2 * M_PI * (k + jitter(random)) / 8;
      s.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  const RestrictedVoronoiMesh d = restricted_voronoi_mesh(s, torus);
  BOOST_TEST(d.contacts.empty());
  check_diagram(d, s, torus);
  for (const auto& cell : d.cells) BOOST_TEST(!cell.empty());
}

// Samples at the cube's exact corners: each side's centre is equidistant from its four corners,
// so the Voronoi edges of those corners run through the side's diagonal at its centre: contacts of
// kind voronoi_edge_through_input_edge, all at side centres, and no other kind.
BOOST_AUTO_TEST_CASE(exact_cube_corners_are_not_generic) {
  const SurfaceMesh cube = test::grid_cube(1).to_surface_mesh();
  std::vector<Point3> s;
  for (int i = 0; i < 8; ++i) s.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const RestrictedVoronoiMesh d = restricted_voronoi_mesh(s, cube);
  BOOST_TEST_REQUIRE(!d.contacts.empty());
  std::set<std::array<double, 3>> centres;
  for (const RvdContact& c : d.contacts) {
    BOOST_TEST(c.kind == RvdContactKind::voronoi_edge_through_input_edge);
    BOOST_TEST(c.sites.size() == 3u);
    int halves = 0, ends = 0;
    for (const double x : c.location) {
      halves += x == 0.5;
      ends += x == 0 || x == 1;
    }
    BOOST_TEST((halves == 2 && ends == 1));
    centres.insert(c.location);
  }
  BOOST_TEST(centres.size() == 6u);
}

// The octahedron ±e_i with samples (0, 0, ±2): the bisector z = 0 holds the four equator
// vertices.
BOOST_AUTO_TEST_CASE(bisector_through_input_vertices) {
  const SurfaceMesh octahedron = test::octahedron().to_surface_mesh();
  const RestrictedVoronoiMesh d = restricted_voronoi_mesh({Point3(0, 0, 2), Point3(0, 0, -2)}, octahedron);
  BOOST_TEST_REQUIRE(d.contacts.size() == 4u);
  for (const RvdContact& c : d.contacts) {
    BOOST_TEST(c.kind == RvdContactKind::input_vertex_on_bisector);
    BOOST_TEST((c.sites == std::vector<std::size_t>{0, 1}));
    BOOST_TEST(c.location[2] == 0.0);
    BOOST_TEST(std::abs(c.location[0]) + std::abs(c.location[1]) == 1.0);
  }
  // Ties go to the cell being clipped: each cell holds its four closed half-octahedron triangles.
  BOOST_TEST(d.cells[0].size() == 4u);
  BOOST_TEST(d.cells[1].size() == 4u);
}

BOOST_AUTO_TEST_CASE(preconditions) {
  const SurfaceMesh cube = test::grid_cube(1).to_surface_mesh();
  BOOST_CHECK_THROW((void)restricted_voronoi_mesh({Point3(0, 0, 0), Point3(0, 0, 0)}, cube), PreconditionViolation);
  const double inf = std::numeric_limits<double>::infinity();
  BOOST_CHECK_THROW((void)restricted_voronoi_mesh({Point3(inf, 0, 0)}, cube), PreconditionViolation);
  SurfaceMesh open = cube;
  CGAL::Euler::remove_face(open.halfedge(*open.faces().begin()), open);
  open.collect_garbage();
  BOOST_CHECK_THROW((void)restricted_voronoi_mesh({Point3(0, 0, 0)}, open), PreconditionViolation);
  // One sample: its cell is all of R³, so each triangle is one piece, unclipped.
  const RestrictedVoronoiMesh d = restricted_voronoi_mesh({Point3(5, 5, 5)}, cube);
  BOOST_TEST(d.cells[0].size() == cube.number_of_faces());
  for (const RvdPolygon& polygon : d.cells[0]) BOOST_TEST(polygon.vertices.size() == 3u);
}

BOOST_AUTO_TEST_SUITE_END()
