#include "meshing/core/mesh_checker.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>

#include <unistd.h>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "meshing/inputs/mesh_io.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;
using delmesh::test::Soup;
namespace fs = std::filesystem;

namespace {

const double pi = std::acos(-1.0);

MeshReport check(const Soup& s) { return check_mesh(s.points, s.triangles); }

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_checker_suite)

BOOST_AUTO_TEST_CASE(tetrahedron_is_a_sphere) {
  const MeshReport r = check(test::tetrahedron());
  BOOST_TEST(r.vertices == 4u);
  BOOST_TEST(r.edges == 6u);
  BOOST_TEST(r.triangles == 4u);
  BOOST_TEST(r.components == 1);
  BOOST_TEST(r.euler_characteristic == 2);
  BOOST_TEST(r.genus_per_component == std::vector<int>{0}, boost::test_tools::per_element());
  BOOST_TEST(r.closed);
  BOOST_TEST(r.manifold);
  BOOST_TEST(r.orientable);
  BOOST_TEST(r.oriented);
  BOOST_TEST(r.has_topology({0}));
  BOOST_TEST(!r.has_topology({1}));
  // Regular tetrahedron with edge 2√2: volume (2√2)³/(6√2) = 8/3, outward.
  BOOST_TEST(r.signed_volume == 8.0 / 3.0, boost::test_tools::tolerance(1e-12));
  // Dihedral angle arccos(1/3), so roughness π − arccos(1/3) = arccos(−1/3).
  BOOST_TEST(r.max_roughness_rad == std::acos(-1.0 / 3.0), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.min_angle_deg == 60.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(regular_octahedron_closed_forms) {
  const MeshReport r = check(test::octahedron());
  BOOST_TEST(r.vertices == 6u);
  BOOST_TEST(r.edges == 12u);
  BOOST_TEST(r.triangles == 8u);
  BOOST_TEST(r.euler_characteristic == 2);
  BOOST_TEST(r.has_topology({0}));
  BOOST_TEST(r.oriented);
  BOOST_TEST(r.signed_volume == 4.0 / 3.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.min_angle_deg == 60.0, boost::test_tools::tolerance(1e-12));
  // Equilateral: circumradius a/√3, ratio 1/√3.
  BOOST_TEST(r.max_radius_edge_ratio == 1.0 / std::sqrt(3.0), boost::test_tools::tolerance(1e-12));
  // Dihedral angle arccos(−1/3), roughness π − arccos(−1/3) = arccos(1/3).
  BOOST_TEST(r.max_roughness_rad == std::acos(1.0 / 3.0), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.min_edge_length == std::sqrt(2.0), boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.max_edge_length == std::sqrt(2.0), boost::test_tools::tolerance(1e-12));
}

// The measures do not depend on the scale: an irregular octahedron scaled by 1e200, 1e-300 (whose
// squared lengths overflow or underflow) and 2^-1000 gives the unscaled measures (to rounding;
// exactly for the power of two).
BOOST_AUTO_TEST_CASE(measures_do_not_depend_on_scale) {
  Soup base = test::octahedron();
  // Make it irregular, so every measure is a distinct number.
  base.points[0] = Point3(1.3, 0.1, -0.2);
  base.points[4] = Point3(0.2, -0.1, 0.7);
  const MeshReport unscaled = check(base);
  BOOST_REQUIRE(unscaled.has_topology({0}));
  for (const double scale : {1e200, 1e-300, std::ldexp(1.0, -1000)}) {
    BOOST_TEST_CONTEXT("scale " << scale) {
      Soup s = base;
      for (Point3& p : s.points) p = Point3(p.x() * scale, p.y() * scale, p.z() * scale);
      const MeshReport r = check(s);
      const double tolerance = scale == 1e200 || scale == 1e-300 ? 1e-12 : 0;
      BOOST_TEST(r.has_topology({0}));
      BOOST_TEST(std::abs(r.min_angle_deg - unscaled.min_angle_deg) <= tolerance * 60);
      BOOST_TEST(std::abs(r.max_radius_edge_ratio - unscaled.max_radius_edge_ratio) <= tolerance);
      BOOST_TEST(std::abs(r.max_roughness_rad - unscaled.max_roughness_rad) <= tolerance);
      BOOST_TEST(std::abs(r.min_edge_length / scale - unscaled.min_edge_length) <= tolerance);
      BOOST_TEST(std::abs(r.max_edge_length / scale - unscaled.max_edge_length) <= tolerance);
    }
  }
}

BOOST_AUTO_TEST_CASE(reversed_octahedron_is_oriented_inward) {
  Soup s = test::octahedron();
  for (auto& t : s.triangles) std::swap(t[1], t[2]);
  const MeshReport r = check(s);
  BOOST_TEST(r.oriented);
  BOOST_TEST(r.signed_volume == -4.0 / 3.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.max_roughness_rad == std::acos(1.0 / 3.0), boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(grid_tori_have_genus_one) {
  for (auto [n, m] : {std::pair{3, 3}, std::pair{8, 5}, std::pair{24, 12}}) {
    const MeshReport r = check(test::torus(n, m));
    BOOST_TEST(r.vertices == std::size_t(n * m));
    BOOST_TEST(r.edges == std::size_t(3 * n * m));
    BOOST_TEST(r.triangles == std::size_t(2 * n * m));
    BOOST_TEST(r.components == 1);
    BOOST_TEST(r.euler_characteristic == 0);
    BOOST_TEST(r.has_topology({1}), "torus " << n << "x" << m << ": " << r);
    BOOST_TEST(r.oriented);
  }
  // Volume of the torus R = 2, r = 1 is 2π²Rr² ≈ 39.48; a fine polyhedral one comes close, outward.
  const MeshReport fine = check(test::torus(96, 48));
  BOOST_TEST(fine.signed_volume == 4 * pi * pi, boost::test_tools::tolerance(0.01));
}

BOOST_AUTO_TEST_CASE(two_disjoint_icosahedra) {
  Soup s = test::icosahedron();
  s.append(test::icosahedron().translated(5, 0, 0));
  const MeshReport r = check(s);
  BOOST_TEST(r.vertices == 24u);
  BOOST_TEST(r.components == 2);
  BOOST_TEST(r.euler_characteristic == 4);
  BOOST_TEST(r.has_topology({0, 0}));
  BOOST_TEST(!r.has_topology({0}));
  BOOST_TEST(r.component_reports.size() == 2u);
  for (const ComponentReport& c : r.component_reports) {
    BOOST_TEST(c.euler_characteristic == 2);
    BOOST_TEST(c.triangles == 20u);
  }
  BOOST_TEST(r.signed_volume > 0);
  BOOST_TEST(r.min_angle_deg == 60.0, boost::test_tools::tolerance(1e-9));
  // Icosahedron dihedral angle arccos(−√5/3): roughness arccos(√5/3).
  BOOST_TEST(r.max_roughness_rad == std::acos(std::sqrt(5.0) / 3.0), boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(sphere_and_torus_mixed_genera_sorted) {
  Soup s = test::torus(10, 6);
  s.append(test::octahedron().translated(10, 0, 0));
  s.append(test::torus(7, 4).translated(-10, 0, 0));
  const MeshReport r = check(s);
  BOOST_TEST(r.components == 3);
  BOOST_TEST(r.genus_per_component == (std::vector<int>{0, 1, 1}), boost::test_tools::per_element());
  BOOST_TEST(r.euler_characteristic == 2);
  BOOST_TEST(r.has_topology({1, 0, 1}));
}

BOOST_AUTO_TEST_CASE(mobius_strip_is_non_orientable_with_boundary) {
  const MeshReport r = check(test::mobius_strip(7));
  BOOST_TEST(r.components == 1);
  BOOST_TEST(r.euler_characteristic == 0);
  BOOST_TEST(!r.closed);
  BOOST_TEST(!r.manifold);
  BOOST_TEST(!r.orientable);
  BOOST_TEST(!r.oriented);
  BOOST_TEST(r.boundary_edges == 14u);
  BOOST_TEST(r.nonmanifold_vertices == 0u);  // a surface with boundary: links are paths
  BOOST_TEST(r.genus_per_component == std::vector<int>{-1}, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(klein_bottle_is_closed_manifold_non_orientable) {
  const MeshReport r = check(test::klein_bottle(6, 6));
  BOOST_TEST(r.euler_characteristic == 0);
  BOOST_TEST(r.closed);
  BOOST_TEST(r.manifold);
  BOOST_TEST(!r.orientable);
  BOOST_TEST(r.genus_per_component == std::vector<int>{-1}, boost::test_tools::per_element());
  BOOST_TEST(!r.has_topology({1}));
}

BOOST_AUTO_TEST_CASE(open_disk) {
  const MeshReport r = check(test::open_disk(6));
  BOOST_TEST(r.vertices == 7u);
  BOOST_TEST(r.edges == 12u);
  BOOST_TEST(r.euler_characteristic == 1);
  BOOST_TEST(!r.closed);
  BOOST_TEST(!r.manifold);
  BOOST_TEST(r.orientable);
  BOOST_TEST(r.oriented);
  BOOST_TEST(r.boundary_edges == 6u);
  BOOST_TEST(r.nonmanifold_vertices == 0u);
  BOOST_TEST(r.max_roughness_rad == 0.0, boost::test_tools::tolerance(1e-12));  // planar
  BOOST_TEST(r.min_angle_deg == 60.0, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(bow_tie_is_one_non_manifold_component) {
  const MeshReport r = check(test::bow_tie());
  BOOST_TEST(r.components == 1);  // adjacency through shared vertices
  BOOST_TEST(!r.closed);
  BOOST_TEST(!r.manifold);
  BOOST_TEST(r.nonmanifold_vertices == 1u);
  BOOST_TEST(r.euler_characteristic == 1);  // 5 − 6 + 2
}

BOOST_AUTO_TEST_CASE(two_tetrahedra_pinched_at_a_vertex_are_closed_but_not_manifold) {
  Soup s = test::tetrahedron();
  // A second tetrahedron whose vertex 0 is the first one's vertex 0 (same index), the rest new.
  const Soup second = test::tetrahedron().translated(2, 2, 2);
  for (int k = 1; k < 4; ++k) s.points.push_back(second.points[k]);
  for (auto t : second.triangles) {
    std::array<std::size_t, 3> u{};
    for (int k = 0; k < 3; ++k) u[k] = t[k] == 0 ? 0 : t[k] + 3;
    s.triangles.push_back(u);
  }
  const MeshReport r = check(s);
  BOOST_TEST(r.components == 1);
  BOOST_TEST(r.closed);
  BOOST_TEST(!r.manifold);
  BOOST_TEST(r.nonmanifold_vertices == 1u);
  BOOST_TEST(r.genus_per_component == std::vector<int>{-1}, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(edge_in_three_triangles) {
  Soup s = test::hinge(2.0);
  s.points.push_back(Point3(0.5, 0, -1));
  s.triangles.push_back({0, 1, 4});
  const MeshReport r = check(s);
  BOOST_TEST(r.nonmanifold_edges == 1u);
  BOOST_TEST(!r.orientable);
  BOOST_TEST(!r.oriented);
}

BOOST_AUTO_TEST_CASE(first_defects_are_located) {
  // The open disk: its boundary edges are {1, 2}, {2, 3}, ..., {1, 6}; the smallest is {1, 2}.
  const MeshReport disk = check(test::open_disk(6));
  BOOST_REQUIRE(disk.first_boundary_edge.has_value());
  BOOST_TEST((*disk.first_boundary_edge == std::array<std::size_t, 2>{1, 2}));
  BOOST_TEST(!disk.first_nonmanifold_edge.has_value());
  BOOST_TEST(!disk.first_misoriented_edge.has_value());
  // The bow-tie is pinched at vertex 0.
  BOOST_TEST((check(test::bow_tie()).first_nonmanifold_vertex == std::optional<std::size_t>(0)));
  // The flipped hinge traverses its shared edge {0, 1} twice the same way.
  const MeshReport hinge = check(test::hinge(2.0, true));
  BOOST_TEST(hinge.misoriented_edges == 1u);
  BOOST_TEST((hinge.first_misoriented_edge == std::optional<std::array<std::size_t, 2>>({0, 1})));
  // A third triangle on the hinge's edge {0, 1}.
  Soup three = test::hinge(2.0);
  three.points.push_back(Point3(0.5, 0, -1));
  three.triangles.push_back({0, 1, 4});
  BOOST_TEST((check(three).first_nonmanifold_edge == std::optional<std::array<std::size_t, 2>>({0, 1})));
  // A closed manifold has none of them.
  const MeshReport sphere = check(test::icosahedron());
  BOOST_TEST(!sphere.first_boundary_edge.has_value());
  BOOST_TEST(!sphere.first_nonmanifold_vertex.has_value());
  BOOST_TEST(sphere.misoriented_edges == 0u);
}

BOOST_AUTO_TEST_CASE(hinge_roughness_closed_form) {
  for (double phi : {pi, 0.9 * pi, 2.0, pi / 2, 0.3}) {
    for (bool flip : {false, true}) {
      const MeshReport r = check(test::hinge(phi, flip));
      // Roughness is π minus the internal dihedral angle, whatever the given orientation.
      BOOST_TEST(r.max_roughness_rad == pi - phi, boost::test_tools::tolerance(1e-12));
      BOOST_TEST(r.min_angle_deg == 60.0, boost::test_tools::tolerance(1e-12));
      BOOST_TEST(r.max_radius_edge_ratio == 1.0 / std::sqrt(3.0), boost::test_tools::tolerance(1e-12));
      BOOST_TEST(r.oriented == !flip);
      BOOST_TEST(r.orientable);
      BOOST_TEST(r.boundary_edges == 4u);
    }
  }
}

BOOST_AUTO_TEST_CASE(right_and_degenerate_triangles) {
  const std::vector<Point3> pts{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(2, 0, 0)};
  const MeshReport right = check_mesh(pts, {{0, 1, 2}});
  BOOST_TEST(right.min_angle_deg == 45.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(right.max_radius_edge_ratio == std::sqrt(2.0) / 2, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(right.unreferenced_vertices == 1u);
  BOOST_TEST(right.vertices == 3u);
  const MeshReport flat = check_mesh(pts, {{0, 1, 3}});
  BOOST_TEST(flat.min_angle_deg == 0.0);
  BOOST_TEST(flat.max_radius_edge_ratio == std::numeric_limits<double>::infinity());
  BOOST_TEST(to_json(flat)["max_radius_edge_ratio"].is_null());
}

BOOST_AUTO_TEST_CASE(invalid_soups_throw) {
  const std::vector<Point3> pts{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0)};
  BOOST_CHECK_THROW(check_mesh(pts, {{0, 1, 3}}), InvalidInput);
  BOOST_CHECK_THROW(check_mesh(pts, {{0, 1, 1}}), InvalidInput);
  std::vector<Point3> nan_pts = pts;
  nan_pts[2] = Point3(0, std::nan(""), 0);
  BOOST_CHECK_THROW(check_mesh(nan_pts, {{0, 1, 2}}), InvalidInput);
  // A non-finite point nobody uses is only counted.
  nan_pts.push_back(Point3(0, 0, 1));
  BOOST_CHECK_THROW(check_mesh(nan_pts, {{0, 1, 2}}), InvalidInput);
  BOOST_CHECK_NO_THROW(check_mesh(nan_pts, {{0, 1, 3}}));
}

BOOST_AUTO_TEST_CASE(empty_mesh) {
  const MeshReport r = check_mesh({}, {});
  BOOST_TEST(r.components == 0);
  BOOST_TEST(r.euler_characteristic == 0);
  BOOST_TEST(!r.closed);
  BOOST_TEST(!r.has_topology({}));
}

BOOST_AUTO_TEST_CASE(surface_mesh_overload_agrees_with_soup) {
  const Soup s = test::torus(9, 7);
  SurfaceMesh mesh = s.to_surface_mesh();
  const MeshReport a = check(s);
  const MeshReport b = check_mesh(mesh);
  BOOST_TEST(to_json(a).dump() == to_json(b).dump());
  // Removed (garbage) vertices and faces are skipped.
  SurfaceMesh with_garbage = test::octahedron().to_surface_mesh();
  const auto extra = with_garbage.add_vertex(Point3(9, 9, 9));
  with_garbage.remove_vertex(extra);
  BOOST_TEST(check_mesh(with_garbage).has_topology({0}));
  // A quad face is not a triangle mesh.
  SurfaceMesh quad;
  auto v0 = quad.add_vertex(Point3(0, 0, 0)), v1 = quad.add_vertex(Point3(1, 0, 0));
  auto v2 = quad.add_vertex(Point3(1, 1, 0)), v3 = quad.add_vertex(Point3(0, 1, 0));
  quad.add_face(v0, v1, v2, v3);
  BOOST_CHECK_THROW(check_mesh(quad), InvalidInput);
}

// Boundary loops are counted per component; the genus is undefined (null in JSON) on components
// that are not closed orientable 2-manifolds.
BOOST_AUTO_TEST_CASE(boundary_loops_and_undefined_genus) {
  const MeshReport strip = check(test::mobius_strip(7));
  BOOST_TEST(strip.boundary_loops == 1u);  // a Möbius strip has one boundary circle
  const MeshReport disk = check(test::open_disk(6));
  BOOST_TEST(disk.boundary_loops == 1u);
  // A square annulus beside a tetrahedron: two loops in one component, none in the other.
  Soup s = test::tetrahedron();
  const std::size_t o = s.points.size();
  for (const auto& p : {Point3(-2, -2, 5), Point3(2, -2, 5), Point3(2, 2, 5), Point3(-2, 2, 5), Point3(-1, -1, 5),
                        Point3(1, -1, 5), Point3(1, 1, 5), Point3(-1, 1, 5)})
    s.points.push_back(p);
  for (int i = 0; i < 4; ++i) {
    const std::size_t a = o + i, b = o + (i + 1) % 4, c = o + 4 + i, d = o + 4 + (i + 1) % 4;
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({b, d, c});
  }
  const MeshReport r = check(s);
  BOOST_TEST(r.components == 2);
  BOOST_TEST(r.boundary_loops == 2u);
  BOOST_TEST(r.boundary_edges == 8u);
  BOOST_TEST(r.genus_per_component == (std::vector<int>{-1, 0}), boost::test_tools::per_element());
  BOOST_TEST(r.component_reports[0].boundary_loops == 2u);
  BOOST_TEST(r.component_reports[0].boundary_edges == 8u);
  BOOST_TEST(r.component_reports[1].boundary_loops == 0u);
  const nlohmann::json j = to_json(r);
  BOOST_TEST(j["genus_per_component"] == nlohmann::json::parse("[null, 0]"));
  BOOST_TEST(j["component_reports"][0]["genus"].is_null());
  BOOST_TEST(j["component_reports"][0]["boundary_loops"] == 2);
  BOOST_TEST(j["boundary_loops"] == 2);
  // Two triangles sharing only a vertex: one component (vertex adjacency), one pinched vertex,
  // one boundary piece through it.
  const std::vector<Point3> bow{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(-1, 0, 0), Point3(0, -1, 0)};
  const MeshReport b = check_mesh(bow, {{0, 1, 2}, {0, 3, 4}});
  BOOST_TEST(b.nonmanifold_vertices == 1u);
  BOOST_TEST(b.boundary_loops == 1u);
  BOOST_TEST(b.component_reports[0].nonmanifold_vertices == 1u);
}

BOOST_AUTO_TEST_CASE(json_has_the_contract_keys) {
  const nlohmann::json j = to_json(check(test::torus(5, 4)));
  for (const char* key : {"vertices", "triangles", "components", "euler_characteristic", "genus_per_component",
                          "closed_manifold", "orientable", "min_angle_deg", "max_radius_edge_ratio",
                          "max_roughness_rad"}) {
    BOOST_TEST(j.contains(key), key);
  }
  BOOST_TEST(j["genus_per_component"] == nlohmann::json::array({1}));
  BOOST_TEST(j["closed_manifold"] == true);
}

//! CGAL's sample meshes (package libcgal-demo): genus verified by the checker.  Skipped with a
//! message when the tarball is not installed.
BOOST_AUTO_TEST_CASE(cgal_data_meshes) {
  const fs::path tarball = "/usr/share/doc/libcgal-dev/data.tar.gz";
  if (!fs::exists(tarball)) {
    BOOST_TEST_MESSAGE("skipped: " << tarball << " not found (install libcgal-demo)");
    return;
  }
  const fs::path dir = fs::temp_directory_path() / ("delmesh_cgal_data_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // Expected χ computed independently (V − E + F of the file); genus −1: not a closed surface.
  const struct {
    const char* file;
    int euler;
    std::vector<int> genera;
  } cases[] = {{"sphere.off", 2, {0}},        {"eight.off", -2, {2}},
               {"knot.off", 0, {1}},          {"couplingdown.off", -16, {9}},
               {"blobby_3cc.off", 2, {-1, -1, -1}}, {"cube-ouvert.off", 1, {-1}}};
  std::string members;
  for (const auto& c : cases) members += std::string(" data/meshes/") + c.file;
  const std::string command =
      "tar -xzf " + tarball.string() + " -C " + dir.string() + members + " 2>/dev/null";
  BOOST_REQUIRE_MESSAGE(std::system(command.c_str()) == 0, "extracting from " << tarball);
  for (const auto& c : cases) {
    const TriangleSoup soup = read_triangle_soup((dir / "data/meshes" / c.file).string());
    const MeshReport r = check_mesh(soup.points, soup.triangles);
    BOOST_TEST(r.euler_characteristic == c.euler, c.file);
    BOOST_TEST(r.genus_per_component == c.genera, c.file << ": " << r << boost::test_tools::per_element());
    const bool closed_surface = c.genera.front() >= 0;
    BOOST_TEST(r.closed == closed_surface, c.file);
    if (closed_surface) BOOST_TEST(r.has_topology(c.genera), c.file << ": " << r);
  }
  fs::remove_all(dir);
}

BOOST_AUTO_TEST_SUITE_END()
