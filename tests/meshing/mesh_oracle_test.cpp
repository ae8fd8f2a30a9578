// The surface oracle of a triangle mesh (meshing/inputs/mesh_oracle.h): each primitive on a constructed
// mesh whose answer is known, and an end-to-end remesh of a small closed mesh.
#include <boost/test/unit_test.hpp>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "common/errors.h"
#include "known_meshes.h"
#include "meshing/core/detail/vec3.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/input_mesh.h"
#include "meshing/inputs/mesh_oracle.h"
#include "solvers/query_geometry.h"

using namespace delmesh;
using namespace delmesh::detail;

namespace {

SurfaceMesh mesh_of(const std::vector<Vec3>& points, const std::vector<std::array<int, 3>>& triangles) {
  SurfaceMesh m;
  std::vector<SurfaceMesh::Vertex_index> v;
  for (const auto& p : points) v.push_back(m.add_vertex(Point3(p[0], p[1], p[2])));
  for (const auto& t : triangles) BOOST_REQUIRE(m.add_face(v[t[0]], v[t[1]], v[t[2]]) != SurfaceMesh::null_face());
  return m;
}

// The octahedron with vertices ±e_i, outward oriented.
SurfaceMesh octahedron() {
  return mesh_of({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}},
                 {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

// The cube [−1, 1]³, two outward triangles per side.
SurfaceMesh cube() {
  std::vector<Vec3> p;
  for (int i = 0; i < 8; ++i) p.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  // Each side as a quad, counter-clockwise seen from outside.
  const std::vector<std::array<int, 4>> quads{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::vector<std::array<int, 3>> t;
  for (const auto& q : quads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return mesh_of(p, t);
}

// A torus of radii R (centre circle, about the z-axis) and r (tube), n × m quads split in two.
SurfaceMesh torus(double R, double r, int n, int m) {
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      p.push_back({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  std::vector<std::array<int, 3>> t;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh_of(p, t);
}

Domain cube_domain(const Vec3& lo, const Vec3& hi) {
  return Domain::from_box({{lo[0], hi[0]}, {lo[1], hi[1]}, {lo[2], hi[2]}});
}

// The distance from x to the mesh.
double distance_to(const SurfaceMesh& mesh, const Vec3& x) {
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>>>;
  Tree tree(faces(mesh).first, faces(mesh).second, mesh);
  return std::sqrt(tree.squared_distance(Point3(x[0], x[1], x[2])));
}

}  // namespace

BOOST_AUTO_TEST_CASE(octahedron_critical_vertices_are_its_top_and_bottom) {
  MeshOracle oracle(octahedron(), Box3::cube(2));
  const Vec3 d = normalized(Vec3{0.1, 0.2, 1});
  const auto r = oracle.surface_critical(d, box_domain(oracle.box()), 1);
  BOOST_TEST(r.is_complete());
  BOOST_TEST_REQUIRE(r.roots.size() == 2u);
  std::vector<Vec3> found{r.roots[0].world, r.roots[1].world};
  std::sort(found.begin(), found.end());
  BOOST_TEST((found[0] == Vec3{0, 0, -1}));
  BOOST_TEST((found[1] == Vec3{0, 0, 1}));
  // In the direction of an axis the heights of four vertices tie: the tie is broken by index,
  // and there are still exactly one minimum and one maximum.
  const auto tied = oracle.surface_critical({0, 0, 1}, box_domain(oracle.box()), 1);
  BOOST_TEST(tied.roots.size() == 2u);
}

BOOST_AUTO_TEST_CASE(segments_through_a_cube_face_edge_and_vertex) {
  MeshOracle oracle(cube(), Box3::cube(2));
  // Through the interior of the face z = −1 and out of z = 1: two roots at the right t.
  {
    const auto r = oracle.surface_line({0.1, 0.2, -2}, {0, 0, 1}, 0, 4);
    BOOST_TEST(r.is_complete());
    BOOST_TEST_REQUIRE(r.roots.size() == 2u);
    BOOST_TEST(r.roots[0].midpoint[0] == 1.0);
    BOOST_TEST(r.roots[1].midpoint[0] == 3.0);
  }
  // Into the cube through the edge x = y = 1: one crossing at (1, 1, 0.3).
  {
    const auto r = oracle.surface_line({2, 2, 0.3}, {-1, -1, 0}, 0, 2);
    BOOST_TEST(r.is_complete());
    BOOST_TEST_REQUIRE(r.roots.size() == 1u);
    BOOST_TEST(distance(r.roots[0].world, Vec3{1, 1, 0.3}) < 1e-15);
  }
  // Along x + y = 2: touches the edge x = y = 1 without crossing — a double root.
  {
    const auto r = oracle.surface_line({0.5, 1.5, 0.3}, {1, -1, 0}, 0, 1);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST_REQUIRE(r.undecided.size() == 1u);
    BOOST_TEST((r.undecided[0].reason == UndecidedReason::singular_root));
    BOOST_TEST(distance(r.undecided[0].world, Vec3{1, 1, 0.3}) < 1e-15);
  }
  // Through the vertex (1, 1, 1) into the cube: a crossing, at t = 1.
  {
    const auto r = oracle.surface_line({2, 2, 2}, {-1, -1, -1}, 0, 1.5);
    BOOST_TEST(r.is_complete());
    BOOST_TEST_REQUIRE(r.roots.size() == 1u);
    BOOST_TEST((r.roots[0].world == Vec3{1, 1, 1}));
    BOOST_TEST(r.roots[0].midpoint[0] == 1.0);
  }
  // Through the vertex (1, 1, 1) and away, outside on both sides: it touches (a candidate).
  {
    const auto r = oracle.surface_line({0, 2, 1.5}, {1, -1, -0.5}, 0, 2);
    BOOST_TEST(r.roots.empty());
    BOOST_TEST_REQUIRE(r.undecided.size() == 1u);
    BOOST_TEST((r.undecided[0].reason == UndecidedReason::singular_root));
    BOOST_TEST((r.undecided[0].world == Vec3{1, 1, 1}));
  }
  // A zero at the segment's end, and the inside/outside sign.
  {
    const auto r = oracle.surface_line({0, 0, -1}, {0, 0, 1}, 0, 0.5);
    BOOST_TEST_REQUIRE(r.undecided.size() == 1u);
    BOOST_TEST((r.undecided[0].reason == UndecidedReason::boundary_root));
  }
  BOOST_TEST(oracle.value_sign({0, 0, 0}) == -1);
  BOOST_TEST(oracle.value_sign({0, 0, 1.5}) == 1);
  BOOST_TEST(oracle.value_sign({0.3, 0.2, 1}) == 0);
  BOOST_TEST(oracle.value_sign({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}) == -1);
  BOOST_TEST(oracle.value_sign({-0.5, -0.5, 0.5}, {0.5, 0.5, 1.5}) == 0);
  // Normals: a face's, an edge's (the mean), a vertex's; projection onto a face.
  BOOST_TEST(distance(oracle.normal({0.2, 0.3, 1}), Vec3{0, 0, 1}) < 1e-15);
  BOOST_TEST(distance(oracle.normal({1, 1, 0.3}), normalized(Vec3{1, 1, 0})) < 1e-15);
  BOOST_TEST(distance(oracle.normal({1, 1, 1}), normalized(Vec3{1, 1, 1})) < 1e-12);
  BOOST_TEST(distance(*oracle.project({0.2, 0.3, 1.4}), Vec3{0.2, 0.3, 1}) < 1e-15);
}

// value_sign at every point of the grid (k/4)³, |k| ≤ 6, against the exact answer: |x|₁ < 1
// inside the octahedron, |x|∞ < 1 inside the cube; on a face, an edge or a vertex, 0.  Many of the
// points lie on Σ or on the planes of faces and the lines of edges.
BOOST_AUTO_TEST_CASE(value_sign_on_a_grid_matches_the_octahedron_and_the_cube) {
  MeshOracle octahedron_oracle(octahedron(), Box3::cube(2));
  MeshOracle cube_oracle(cube(), Box3::cube(2));
  for (int i = -6; i <= 6; ++i)
    for (int j = -6; j <= 6; ++j)
      for (int k = -6; k <= 6; ++k) {
        const Vec3 x{i / 4.0, j / 4.0, k / 4.0};
        const int l1 = std::abs(i) + std::abs(j) + std::abs(k), linf = std::max({std::abs(i), std::abs(j), std::abs(k)});
        BOOST_TEST_CONTEXT("x = (" << x[0] << ", " << x[1] << ", " << x[2] << ")") {
          BOOST_TEST(octahedron_oracle.value_sign(x) == (l1 < 4 ? -1 : l1 == 4 ? 0 : 1));
          BOOST_TEST(cube_oracle.value_sign(x) == (linf < 4 ? -1 : linf == 4 ? 0 : 1));
        }
      }
}

// The octahedron of radius 2^28 centred at (0x1.98p59, 0x1.84p59, −2^53) (fuzz/crashes/
// fuzz_input_mesh/value_sign_ray_rounds_to_its_source_far_from_the_origin): its coordinates are
// multiples of 128 in x and y, and a point plus a unit vector rounds back to the point, so a ray
// cast constructed as "source + direction" in doubles is degenerate in every direction.
// value_sign decides every side exactly: 0 at the vertices and on a face and an edge, −1 inside,
// +1 inside the bounding box but outside the octahedron and at the box's corners.
BOOST_AUTO_TEST_CASE(value_sign_far_from_the_origin_on_a_coarse_lattice) {
  const double r = std::ldexp(1.0, 28);
  const Vec3 c{0x1.98p59, 0x1.84p59, -0x1p53};
  const std::vector<Vec3> unit{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  std::vector<Point3> points;
  for (const Vec3& u : unit) points.emplace_back(c[0] + r * u[0], c[1] + r * u[1], c[2] + r * u[2]);
  const std::vector<std::vector<std::size_t>> polygons{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const InputMesh input = validate_input_mesh(points, polygons, "far octahedron");
  MeshOracle oracle(input.mesh, input.box);
  BOOST_TEST_REQUIRE(oracle.scale_exponent() == 0);
  for (const Point3& p : points) BOOST_TEST(oracle.value_sign(Vec3{p.x(), p.y(), p.z()}) == 0);
  const auto at = [&](double u, double v, double w) { return Vec3{c[0] + u * r, c[1] + v * r, c[2] + w * r}; };
  BOOST_TEST(oracle.value_sign(c) == -1);
  BOOST_TEST(oracle.value_sign(at(0.25, -0.25, 0.25)) == -1);
  BOOST_TEST(oracle.value_sign(at(0.5, 0.25, 0.25)) == 0);   // inside the face (+, +, +)
  BOOST_TEST(oracle.value_sign(at(0.5, 0, -0.5)) == 0);      // on the edge from +x to −z
  BOOST_TEST(oracle.value_sign(at(0.5, 0.5, 0.5)) == 1);
  BOOST_TEST(oracle.value_sign(at(-0.75, 0, -0.75)) == 1);
  const Box3& box = oracle.box();
  for (int corner = 0; corner < 8; ++corner)
    BOOST_TEST(oracle.value_sign(Vec3{(corner & 1) ? box.hi[0] : box.lo[0], (corner & 2) ? box.hi[1] : box.lo[1],
                                      (corner & 4) ? box.hi[2] : box.lo[2]}) == 1);
}

BOOST_AUTO_TEST_CASE(a_torus_sliced_through_its_hole_gives_two_closed_polylines) {
  const double R = 2, r = 0.7;
  MeshOracle oracle(torus(R, r, 32, 16), Box3::cube(3));
  // The plane x = 0.0123 through the hole: two tube sections about (0, ±R, 0).
  const auto lines = oracle.section({0.0123, 0, 0}, {0, 1, 0}, {0, 0, 1});
  BOOST_TEST_REQUIRE(lines.size() == 2u);
  for (const auto& line : lines) {
    BOOST_TEST(line.closed);
    BOOST_TEST(line.points.size() >= 16u);
    for (const auto& x : line.points) {
      const double tube = std::hypot(std::hypot(x[0], x[1]) - R, x[2]);  // distance to the centre circle
      BOOST_TEST(tube <= 1.01 * r);
      BOOST_TEST(tube >= 0.95 * r);  // the mesh's chords stay close to the tube
    }
  }
  // CurveCritical in that plane over a facet around the tube at y = R: the section is closed, so
  // it has a minimum and a maximum in the direction a = y (at least two roots).
  const Domain facet = Domain::from_box({{R - 1, R + 1}, {-1, 1}});
  const auto critical = oracle.curve_critical({0.0123, 0, 0}, {0, 1, 0}, {0, 0, 1}, facet);
  BOOST_TEST(critical.roots.size() >= 2u);
  for (const auto& root : critical.roots) BOOST_TEST(std::abs(root.world[0] - 0.0123) < 1e-12);
  // A horizontal plane through the hole: the outer and the inner circle.
  const auto rings = oracle.section({0, 0, 0.0123}, {1, 0, 0}, {0, 1, 0});
  BOOST_TEST(rings.size() == 2u);
}

BOOST_AUTO_TEST_CASE(lines_through_a_saddle_vertex_of_a_torus) {
  // The vertex x of the inner equator at angle 0, where the mesh is saddle-shaped.
  const double R = 2, r = 0.7;
  const int n = 32, m = 16;
  MeshOracle oracle(torus(R, r, n, m), Box3::cube(3));
  const Vec3 x{R + r * std::cos(M_PI), 0, r * std::sin(M_PI)};
  // Radially out of the hole into the tube: a crossing at x.
  {
    const auto line = oracle.surface_line({0.5, x[1], x[2]}, {1, 0, 0}, 0, 1.5 - 0.5);
    BOOST_TEST(line.is_complete());
    BOOST_TEST_REQUIRE(line.roots.size() == 1u);
    BOOST_TEST((line.roots[0].world == x));
  }
  // Along the equator's tangent: inside the tube on both sides of x (the chords to the
  // neighbouring meridians bend towards the axis), so the line touches from inside.
  {
    const auto line = oracle.surface_line({x[0], -0.3, x[2]}, {0, 1, 0}, 0, 0.6);
    BOOST_TEST(line.roots.empty());
    BOOST_TEST_REQUIRE(line.undecided.size() == 1u);
    BOOST_TEST((line.undecided[0].reason == UndecidedReason::singular_root));
    BOOST_TEST((line.undecided[0].world == x));
    BOOST_TEST(oracle.value_sign({x[0], 0.2, x[2]}) == -1);
  }
}

BOOST_AUTO_TEST_CASE(section_extrema_are_decided_on_the_exact_crossings) {
  // A tetrahedron cut by the plane x = 0 into a quadrilateral section whose corners are the
  // crossings of the edges A1B1, A2B1, A2B2, A1B2 (A at x = −1, B at x = 1).  Exactly, the heights
  // y are (y_A + y_B)/2, so A1B1 is the lowest corner (y_A1 < y_A2).  In doubles, each crossing is
  // y_A + (y_B − y_A)/2 with y_B − y_A rounded, which puts A2B1 below A1B1 by 1.1e-16.
  const double ya1 = 0x1.4p-52, ya2 = 0x1.44p-52;
  BOOST_TEST_REQUIRE(ya2 + 0.5 * (1 - ya2) < ya1 + 0.5 * (1 - ya1));  // the rounding this test is about
  const SurfaceMesh tetrahedron =
      mesh_of({{-1, ya1, 0}, {-1, ya2, 0.5}, {1, 1, 0}, {1, 3, 0}}, {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}});
  MeshOracle oracle(tetrahedron, Box3::cube(4));
  const Domain facet = Domain::from_box({{-1, 4}, {-1, 1}});
  const auto critical = oracle.curve_critical({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, facet);
  // The lowest corner A1B1 (y ≈ 0.5, z = 0) is an extremum; A2B1 (y ≈ 0.5, z = 0.25), between
  // A1B1 and A2B2, is not.
  bool lowest = false;
  for (const auto& root : critical.roots) {
    if (root.world[1] > 1) continue;  // A1B2 or A2B2, near y = 1.5
    BOOST_TEST(root.world[2] == 0);
    lowest = true;
  }
  BOOST_TEST(lowest);
  BOOST_TEST(critical.undecided.empty());
}

BOOST_AUTO_TEST_CASE(a_silhouette_edge_inside_a_cell) {
  MeshOracle oracle(octahedron(), Box3::cube(2));
  // In a direction close to z the silhouette is the equator square.
  const Vec3 d = normalized(Vec3{0.01, 0.02, 1}), d2 = normalized(Vec3{1, 0.3, 0.1});
  // A cell holding the edge from (1, 0, 0) to (0, 1, 0) and no other equator vertex: (1, 0, 0) is
  // the highest equator vertex in d2, a critical point of the silhouette.
  const Domain cell = cube_domain({-0.2, -0.2, -0.5}, {1.5, 1.5, 0.5});
  const auto critical = oracle.silhouette_critical(d, d2, cell);
  BOOST_TEST_REQUIRE(critical.roots.size() == 1u);
  BOOST_TEST((critical.roots[0].world == Vec3{1, 0, 0}));
  // The plane x = 0.5 crosses that silhouette edge at (0.5, 0.5, 0).
  const Domain facet = Domain::from_box({{-1, 1}, {-1, 1}});
  const auto crossing = oracle.silhouette_plane({0.5, 0, 0}, {0, 1, 0}, {0, 0, 1}, d, facet);
  BOOST_TEST_REQUIRE(crossing.roots.size() == 2u);  // and the edge to (0, −1, 0) at (0.5, −0.5, 0)
  for (const auto& root : crossing.roots) BOOST_TEST(std::abs(std::abs(root.world[1]) - 0.5) < 1e-15);
  // No silhouette about the top vertex: the gradient cone proves it.
  BOOST_TEST(oracle.prove_gradient_cone(AffineChart::identity(), cube_domain({-0.2, -0.2, 0.8}, {0.2, 0.2, 1.2}), d).proved);
  BOOST_TEST(!oracle.prove_gradient_cone(AffineChart::identity(), cell, d).proved);
  // A plane touching the top vertex: a FacetContact there; a generic plane: none.
  const auto contact = oracle.surface_plane_contact({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, facet);
  BOOST_TEST_REQUIRE(contact.roots.size() == 1u);
  BOOST_TEST((contact.roots[0].world == Vec3{0, 0, 1}));
  BOOST_TEST(oracle.surface_plane_contact({0, 0, 0.3}, {1, 0, 0}, {0, 1, 0}, facet).roots.empty());
  // By name, as the registry orders the parameters.
  const auto frame = orthonormal_frame(d);
  const auto by_name = oracle.solve("surface_critical", {frame.a[0], frame.a[1], frame.a[2], frame.b[0], frame.b[1], frame.b[2]},
                                    box_domain(oracle.box()), 1);
  BOOST_TEST(by_name.roots.size() == 2u);
  BOOST_CHECK_THROW((void)oracle.solve("no_such_primitive", {}, facet, 1), InvalidInput);
}

BOOST_AUTO_TEST_CASE(an_icosphere_remeshed_is_a_sphere_on_the_input) {
  const SurfaceMesh input = test::icosphere(2).to_surface_mesh();
  MeshOracle oracle(input, Box3::cube(1.3));
  DelMeshOptions options;
  options.lambda = 0.06;
  options.threads = 1;
  options.min_spacing = 0.01;
  const DelMeshResult result = del_mesh(oracle, options);
  const MeshReport report = check_mesh(result.mesh);
  BOOST_TEST(report.components == 1u);
  BOOST_TEST_REQUIRE(report.genus_per_component.size() == 1u);
  BOOST_TEST(report.genus_per_component[0] == 0);
  double worst = 0;
  for (const auto& p : result.mesh.points()) worst = std::max(worst, distance_to(input, {p.x(), p.y(), p.z()}));
  BOOST_TEST(worst <= 1e-9 * oracle.diagonal());
  BOOST_TEST(result.statistics["solver"]["backend"] == "mesh");
}
