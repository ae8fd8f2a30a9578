// Remeshing at unit scale (meshing/inputs/unit_scale.h): the exponent, the exact conversions in and out,
// and MeshOracle on meshes of size 1e-100 and 1e80 answering as on the unit-size mesh.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>

#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/driver/scaled_run.h"
#include "meshing/inputs/input_mesh.h"
#include "meshing/inputs/mesh_oracle.h"

using namespace delmesh;

namespace {

Box3 cube_box(double h) { return Box3::cube(h); }

// The octahedron with vertices ±s e_i, outward oriented.
SurfaceMesh octahedron(double s) {
  SurfaceMesh m;
  std::vector<SurfaceMesh::Vertex_index> v;
  for (const Point3& p : {Point3(s, 0, 0), Point3(-s, 0, 0), Point3(0, s, 0), Point3(0, -s, 0), Point3(0, 0, s),
                          Point3(0, 0, -s)})
    v.push_back(m.add_vertex(p));
  const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (const auto& f : faces) BOOST_REQUIRE(m.add_face(v[f[0]], v[f[1]], v[f[2]]) != SurfaceMesh::null_face());
  return m;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(unit_scale)

BOOST_AUTO_TEST_CASE(exponent_is_zero_in_the_moderate_range) {
  BOOST_TEST(unit_scale_exponent(cube_box(1)) == 0);
  BOOST_TEST(unit_scale_exponent(cube_box(1e9)) == 0);  // side 2e9 < 2^32
  BOOST_TEST(unit_scale_exponent(cube_box(1e-9)) == 0);
  BOOST_TEST(unit_scale_exponent(cube_box(std::ldexp(1.0, 31))) == 32);  // side 2^32
  BOOST_TEST(unit_scale_exponent(cube_box(std::ldexp(1.0, -34))) == -33);
  const int k = unit_scale_exponent(cube_box(1e-100));
  const double side = std::ldexp(2e-100, -k);
  BOOST_TEST((side >= 1 && side < 2));
}

BOOST_AUTO_TEST_CASE(conversions_are_exact_and_restore_the_statistics) {
  const int k = -400;
  DelMeshOptions options;
  options.min_spacing = 3e-121;
  options.size_bound = 5e-121;
  const DelMeshOptions unit = unit_scale_options(options, k);
  BOOST_TEST(unit.min_spacing == std::ldexp(3e-121, 400));
  BOOST_TEST(*unit.size_bound == std::ldexp(5e-121, 400));

  DelMeshResult result;
  result.mesh = octahedron(0.75);
  result.statistics = {{"clip_box", {-1, 1, -1, 1, -1, 1}},
                       {"unsettled", {{"count", 1}, {"regions", {{{"check", "seed"}, {"location", {0.5, 0.25, 0}}}}}}},
                       {"min_spacing", {{"value", 0.125}, {"topology_value", 0.0625}, {"reached", true},
                                        {"witnesses_below", 3}, {"locations", {{1, 2, 3}}}}},
                       {"topology_phase", {{"min_spacing", {{"value", 0.125}, {"locations", nlohmann::json::array()}}}}},
                       {"vertices", 6}};
  restore_scale(result, k);
  const auto& j = result.statistics;
  BOOST_TEST(j.at("unit_scale_exponent") == k);
  BOOST_TEST(j.at("clip_box").at(1).get<double>() == std::ldexp(1.0, k));
  BOOST_TEST(j.at("unsettled").at("regions").at(0).at("location").at(1).get<double>() == std::ldexp(0.25, k));
  BOOST_TEST(j.at("min_spacing").at("value").get<double>() == std::ldexp(0.125, k));
  BOOST_TEST(j.at("min_spacing").at("topology_value").get<double>() == std::ldexp(0.0625, k));
  BOOST_TEST(j.at("min_spacing").at("witnesses_below") == 3);  // a count, not a length
  BOOST_TEST(j.at("min_spacing").at("locations").at(0).at(2).get<double>() == std::ldexp(3.0, k));
  BOOST_TEST(j.at("topology_phase").at("min_spacing").at("value").get<double>() == std::ldexp(0.125, k));
  BOOST_TEST(j.at("vertices") == 6);
  for (auto v : result.mesh.vertices()) {
    const Point3& p = result.mesh.point(v);
    BOOST_TEST(std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())}) == std::ldexp(0.75, k));
  }
}

// MeshOracle on the octahedron of size s answers at unit scale: its box is the input's times
// 2^-k, and projection, sides and seeds are those of the unit octahedron, scaled.
BOOST_AUTO_TEST_CASE(mesh_oracle_at_extreme_scales) {
  for (const double s : {1e-100, 1e80, 1e-300}) {
    BOOST_TEST_CONTEXT("size " << s) {
      MeshOracle oracle(octahedron(s), cube_box(2 * s));
      const int k = oracle.scale_exponent();
      BOOST_TEST(k == unit_scale_exponent(cube_box(2 * s)));
      BOOST_TEST(k != 0);
      BOOST_TEST(oracle.box().hi[0] == std::ldexp(2 * s, -k));
      const double u = std::ldexp(s, -k);  // the octahedron's vertex at unit scale
      BOOST_TEST((u >= 0.25 && u < 0.5));
      // The closest point to (u, u, u) is the centre of the face x + y + z = u.
      const auto y = oracle.project({u, u, u});
      BOOST_REQUIRE(y.has_value());
      for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs((*y)[i] - u / 3) < 1e-15);
      BOOST_TEST(oracle.value_sign(Vec3{0, 0, 0}) == -1);
      BOOST_TEST(oracle.value_sign(Vec3{u, u, u}) == 1);
      const Box3& b = oracle.box();
      const Domain domain = Domain::from_box({{b.lo[0], b.hi[0]}, {b.lo[1], b.hi[1]}, {b.lo[2], b.hi[2]}});
      const auto seeds = oracle.surface_critical({0.1, 0.2, 0.97}, domain, 1000);
      BOOST_TEST(seeds.roots.size() == 2u);
    }
  }
}

// A remesh of the octahedron of size s = 2^-332 through the conversions is the remesh of the
// octahedron of unit size (the same octahedron scaled by 2^-k, meshed unscaled), scaled back by
// 2^k exactly: the same status, the same triangles, every vertex the same times 2^k, on the input.
BOOST_AUTO_TEST_CASE(remesh_at_a_tiny_scale_is_the_unit_remesh_scaled) {
  const double s = std::ldexp(1.0, -332);
  MeshOracle tiny(octahedron(s), cube_box(1.25 * s));
  const int k = tiny.scale_exponent();
  BOOST_REQUIRE(k != 0);
  const double u = std::ldexp(s, -k);
  MeshOracle unit(octahedron(u), cube_box(1.25 * u));
  BOOST_REQUIRE(unit.scale_exponent() == 0);
  DelMeshOptions options;
  options.threads = 1;
  options.max_points = 300;
  options.time_limit_seconds = 60;
  options.min_spacing = 1e-3 * s;
  DelMeshResult scaled = del_mesh(tiny, unit_scale_options(options, k));
  restore_scale(scaled, k);
  DelMeshOptions unit_options = options;
  unit_options.min_spacing = 1e-3 * u;
  const DelMeshResult reference = del_mesh(unit, unit_options);
  BOOST_TEST(scaled.status == reference.status);
  BOOST_TEST(scaled.statistics.at("min_angle_deg") == reference.statistics.at("min_angle_deg"));
  BOOST_TEST(scaled.statistics.at("clip_box").at(1).get<double>() ==
             std::ldexp(reference.statistics.at("clip_box").at(1).get<double>(), k));
  BOOST_REQUIRE(scaled.mesh.number_of_vertices() == reference.mesh.number_of_vertices());
  BOOST_TEST(scaled.mesh.number_of_vertices() >= 6u);
  BOOST_TEST(scaled.mesh.number_of_faces() == reference.mesh.number_of_faces());
  for (auto v : scaled.mesh.vertices()) {
    const Point3& p = scaled.mesh.point(v);
    const Point3& q = reference.mesh.point(v);
    BOOST_TEST(p.x() == std::ldexp(q.x(), k));
    BOOST_TEST(p.y() == std::ldexp(q.y(), k));
    BOOST_TEST(p.z() == std::ldexp(q.z(), k));
    // On the octahedron |x| + |y| + |z| = s.
    BOOST_TEST(std::abs(std::abs(p.x()) + std::abs(p.y()) + std::abs(p.z()) - s) < 1e-12 * s);
  }
}

// The octahedron of size 2^-1074 (the least subnormal double) and of size 2^-1000: validation's
// box holds the vertices strictly (its margin would round away), and the oracle works on it.
BOOST_AUTO_TEST_CASE(validated_subnormal_mesh_gives_an_oracle) {
  for (const double s : {std::ldexp(1.0, -1074), std::ldexp(1.0, -1000)}) {
    BOOST_TEST_CONTEXT("size " << s) {
      const SurfaceMesh m = octahedron(s);
      std::vector<Point3> points(m.points().begin(), m.points().end());
      std::vector<std::vector<std::size_t>> polygons;
      for (auto f : m.faces()) {
        std::vector<std::size_t> polygon;
        for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) polygon.push_back(v.idx());
        polygons.push_back(polygon);
      }
      const InputMesh input = validate_input_mesh(points, polygons, "octahedron");
      for (int i = 0; i < 3; ++i) {
        BOOST_TEST(input.box.lo[i] < -s);
        BOOST_TEST(input.box.hi[i] > s);
      }
      std::unique_ptr<MeshOracle> oracle;
      BOOST_REQUIRE_NO_THROW(oracle = std::make_unique<MeshOracle>(input.mesh, input.box));
      BOOST_TEST(oracle->scale_exponent() < -990);
      BOOST_TEST(oracle->value_sign(Vec3{0, 0, 0}) == -1);
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
