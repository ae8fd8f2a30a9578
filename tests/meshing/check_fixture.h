#pragma once
// A hand-built sample set on a given surface, for the tests of the checks of §5.3; and the
// assertions every test of a DelMesh output makes on that output.
#include <array>
#include <cstddef>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/core/mesh_checker.h"
#include "meshing/core/surface_mesh.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/implicit_oracle.h"
#include "meshing/voronoi/restricted_delaunay.h"
#include "symbolic/catalog.h"

namespace delmesh::test {

struct CheckFixture {
  Box3 box;
  ImplicitOracle oracle;
  Delaunay del;
  RestrictedDelaunay restricted;
  CheckFixture(const std::string& equation, double half_width, const std::vector<Vec3>& points)
      : box(Box3::cube(half_width)),
        oracle(Surface::parse(equation), box, SolverBackend::subdivision),
        restricted(del, oracle, 1) {
    for (const auto& p : points) del.insert(p, false);
  }
};

inline const char* unit_sphere = "x^2+y^2+z^2-1";

//! The signed volume Σ det(a, b, c)/6 of each connected component of a triangle soup, where two
//! triangles are connected iff they share a vertex (the components of mesh_checker.h), ordered
//! by each component's first triangle.  For a closed component it does not depend on the origin
//! and is the enclosed volume if the triangles face away from it, minus that volume otherwise.
inline std::vector<double> component_signed_volumes(const std::vector<Point3>& points,
                                                    const std::vector<std::array<std::size_t, 3>>& triangles) {
  std::vector<std::size_t> parent(points.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& t : triangles) {
    parent[find(t[1])] = find(t[0]);
    parent[find(t[2])] = find(t[0]);
  }
  std::vector<std::size_t> slot(points.size(), triangles.size());  // root → index into volumes
  std::vector<double> volumes;
  for (const auto& t : triangles) {
    const std::size_t root = find(t[0]);
    if (slot[root] == triangles.size()) {
      slot[root] = volumes.size();
      volumes.push_back(0);
    }
    const Vector3 a = points[t[0]] - CGAL::ORIGIN, b = points[t[1]] - CGAL::ORIGIN, c = points[t[2]] - CGAL::ORIGIN;
    volumes[slot[root]] += CGAL::scalar_product(a, CGAL::cross_product(b, c)) / 6;
  }
  return volumes;
}

inline std::vector<double> component_signed_volumes(const SurfaceMesh& mesh) {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  mesh_to_soup(mesh, points, triangles);
  return component_signed_volumes(points, triangles);
}

//! Asserts that the statistics report a fully certified run: status "complete", every answer of
//! the oracle certified, and nothing left unsettled (no unsettled region, no defect of the output).
inline void check_complete(const nlohmann::json& statistics) {
  BOOST_TEST(statistics.at("status").get<std::string>() == "complete");
  BOOST_TEST(statistics.at("solver_certified").get<bool>());
  const auto& unsettled = statistics.at("unsettled");
  BOOST_TEST(unsettled.at("count").get<std::size_t>() == 0u, unsettled.dump());
  BOOST_TEST(unsettled.at("output_defects").empty(), unsettled.dump());
}

//! Asserts what the statistics and the mesh of a complete DelMesh run on a catalog surface must
//! say: every triangle of Tri S|Σ is in the mesh (faces_not_added = 0), no two triangles traverse
//! an edge in the same direction (orientation_inconsistent_edges = 0), the mesh has the reported
//! number of components, and each component faces outward.
//!
//! Outward: del_mesh orients each triangle along ∇E at its dual point, towards E > 0.  Every
//! catalog surface has E < 0 inside and E > 0 outside, and none of its components lies inside
//! another, so each component bounds a region of {E < 0} on its inner side and its signed volume
//! is that region's volume: positive.  (A component bounding a cavity {E > 0} inside a solid
//! would have a negative one; the catalog has no such surface.)
inline void check_oriented_output(const nlohmann::json& statistics, const std::vector<Point3>& points,
                                  const std::vector<std::array<std::size_t, 3>>& triangles) {
  BOOST_TEST(statistics.at("faces_not_added").get<std::size_t>() == 0u);
  BOOST_TEST(statistics.at("orientation_inconsistent_edges").get<std::size_t>() == 0u);
  const auto volumes = component_signed_volumes(points, triangles);
  BOOST_TEST(volumes.size() == statistics.at("components").get<std::size_t>());
  BOOST_TEST(!volumes.empty());
  for (std::size_t i = 0; i < volumes.size(); ++i)
    BOOST_TEST(volumes[i] > 0, "component " << i << " has signed volume " << volumes[i]);
}

inline void check_oriented_output(const nlohmann::json& statistics, const SurfaceMesh& mesh) {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  mesh_to_soup(mesh, points, triangles);
  check_oriented_output(statistics, points, triangles);
}

//! Theorem 6.1 on a DelMesh run of a catalog surface at λ ≤ 0.06, checked on the output by the
//! independent checker: a certified, outward-oriented closed manifold with the catalog's
//! components and genera, and the angle, radius-edge and roughness bounds.
inline void check_theorem_6_1(const CatalogEntry& entry, const DelMeshResult& result, double lambda) {
  check_complete(result.statistics);
  check_oriented_output(result.statistics, result.mesh);
  const auto r = check_mesh(result.mesh);
  const auto b = theorem_bounds(lambda);
  BOOST_TEST_MESSAGE(entry.name << " lambda " << lambda << ": " << r.vertices << " vertices, min angle "
                                << r.min_angle_deg << ", rho " << r.max_radius_edge_ratio << ", roughness "
                                << r.max_roughness_rad);
  BOOST_TEST(r.closed);
  BOOST_TEST(r.manifold);
  BOOST_TEST(r.orientable);
  BOOST_TEST(r.components == entry.components);
  BOOST_TEST(r.genus_per_component == entry.genus_per_component, boost::test_tools::per_element());
  BOOST_TEST(r.min_angle_deg >= b.min_angle_deg - 1e-9);
  BOOST_TEST(r.max_radius_edge_ratio <= b.max_radius_edge_ratio + 1e-9);
  BOOST_TEST(r.max_roughness_rad <= b.max_roughness_rad + 1e-9);
}

}  // namespace delmesh::test
