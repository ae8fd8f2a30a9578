#include "meshing/inputs/input_mesh.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/inputs/mesh_io.h"
#include "tests/meshing/known_meshes.h"
#include "tests/temp_dir.h"

using namespace delmesh;
namespace fs = std::filesystem;

namespace {

using test::TempDir;

//! Writes the soup into dir as name (format by extension) and returns its path.
std::string write_soup(const TempDir& dir, const std::string& name, const test::Soup& soup) {
  const std::string file = dir.file(name);
  write_triangle_soup({soup.points, soup.triangles}, file);
  return file;
}

std::vector<std::vector<std::size_t>> polygons_of(const test::Soup& soup) {
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
  return polygons;
}

//! The message of the InvalidInput that validating the soup throws ("" if none is thrown).
std::string refusal(const test::Soup& soup) {
  try {
    (void)validate_input_mesh(soup.points, polygons_of(soup), "m.off");
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

test::Soup reversed(test::Soup soup) {
  for (auto& t : soup.triangles) std::swap(t[1], t[2]);
  return soup;
}

//! The tetrahedron moved by dx along the x axis.
test::Soup tetrahedron_at(double dx) { return test::tetrahedron().translated(dx, 0, 0); }

}  // namespace

BOOST_AUTO_TEST_SUITE(input_mesh_suite)

BOOST_AUTO_TEST_CASE(octahedron_file_gives_box_median_and_counts) {
  TempDir dir;
  const InputMesh input = read_input_mesh(write_soup(dir, "octahedron.off", test::octahedron()));
  BOOST_TEST(input.report.vertices == 6u);
  BOOST_TEST(input.report.triangles == 8u);
  BOOST_TEST(input.report.components == 1);
  BOOST_TEST(input.report.genus_per_component == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST(input.report.oriented);
  BOOST_TEST(!input.reoriented());
  BOOST_TEST(input.faces_read == 8u);
  BOOST_TEST(input.polygons_triangulated == 0u);
  // Every edge of the octahedron has length √2; its bounding box is [−1, 1]³.
  BOOST_TEST(input.median_edge_length == std::sqrt(2.0), boost::test_tools::tolerance(1e-15));
  BOOST_TEST(input.bounding_box_diagonal == 2 * std::sqrt(3.0), boost::test_tools::tolerance(1e-15));
  const double margin = tolerances::input_mesh_box_margin * 2 * std::sqrt(3.0);
  for (int i = 0; i < 3; ++i) {
    BOOST_TEST(input.box.lo[i] == -1 - margin, boost::test_tools::tolerance(1e-15));
    BOOST_TEST(input.box.hi[i] == 1 + margin, boost::test_tools::tolerance(1e-15));
  }
  BOOST_TEST(input.report.signed_volume == 4.0 / 3.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(inward_mesh_is_reoriented_outward) {
  TempDir dir;
  const InputMesh input = read_input_mesh(write_soup(dir, "inward.obj", reversed(test::octahedron())));
  BOOST_TEST(input.components_reversed == 1u);
  BOOST_TEST(input.reoriented());
  BOOST_TEST(input.report.signed_volume == 4.0 / 3.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(nested_components_bound_a_volume) {
  // An outward octahedron inside a larger outward one: the inner one bounds a cavity, so it is
  // turned inward; the volume bounded is that of the shell, (8 − 1)·4/3.
  test::Soup shell = test::octahedron();
  for (Point3& p : shell.points) p = Point3(2 * p.x(), 2 * p.y(), 2 * p.z());
  shell.append(test::octahedron());
  const InputMesh input = validate_input_mesh(shell.points, polygons_of(shell), "nested");
  BOOST_TEST(input.components_reversed == 1u);
  BOOST_TEST(input.report.components == 2);
  BOOST_TEST(input.report.signed_volume == 7 * 4.0 / 3.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(empty_mesh_is_refused) {
  const std::string why = refusal(test::Soup{});
  BOOST_TEST(contains(why, "input mesh 'm.off': the mesh is empty"), why);
  // A file without faces: the reader's message.
  TempDir dir;
  const std::string file = (dir.path / "empty.off").string();
  { std::ofstream(file) << "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"; }
  BOOST_CHECK_THROW((void)read_input_mesh(file), InvalidInput);
}

// Coordinates around 1e154 are finite, but the orientation tests' triple products overflow: the mesh
// is refused with the vertex named, while 1e99 is accepted.
BOOST_AUTO_TEST_CASE(huge_coordinates_are_refused) {
  test::Soup huge = test::tetrahedron();
  for (Point3& p : huge.points) p = Point3(p.x() * 1e154, p.y() * 1e154, p.z() * 1e154);
  const std::string why = refusal(huge);
  BOOST_TEST(contains(why, "input mesh 'm.off': vertex 0 ("), why);
  BOOST_TEST(contains(why, "has a coordinate too large: above 1e100"), why);
  test::Soup large = test::tetrahedron();
  for (Point3& p : large.points) p = Point3(p.x() * 1e99 / 2, p.y() * 1e99 / 2, p.z() * 1e99 / 2);
  BOOST_TEST(refusal(large).empty());
  BOOST_TEST(tolerances::input_mesh_max_coordinate == 1e100);  // the message's figure
}

BOOST_AUTO_TEST_CASE(open_mesh_names_a_boundary_edge) {
  test::Soup open = test::octahedron();
  open.triangles.pop_back();
  const std::string why = refusal(open);
  BOOST_TEST(contains(why, "not closed: 3 boundary edges in 1 loop, e.g. the edge from vertex "), why);
  BOOST_TEST(contains(why, "lies in one face only"), why);
}

BOOST_AUTO_TEST_CASE(non_manifold_edge_is_refused) {
  // Two tetrahedra glued along the edge {0, 1}: it lies in four faces.
  test::Soup two = test::tetrahedron();
  two.points.push_back(Point3(3, 0, 0));
  two.points.push_back(Point3(3, 1, 0));
  const std::size_t a = 4, b = 5;
  two.triangles.push_back({0, 1, a});
  two.triangles.push_back({0, a, b});
  two.triangles.push_back({0, b, 1});
  two.triangles.push_back({1, b, a});
  const std::string why = refusal(two);
  BOOST_TEST(contains(why, "not a manifold: 1 edge lies in three or more faces, e.g. the edge from vertex 0 (1, 1, 1) "
                           "to vertex 1 (1, -1, -1)"),
             why);
}

BOOST_AUTO_TEST_CASE(pinched_vertex_is_refused) {
  // Two tetrahedra sharing the vertex 0 only.
  test::Soup two = test::tetrahedron();
  test::Soup other = tetrahedron_at(2);
  other.points[0] = two.points[0];
  two.append(other);
  // Identify the second copy's vertex 0 (index 4) with vertex 0.
  for (auto& t : two.triangles)
    for (auto& v : t)
      if (v == 4) v = 0;
  const std::string why = refusal(two);
  BOOST_TEST(contains(why, "not a manifold: 1 vertex is shared by separate fans of faces, e.g. vertex 0 (1, 1, 1)"),
             why);
}

BOOST_AUTO_TEST_CASE(inconsistent_orientation_is_refused) {
  test::Soup soup = test::octahedron();
  std::swap(soup.triangles[3][1], soup.triangles[3][2]);
  const std::string why = refusal(soup);
  BOOST_TEST(contains(why, "the faces are not consistently oriented: 3 edges are traversed in the same direction"),
             why);
}

BOOST_AUTO_TEST_CASE(non_orientable_surface_is_refused) {
  const std::string why = refusal(test::klein_bottle(6, 6));
  BOOST_TEST(contains(why, "the surface is not orientable"), why);
}

BOOST_AUTO_TEST_CASE(degenerate_triangle_is_refused) {
  // The tetrahedron with its face (0, 1, 2) replaced by (0, m, 2), (m, 1, 2) and the collinear
  // (0, 1, m) closing the edge {0, 1} of the face (0, 3, 1): m is the midpoint of 0 and 1.
  test::Soup soup = test::tetrahedron();
  soup.points.push_back(Point3(1, 0, 0));
  soup.triangles[0] = {0, 4, 2};
  soup.triangles.push_back({4, 1, 2});
  soup.triangles.push_back({0, 1, 4});
  const std::string why = refusal(soup);
  BOOST_TEST(contains(why, "a triangle is degenerate (its vertices are collinear)"), why);
}

BOOST_AUTO_TEST_CASE(self_intersection_is_refused) {
  // Two tetrahedra that overlap without sharing a vertex.
  test::Soup two = test::tetrahedron();
  two.append(tetrahedron_at(0.5));
  const std::string why = refusal(two);
  BOOST_TEST(contains(why, "the surface intersects itself, e.g. the triangle of vertex "), why);
}

BOOST_AUTO_TEST_CASE(polygons_are_triangulated) {
  // The cube as six quadrilaterals, and the L-shaped prism whose top and bottom are non-convex
  // hexagons listed from a convex corner (a fan from there would leave the polygon).
  const std::vector<Point3> cube = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 1, 0), Point3(0, 1, 0),
                                    Point3(0, 0, 1), Point3(1, 0, 1), Point3(1, 1, 1), Point3(0, 1, 1)};
  const std::vector<std::vector<std::size_t>> quads = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                       {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const InputMesh box = validate_input_mesh(cube, quads, "cube");
  BOOST_TEST(box.polygons_triangulated == 6u);
  BOOST_TEST(box.report.triangles == 12u);
  BOOST_TEST(box.report.vertices == 8u);
  BOOST_TEST(box.report.genus_per_component == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST(box.report.signed_volume == 1.0, boost::test_tools::tolerance(1e-14));

  // L = [0,2]×[0,1] ∪ [0,1]×[0,2]; bottom ring 0..5 at z = 0, top ring 6..11 at z = 1.
  const double l[6][2] = {{2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}};
  std::vector<Point3> points;
  for (double z : {0.0, 1.0})
    for (const auto& c : l) points.emplace_back(c[0], c[1], z);
  std::vector<std::vector<std::size_t>> faces = {{0, 5, 4, 3, 2, 1}, {6, 7, 8, 9, 10, 11}};
  for (std::size_t i = 0; i < 6; ++i) faces.push_back({i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i});
  const InputMesh prism = validate_input_mesh(points, faces, "prism");
  BOOST_TEST(prism.polygons_triangulated == 8u);
  BOOST_TEST(prism.report.triangles == 2u * 4 + 6u * 2);
  BOOST_TEST(prism.report.genus_per_component == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST(prism.report.signed_volume == 3.0, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(polygon_files_are_triangulated) {
  // The cube of six quadrilaterals as a file: read_input_mesh takes the polygons as they are.
  TempDir dir;
  const std::string path = dir.write("cube.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                                 "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n");
  const InputMesh cube = read_input_mesh(path);
  BOOST_TEST(cube.faces_read == 6u);
  BOOST_TEST(cube.polygons_triangulated == 6u);
  BOOST_TEST(cube.report.triangles == 12u);
  BOOST_TEST(cube.report.genus_per_component == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST(cube.report.signed_volume == 1.0, boost::test_tools::tolerance(1e-14));
}

BOOST_AUTO_TEST_CASE(unreferenced_points_are_dropped) {
  test::Soup soup = test::tetrahedron();
  soup.points.insert(soup.points.begin(), Point3(100, 100, 100));
  for (auto& t : soup.triangles)
    for (auto& v : t) ++v;
  const InputMesh input = validate_input_mesh(soup.points, polygons_of(soup), "t");
  BOOST_TEST(input.unreferenced_vertices == 1u);
  BOOST_TEST(input.report.vertices == 4u);
  BOOST_TEST(input.bounding_box_diagonal == 2 * std::sqrt(3.0), boost::test_tools::tolerance(1e-15));
  // The vertices keep the file's order.
  BOOST_TEST(input.mesh.point(SurfaceMesh::Vertex_index(0)) == Point3(1, 1, 1));
}

BOOST_AUTO_TEST_CASE(real_mesh_eight_has_genus_two) {
  // eight.off of CGAL's data (libcgal-demo, scripts/install-deps.sh): a closed genus-2 surface.
  const std::string archive = "/usr/share/doc/libcgal-dev/data.tar.gz";
  BOOST_REQUIRE_MESSAGE(fs::exists(archive), archive + " is missing (install libcgal-demo)");
  TempDir dir;
  const std::string command =
      "tar -xzf " + archive + " -C '" + dir.path.string() + "' data/meshes/eight.off";
  BOOST_REQUIRE(std::system(command.c_str()) == 0);
  const InputMesh input = read_input_mesh((dir.path / "data/meshes/eight.off").string());
  BOOST_TEST(input.report.vertices == 315u);
  BOOST_TEST(input.report.triangles == 634u);
  BOOST_TEST(input.report.genus_per_component == std::vector<int>{2}, boost::test_tools::per_element());
  BOOST_TEST(input.report.oriented);
  BOOST_TEST(input.report.signed_volume > 0);
  BOOST_TEST(input.median_edge_length > 0);
  BOOST_TEST(input.median_edge_length < input.bounding_box_diagonal);
}

// An octahedron 32 across at 2^54 from the origin lies on a lattice of 4 (its coordinates' unit in
// the last place), 14 units across: refused with the reason and the remedy.  At 2^30 the same
// octahedron spans about 2^27 units and is accepted.
BOOST_AUTO_TEST_CASE(a_coarse_lattice_far_from_the_origin_is_refused) {
  for (const double offset : {std::ldexp(1.0, 54), std::ldexp(1.0, 30)}) {
    BOOST_TEST_CONTEXT("offset " << offset) {
      const test::Soup unit = test::octahedron();
      std::vector<Point3> points;
      for (const Point3& p : unit.points) points.emplace_back(offset + 16 * p.x(), offset + 16 * p.y(), offset + 16 * p.z());
      std::vector<std::vector<std::size_t>> polygons;
      for (const auto& t : unit.triangles) polygons.push_back({t[0], t[1], t[2]});
      if (offset > std::ldexp(1.0, 40)) {
        try {
          (void)validate_input_mesh(points, polygons, "far.off");
          BOOST_ERROR("a mesh 14 units in the last place across was accepted");
        } catch (const InvalidInput& e) {
          BOOST_TEST(std::string(e.what()).find("too far from the origin for its size") != std::string::npos, e.what());
          BOOST_TEST(std::string(e.what()).find("translate it towards the origin") != std::string::npos, e.what());
        }
      } else {
        BOOST_TEST(validate_input_mesh(points, polygons, "far.off").bounding_box_diagonal > 55);
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
