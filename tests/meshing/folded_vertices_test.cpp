#include "meshing/inputs/folded_vertices.h"

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <boost/test/unit_test.hpp>

#include "meshing/inputs/input_mesh.h"
#include "tests/meshing/known_meshes.h"
#include "tests/temp_dir.h"

using namespace delmesh;
namespace fs = std::filesystem;

namespace {

// A fan of four faces around the origin whose normals are positive multiples of (1, 0, 0.3),
// (0, 1, −0.3), (−1, 0, 0.3), (0, −1, −0.3): their mean is the origin, inside their tetrahedron.
test::Soup folded_fan() {
  return {{Point3(0, 0, 0), Point3(-0.3, -0.3, 1), Point3(0.3, -0.3, -1), Point3(-0.3, -0.3, -1),
           Point3(0.3, -0.3, 1)},
          {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}};
}

std::vector<SurfaceMesh::Vertex_index> folded_in_archive_mesh(const std::string& name, SurfaceMesh* mesh = nullptr) {
  const std::string archive = "/usr/share/doc/libcgal-dev/data.tar.gz";
  BOOST_REQUIRE_MESSAGE(fs::exists(archive), archive + " is missing (install libcgal-demo)");
  test::TempDir dir;
  const std::string member = "data/meshes/" + name + ".off";
  const std::string command = "tar -xzf " + archive + " -C '" + dir.path.string() + "' " + member;
  BOOST_REQUIRE(std::system(command.c_str()) == 0);
  const InputMesh input = read_input_mesh((dir.path / member).string());
  if (mesh) *mesh = input.mesh;
  BOOST_TEST(input.folded_vertices == folded_vertices(input.mesh), boost::test_tools::per_element());
  return input.folded_vertices;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(folded_vertices_suite)

BOOST_AUTO_TEST_CASE(a_fan_whose_normals_surround_the_origin_is_folded) {
  SurfaceMesh mesh = folded_fan().to_surface_mesh();
  mesh.add_vertex(Point3(5, 5, 5));  // an isolated vertex is never folded
  const auto folded = folded_vertices(mesh);
  BOOST_REQUIRE(folded.size() == 1u);
  BOOST_TEST(mesh.point(folded.front()) == Point3(0, 0, 0));
  // Every direction sees the fan's faces facing both ways.
  for (const Vector3 n : {Vector3(0, 0, 1), Vector3(1, 0, 0), Vector3(0.3, -0.7, 0.2), Vector3(-1, 2, 5)}) {
    int facing = 0, away = 0;
    for (const auto f : mesh.faces()) {
      const auto h = mesh.halfedge(f);
      const Point3 &a = mesh.point(mesh.source(h)), &b = mesh.point(mesh.target(h)),
                   &c = mesh.point(mesh.target(mesh.next(h)));
      const double d = CGAL::cross_product(b - a, c - a) * n;
      facing += d > 0;
      away += d < 0;
    }
    BOOST_TEST(facing > 0);
    BOOST_TEST(away > 0);
  }
}

// The apex of a fan of six faces whose normals surround the origin only as a whole: the origin
// is interior to their hull but to no tetrahedron of four of them (it lies on a triangle of them).
BOOST_AUTO_TEST_CASE(normals_surrounding_the_origin_only_as_a_whole_are_folded) {
  using I3 = std::array<long long, 3>;
  const std::vector<I3> ring{{-1, -1, -2}, {1, 2, -2}, {0, 1, 1}, {1, 1, 2}, {0, -2, 0}, {0, 2, 1}};
  const auto cross = [](const I3& a, const I3& b) {
    return I3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const auto det = [&](const I3& a, const I3& b, const I3& c) {
    const I3 m = cross(b, c);
    return a[0] * m[0] + a[1] * m[1] + a[2] * m[2];
  };
  // The face (apex, r_k, r_k+1) has normal r_k × r_k+1 (exact in integers).
  std::vector<I3> normals;
  for (std::size_t k = 0; k < ring.size(); ++k) normals.push_back(cross(ring[k], ring[(k + 1) % ring.size()]));
  // No tetrahedron of four normals holds the origin strictly inside: the origin is on the same
  // side of all four faces of none of them.
  const I3 o{0, 0, 0};
  for (std::size_t a = 0; a < 6; ++a)
    for (std::size_t b = a + 1; b < 6; ++b)
      for (std::size_t c = b + 1; c < 6; ++c)
        for (std::size_t d = c + 1; d < 6; ++d) {
          const auto orient = [&](const I3& p, const I3& q, const I3& r, const I3& t) {
            const auto minus = [](const I3& x, const I3& y) { return I3{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; };
            const long long v = det(minus(q, p), minus(r, p), minus(t, p));
            return (v > 0) - (v < 0);
          };
          const I3 &na = normals[a], &nb = normals[b], &nc = normals[c], &nd = normals[d];
          const int s = orient(na, nb, nc, nd);
          const bool inside = s != 0 && orient(o, nb, nc, nd) == s && orient(na, o, nc, nd) == s &&
                              orient(na, nb, o, nd) == s && orient(na, nb, nc, o) == s;
          BOOST_TEST(!inside);
        }
  test::Soup fan;
  fan.points.push_back(Point3(0, 0, 0));
  for (const I3& r : ring) fan.points.push_back(Point3(r[0], r[1], r[2]));
  for (std::size_t k = 0; k < ring.size(); ++k) fan.triangles.push_back({0, 1 + k, 1 + (k + 1) % ring.size()});
  const SurfaceMesh mesh = fan.to_surface_mesh();
  const auto folded = folded_vertices(mesh);
  BOOST_REQUIRE(folded.size() == 1u);
  BOOST_TEST(mesh.point(folded.front()) == Point3(0, 0, 0));
}

// A high-valence vertex (the pole of a UV sphere with 4096 faces around it) is decided at once.
BOOST_AUTO_TEST_CASE(a_pole_of_high_valence_is_not_folded) {
  const int k = 4096;
  test::Soup cone;
  cone.points.push_back(Point3(0, 0, 1));
  for (int i = 0; i < k; ++i)
    cone.points.push_back(Point3(std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), 0.9));
  for (int i = 0; i < k; ++i) cone.triangles.push_back({0, static_cast<std::size_t>(1 + i),
                                                        static_cast<std::size_t>(1 + (i + 1) % k)});
  BOOST_TEST(folded_vertices(cone.to_surface_mesh()).empty());
}

BOOST_AUTO_TEST_CASE(convex_saddle_and_flat_vertices_are_not_folded) {
  BOOST_TEST(folded_vertices(test::octahedron().to_surface_mesh()).empty());
  BOOST_TEST(folded_vertices(test::icosahedron().to_surface_mesh()).empty());
  // The torus has saddle vertices on its inner equator: their normals still fit in a hemisphere.
  BOOST_TEST(folded_vertices(test::torus(16, 8).to_surface_mesh()).empty());
  // Four coplanar faces: every normal is the same, nowhere near surrounding the origin.
  const test::Soup flat{{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0), Point3(-1, 0, 0), Point3(0, -1, 0)},
                        {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}};
  BOOST_TEST(folded_vertices(flat.to_surface_mesh()).empty());
}

BOOST_AUTO_TEST_CASE(cgal_meshes_femur_has_one_folded_vertex_the_others_none) {
  // femur's fold is why its remeshing cannot end complete (paper/README.md, "Remeshing").
  SurfaceMesh femur;
  const auto folded = folded_in_archive_mesh("femur", &femur);
  BOOST_REQUIRE(folded.size() == 1u);
  const Point3& x = femur.point(folded.front());
  BOOST_TEST(std::abs(x.x() + 0.006) < 1e-3);
  BOOST_TEST(std::abs(x.y() + 0.074) < 1e-3);
  BOOST_TEST(std::abs(x.z() + 0.434) < 1e-3);
  for (const std::string name : {"eight", "knot1", "knot2", "elephant"})
    BOOST_TEST(folded_in_archive_mesh(name).empty(), name);
}

BOOST_AUTO_TEST_SUITE_END()
