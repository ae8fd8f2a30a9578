#include "meshing/inputs/self_intersection_repair.h"

#include <cmath>
#include <string>

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "tests/meshing/feature_meshes.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;

namespace {

using Polygons = std::vector<std::vector<std::size_t>>;

test::Soup box(double x0, double x1, double y0, double y1, double z0, double z1) {
  test::Soup s = test::grid_cube(1);
  for (Point3& p : s.points)
    p = Point3(x0 + p.x() * (x1 - x0), y0 + p.y() * (y1 - y0), z0 + p.z() * (z1 - z0));
  return s;
}

Polygons polygons_of(const test::Soup& s) {
  Polygons out;
  for (const auto& t : s.triangles) out.push_back({t[0], t[1], t[2]});
  return out;
}

// The cube [0, 2]³ and the bar [1, 3] × [0.5, 1.5]² through its face x = 2, as one mesh: two
// closed components whose faces cross (no faces coplanar).
test::Soup overlapping_boxes() {
  test::Soup s = box(0, 2, 0, 2, 0, 2);
  s.append(box(1, 3, 0.5, 1.5, 0.5, 1.5));
  return s;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(self_intersection_repair_suite)

BOOST_AUTO_TEST_CASE(overlapping_boxes_are_refused_without_repair_and_united_with_it) {
  const test::Soup soup = overlapping_boxes();
  try {
    (void)validate_input_mesh(soup.points, polygons_of(soup), "boxes.off");
    BOOST_FAIL("the overlapping boxes were accepted");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("the surface intersects itself") != std::string::npos, e.what());
  }
  const RepairedInput repaired = repair_input_mesh(soup.points, polygons_of(soup), "boxes.off");
  const RepairReport& r = repaired.report;
  BOOST_TEST(r.method == "autorefine");
  BOOST_TEST(r.changed());
  BOOST_TEST(r.intersecting_pairs > 0u);
  BOOST_TEST(r.faces_before == 24u);
  BOOST_TEST(r.vertices_before == 16u);
  BOOST_TEST(r.faces_after == repaired.input.mesh.number_of_faces());
  BOOST_TEST(r.vertices_after == repaired.input.mesh.number_of_vertices());
  // The union: one closed component of genus 0 and volume 8 + 1, without self-intersections.
  const SurfaceMesh& mesh = repaired.input.mesh;
  BOOST_TEST(repaired.input.report.components == 1u);
  BOOST_TEST(repaired.input.report.genus_per_component == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST(!CGAL::Polygon_mesh_processing::does_self_intersect(mesh));
  BOOST_TEST(std::abs(CGAL::Polygon_mesh_processing::volume(mesh) - 9.0) < 1e-12);
  const std::string line = r.summary("boxes.off");
  BOOST_TEST(line.find("boxes.off: ") == 0u, line);
  BOOST_TEST(line.find("removed by autorefinement") != std::string::npos, line);
  BOOST_TEST(line.find('\n') == std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_valid_mesh_is_left_as_it_is) {
  const test::Soup cube = box(0, 1, 0, 1, 0, 1);
  const RepairedInput repaired = repair_input_mesh(cube.points, polygons_of(cube), "cube.off");
  BOOST_TEST(repaired.report.method == "none");
  BOOST_TEST(!repaired.report.changed());
  BOOST_TEST(repaired.report.intersecting_pairs == 0u);
  BOOST_TEST(repaired.report.faces_after == 12u);
  const InputMesh plain = validate_input_mesh(cube.points, polygons_of(cube), "cube.off");
  BOOST_TEST(repaired.input.mesh.number_of_faces() == plain.mesh.number_of_faces());
  for (auto v : plain.mesh.vertices()) BOOST_TEST(repaired.input.mesh.point(v) == plain.mesh.point(v));
  BOOST_TEST(repaired.report.summary("cube.off") == "cube.off: no self-intersections, nothing to repair");
}

BOOST_AUTO_TEST_CASE(other_defects_keep_their_own_message) {
  // An open mesh that also intersects itself: the boxes without one triangle.  Repair does not
  // close holes: the refusal is validation's "not closed".
  test::Soup open = overlapping_boxes();
  open.triangles.pop_back();
  try {
    (void)repair_input_mesh(open.points, polygons_of(open), "open.off");
    BOOST_FAIL("an open mesh was repaired");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("input mesh 'open.off': not closed") == 0u, e.what());
  }
}

BOOST_AUTO_TEST_CASE(cgal_meshes_that_intersect_themselves) {
  // bull: autorefinement fixes its 3 pairs; diplodocus: autorefinement crashes (in its child
  // process) and local removal fixes it; cow: autorefinement splits it, local removal fails, so
  // it is refused with both reasons.
  test::TempDir dir;
  const RepairedInput bull = read_and_repair_input_mesh(test::cgal_data_mesh("bull", dir));
  BOOST_TEST(bull.report.method == "autorefine");
  BOOST_TEST(bull.report.intersecting_pairs == 3u);
  BOOST_TEST(!CGAL::Polygon_mesh_processing::does_self_intersect(bull.input.mesh));
  const RepairedInput diplodocus = read_and_repair_input_mesh(test::cgal_data_mesh("diplodocus", dir));
  BOOST_TEST(diplodocus.report.method == "local");
  BOOST_TEST(diplodocus.report.intersecting_pairs == 116u);
  BOOST_TEST(!CGAL::Polygon_mesh_processing::does_self_intersect(diplodocus.input.mesh));
  try {
    (void)read_and_repair_input_mesh(test::cgal_data_mesh("cow", dir));
    BOOST_FAIL("cow was repaired");
  } catch (const InvalidInput& e) {
    const std::string why = e.what();
    BOOST_TEST(why.find("--repair could not remove the self-intersections: 101 pairs of triangles intersect; "
                        "autorefinement split the mesh into 2 components") != std::string::npos, why);
    BOOST_TEST(why.find('\n') == std::string::npos);
  }
}

BOOST_AUTO_TEST_SUITE_END()
