#include "meshing/inputs/mesh_io.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <sstream>
#include <string>

#include <boost/test/unit_test.hpp>

#include <CGAL/IO/STL.h>

#include "common/errors.h"
#include "meshing/core/mesh_checker.h"
#include "tests/meshing/known_meshes.h"
#include "tests/meshing/mesh_io_vtp_reader.h"
#include "tests/temp_dir.h"

using namespace delmesh;
namespace fs = std::filesystem;

namespace {

using test::TempDir;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

//! A torus whose coordinates need all 17 digits (not representable in fewer).
SurfaceMesh awkward_torus() {
  test::Soup s = test::torus(7, 5);
  for (Point3& p : s.points) p = Point3(p.x() / 3.0, p.y() * std::sqrt(2.0), p.z() + 1e-9 / 7.0);
  return s.to_surface_mesh();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mesh_io_suite)

BOOST_AUTO_TEST_CASE(round_trip_is_exact_in_every_format) {
  TempDir dir;
  const SurfaceMesh mesh = awkward_torus();
  for (const char* name : {"t.off", "t.ply", "t.obj", "T.OFF"}) {
    const std::string path = dir.file(name);
    write_mesh(mesh, path);
    const SurfaceMesh back = read_mesh(path);
    BOOST_TEST(back.number_of_vertices() == mesh.number_of_vertices(), name);
    BOOST_TEST(back.number_of_faces() == mesh.number_of_faces(), name);
    // Every coordinate comes back bit for bit, in the same order.
    auto it = back.vertices().begin();
    bool exact = true;
    for (auto v : mesh.vertices()) exact = exact && back.point(*it++) == mesh.point(v);
    BOOST_TEST(exact, name);
    BOOST_TEST(check_mesh(back).has_topology({1}), name);
    BOOST_TEST(check_mesh(back).oriented, name);
    // Same faces with the same orientation: the soups are identical.
    TriangleSoup a = read_triangle_soup(path);
    std::vector<Point3> pts;
    std::vector<std::array<std::size_t, 3>> tris;
    mesh_to_soup(mesh, pts, tris);
    BOOST_TEST((a.triangles == tris), name);
    // No temporary file is left behind.
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir.path)) files += entry.is_regular_file();
    BOOST_TEST(files == 1u);
    fs::remove(path);
  }
}

BOOST_AUTO_TEST_CASE(output_is_byte_reproducible_and_readable_text) {
  TempDir dir;
  const SurfaceMesh mesh = awkward_torus();
  for (const char* ext : {".off", ".ply", ".obj"}) {
    write_mesh(mesh, dir.file(std::string("a") + ext));
    write_mesh(mesh, dir.file(std::string("b") + ext));
    const std::string a = slurp(dir.file(std::string("a") + ext));
    BOOST_TEST(!a.empty());
    BOOST_TEST(a == slurp(dir.file(std::string("b") + ext)), ext);
  }
  // Headers that MeshLab and ParaView expect.
  BOOST_TEST(slurp(dir.file("a.off")).rfind("OFF", 0) == 0u);
  const std::string ply = slurp(dir.file("a.ply"));
  BOOST_TEST(ply.rfind("ply\nformat ascii 1.0\n", 0) == 0u);
  BOOST_TEST(ply.find("element face 70") != std::string::npos);
  BOOST_TEST(slurp(dir.file("a.obj")).find("\nf ") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(overwrite_replaces_the_file) {
  TempDir dir;
  const std::string path = dir.file("m.off");
  write_mesh(test::octahedron().to_surface_mesh(), path);
  write_mesh(test::icosahedron().to_surface_mesh(), path);
  BOOST_TEST(read_mesh(path).number_of_vertices() == 12u);
}

BOOST_AUTO_TEST_CASE(write_errors) {
  TempDir dir;
  const SurfaceMesh mesh = test::octahedron().to_surface_mesh();
  BOOST_CHECK_THROW(write_mesh(mesh, dir.file("m.stp")), InvalidInput);
  BOOST_CHECK_THROW(write_mesh(mesh, dir.file("m")), InvalidInput);
  BOOST_CHECK_THROW(write_mesh(mesh, dir.file("no/such/dir/m.off")), std::runtime_error);
}

BOOST_AUTO_TEST_CASE(format_by_extension) {
  BOOST_TEST(mesh_format("a.off") == MeshFormat::off);
  BOOST_TEST(mesh_format("a.PLY") == MeshFormat::ply);
  BOOST_TEST(mesh_format("dir.x/a.obj") == MeshFormat::obj);
  BOOST_TEST(mesh_format("a.STL") == MeshFormat::stl);
  BOOST_TEST(mesh_format("a.vtp") == MeshFormat::vtp);
  try {
    (void)mesh_format("a.vtk");
    BOOST_ERROR("mesh_format accepted .vtk");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("unknown extension '.vtk' (expected .off, .ply, .obj, .stl or .vtp)") !=
               std::string::npos, e.what());
  }
  // .vtp is written, not read.
  TempDir dir;
  write_mesh(test::octahedron().to_surface_mesh(), dir.file("o.vtp"));
  try {
    (void)read_polygon_soup(dir.file("o.vtp"));
    BOOST_ERROR("read_polygon_soup read a .vtp file");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("(expected .off, .ply, .obj or .stl; .vtp files are written, not read)") !=
                   std::string::npos,
               e.what());
  }
}

// Binary STL through CGAL's writer: 80-byte header, triangle count, 50 bytes per triangle; CGAL's
// reader gives back the same triangles, corners in the same order, as float32 coordinates.
BOOST_AUTO_TEST_CASE(binary_stl_round_trip) {
  TempDir dir;
  const SurfaceMesh mesh = awkward_torus();
  const std::string path = dir.file("t.stl");
  write_mesh(mesh, path);
  const std::string bytes = slurp(path);
  BOOST_TEST(bytes.size() == 84 + 50 * mesh.number_of_faces());
  BOOST_TEST(bytes.rfind("solid", 0) != 0u);  // a binary file must not start like an ASCII one
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  BOOST_TEST(count == mesh.number_of_faces());

  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::ifstream in(path, std::ios::binary);
  BOOST_REQUIRE(CGAL::IO::read_STL(in, points, triangles));
  std::vector<Point3> written_points;
  std::vector<std::array<std::size_t, 3>> written;
  mesh_to_soup(mesh, written_points, written);
  BOOST_REQUIRE(triangles.size() == written.size());
  const auto as_float = [](const Point3& p) {
    return Point3(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  };
  bool same = true;
  for (std::size_t t = 0; t < written.size(); ++t)
    for (int k = 0; k < 3; ++k) same = same && points[triangles[t][k]] == as_float(written_points[written[t][k]]);
  BOOST_TEST(same);
  // The float32 points are distinct here, so CGAL's reader (which merges equal points) gives
  // back one point per vertex.
  BOOST_TEST(points.size() == written_points.size());
  BOOST_TEST(slurp(path) == bytes);  // reproducible
  write_mesh(mesh, dir.file("again.stl"));
  BOOST_TEST(slurp(dir.file("again.stl")) == bytes);
}

// VTK XML PolyData: every coordinate and normal as written, the triangles as Polys; without
// normals no PointData.  Normals leave the bytes of OFF, PLY and OBJ unchanged.
BOOST_AUTO_TEST_CASE(vtp_carries_points_triangles_and_normals) {
  TempDir dir;
  const SurfaceMesh mesh = awkward_torus();
  TriangleSoup soup;
  mesh_to_soup(mesh, soup.points, soup.triangles);
  PointNormals normals;
  for (const Point3& p : soup.points) {
    const double r = std::sqrt(p.x() * p.x() + p.y() * p.y() + p.z() * p.z());
    normals.push_back({p.x() / r, p.y() / r, p.z() / r});
  }
  std::ostringstream out;
  write_mesh(mesh, out, MeshFormat::vtp, normals);
  const std::string path = dir.write("t.vtp", out.str());
  const test::VtpFile vtp = test::read_vtp(path);
  BOOST_TEST(vtp.points == soup.points.size());
  BOOST_TEST(vtp.polys == soup.triangles.size());
  const std::vector<double>& P = vtp.arrays.at("Points");
  const std::vector<double>& N = vtp.arrays.at("Normals");
  const std::vector<double>& C = vtp.arrays.at("connectivity");
  const std::vector<double>& O = vtp.arrays.at("offsets");
  BOOST_REQUIRE(P.size() == 3 * soup.points.size());
  BOOST_REQUIRE(N.size() == 3 * soup.points.size());
  BOOST_REQUIRE(C.size() == 3 * soup.triangles.size());
  BOOST_REQUIRE(O.size() == soup.triangles.size());
  bool exact = true;
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    for (int k = 0; k < 3; ++k) exact = exact && P[3 * i + k] == soup.points[i][k] && N[3 * i + k] == normals[i][k];
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    exact = exact && O[t] == static_cast<double>(3 * (t + 1));
    for (int k = 0; k < 3; ++k) exact = exact && C[3 * t + k] == static_cast<double>(soup.triangles[t][k]);
  }
  BOOST_TEST(exact);
  // The same bytes to a file.
  write_mesh(mesh, dir.file("again.vtp"));
  const std::string plain = slurp(dir.file("again.vtp"));
  BOOST_TEST(plain.find("<PointData") == std::string::npos);
  BOOST_TEST(test::read_vtp(dir.file("again.vtp")).arrays.count("Normals") == 0u);
  for (MeshFormat format : {MeshFormat::off, MeshFormat::ply, MeshFormat::obj}) {
    std::ostringstream with, without;
    write_mesh(mesh, with, format, normals);
    write_mesh(mesh, without, format);
    BOOST_TEST(with.str() == without.str(), format);
  }
  // One normal per point, or none.
  normals.pop_back();
  std::ostringstream ignored;
  BOOST_CHECK_THROW(write_mesh(mesh, ignored, MeshFormat::vtp, normals), PreconditionViolation);
}

// The certified distances are point data of their own ("Scalars"), one number per point, with or
// without normals; a wrong count or a number that is no distance is a precondition violation.
BOOST_AUTO_TEST_CASE(vtp_carries_certified_distances) {
  TempDir dir;
  const SurfaceMesh mesh = awkward_torus();
  PointDistances distances;
  for (std::size_t i = 0; i < mesh.number_of_vertices(); ++i) distances.push_back(1e-3 / (1.0 + static_cast<double>(i)) / 3.0);
  PointNormals normals(mesh.number_of_vertices(), {0, 0, 1});
  for (const bool with_normals : {false, true}) {
    std::ostringstream out;
    write_mesh(mesh, out, MeshFormat::vtp, with_normals ? normals : PointNormals{}, distances);
    const std::string text = out.str();
    const test::VtpFile vtp = test::read_vtp(dir.write("d.vtp", text));
    BOOST_TEST(vtp.arrays.count("Normals") == (with_normals ? 1u : 0u));
    const std::vector<double>& D = vtp.arrays.at("certified_distance");
    BOOST_TEST((D == distances));  // every double as written
    BOOST_TEST(text.find("Scalars=\"certified_distance\"") != std::string::npos);
    BOOST_TEST((text.find("Normals=\"Normals\"") != std::string::npos) == with_normals);
    BOOST_TEST(text.find("Name=\"certified_distance\" NumberOfComponents=\"1\"") != std::string::npos);
  }
  for (MeshFormat format : {MeshFormat::off, MeshFormat::ply, MeshFormat::obj, MeshFormat::stl}) {
    std::ostringstream with, without;
    write_mesh(mesh, with, format, normals, distances);
    write_mesh(mesh, without, format);
    BOOST_TEST(with.str() == without.str(), format);
  }
  std::ostringstream ignored;
  PointDistances short_by_one(distances.begin(), distances.end() - 1);
  BOOST_CHECK_THROW(write_mesh(mesh, ignored, MeshFormat::vtp, {}, short_by_one), PreconditionViolation);
  for (double bad : {-1e-300, std::nan(""), std::numeric_limits<double>::infinity()}) {
    PointDistances d = distances;
    d[3] = bad;
    BOOST_CHECK_THROW(write_mesh(mesh, ignored, MeshFormat::vtp, {}, d), PreconditionViolation);
  }
}

namespace {

//! A binary STL file: `header` padded to 80 bytes, the count, then the triangles' records
//! (normal 0, corners, attribute 0).
std::string binary_stl(const std::string& header, std::uint32_t count, const std::vector<std::array<float, 9>>& triangles) {
  std::string bytes = header;
  bytes.resize(80, ' ');
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : triangles) {
    const float normal[3] = {0, 0, 0};
    bytes.append(reinterpret_cast<const char*>(normal), sizeof normal);
    bytes.append(reinterpret_cast<const char*>(t.data()), sizeof(float) * 9);
    bytes.append(2, '\0');
  }
  return bytes;
}

//! The four outward triangles of the tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1).
const std::vector<std::array<float, 9>> tetrahedron_stl = {{0, 0, 0, 0, 1, 0, 1, 0, 0},
                                                           {0, 0, 0, 1, 0, 0, 0, 0, 1},
                                                           {0, 0, 0, 0, 0, 1, 0, 1, 0},
                                                           {1, 0, 0, 0, 1, 0, 0, 0, 1}};

}  // namespace

// Write STL, read it back: the triangles' corners merged into one point per vertex (CGAL's writer
// repeats them), numbered in the order of first appearance, and the same closed torus with the
// same triangles in the same order, at float32 precision.
BOOST_AUTO_TEST_CASE(stl_round_trip_merges_the_corners) {
  TempDir dir;
  const SurfaceMesh mesh = awkward_torus();
  const std::string path = dir.file("t.stl");
  write_mesh(mesh, path);
  TriangleSoup written;
  mesh_to_soup(mesh, written.points, written.triangles);
  const TriangleSoup soup = read_triangle_soup(path);
  BOOST_TEST(soup.points.size() == written.points.size());
  BOOST_REQUIRE(soup.triangles.size() == written.triangles.size());
  const auto as_float = [](const Point3& p) {
    return Point3(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  };
  bool same = true, first_appearance = true;
  std::size_t next = 0;
  for (std::size_t t = 0; t < written.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      same = same && soup.points[soup.triangles[t][k]] == as_float(written.points[written.triangles[t][k]]);
      if (soup.triangles[t][k] == next) ++next;
      else first_appearance = first_appearance && soup.triangles[t][k] < next;
    }
  BOOST_TEST(same);
  BOOST_TEST(first_appearance);
  BOOST_TEST(next == soup.points.size());
  const SurfaceMesh back = read_mesh(path);
  BOOST_TEST(check_mesh(back).has_topology({1}));
  // Written again from what was read and read back, the same soup (the float32 coordinates are
  // exact doubles; only the normals, recomputed from them, may differ in the file).
  write_mesh(back, dir.file("again.stl"));
  const TriangleSoup again = read_triangle_soup(dir.file("again.stl"));
  BOOST_TEST((again.points == soup.points));
  BOOST_TEST((again.triangles == soup.triangles));
}

// ASCII STL: keywords in any case, CRLF ends of lines, two solids, -0 and 0 one point, names and
// normals ignored; a binary file whose header begins with "solid" is read as binary (its size is
// 84 + 50 N).
BOOST_AUTO_TEST_CASE(reads_ascii_and_binary_stl) {
  TempDir dir;
  const std::string ascii =
      "solid tet\r\n"
      "  facet normal 0 0 -1\r\n    outer loop\r\n      vertex 0 0 0\r\n      vertex 0 1 0\r\n      vertex 1 0 0\r\n"
      "    endloop\r\n  endfacet\r\n"
      "  FACET NORMAL 0 -1 0\r\n    OUTER LOOP\r\n      VERTEX -0 0 0\r\n      VERTEX 1 0 0\r\n      VERTEX 0 0 1\r\n"
      "    ENDLOOP\r\n  ENDFACET\r\n"
      "endsolid tet\r\n"
      "solid second\n"
      "facet normal nan nan nan\nouter loop\nvertex 0 0 0\nvertex 0 0 1e0\nvertex 0 1 0\nendloop\nendfacet\n"
      "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
      "endsolid second\n";
  const TriangleSoup a = read_triangle_soup(dir.write("tet.stl", ascii));
  BOOST_REQUIRE(a.points.size() == 4u);
  BOOST_TEST((a.points == std::vector<Point3>{Point3(0, 0, 0), Point3(0, 1, 0), Point3(1, 0, 0), Point3(0, 0, 1)}));
  BOOST_TEST((a.triangles == std::vector<std::array<std::size_t, 3>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {2, 1, 3}}));
  const MeshReport report = check_mesh(read_mesh(dir.file("tet.stl")));
  BOOST_TEST(report.has_topology({0}));

  const std::string binary = binary_stl("solid but binary", 4, tetrahedron_stl);
  BOOST_REQUIRE(binary.size() == 84u + 4u * 50u);
  const TriangleSoup b = read_triangle_soup(dir.write("TET.STL", binary));
  BOOST_TEST((b.points == a.points));
  BOOST_TEST((b.triangles == a.triangles));
}

// Every malformed STL file is one InvalidInput that names the file and says what is wrong; a
// count that does not match the size is refused before anything is allocated for it.
BOOST_AUTO_TEST_CASE(malformed_stl_is_invalid_input) {
  TempDir dir;
  const std::string good = binary_stl("", 4, tetrahedron_stl);
  std::string nan_corner = good;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_corner.data() + 84 + 12 + 4, &nan, 4);
  const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
  const std::pair<const char*, std::string> bad[] = {
      {"binary STL: its 84-byte header declares 4 triangles, which take 84 + 50 x 4 = 284 bytes, but the file has 283 bytes",
        good.substr(0, good.size() - 1)},
      {"declares 5 triangles, which take 84 + 50 x 5 = 334 bytes, but the file has 284 bytes", binary_stl("", 5, tetrahedron_stl)},
      {"declares 4294967295 triangles, which take 84 + 50 x 4294967295 = 214748364834 bytes, but the file has 84 bytes",
        binary_stl("", 0xffffffffu, {})},
      {"truncated: binary STL has an 84-byte header, the file has 40 bytes", good.substr(0, 40)},
      {"triangle 0 has a non-finite coordinate", nan_corner},
      {"has no faces", binary_stl("", 0, {})},
      {"is empty", ""},
      {"triangle 0 has a non-finite coordinate", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e999 0 0\n"
                                               "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n"},
      {"truncated: the file ends before 'endsolid' (after 1 facets)", "solid x\n" + facet},
      {"truncated: the file ends in facet 0 (expected 'endfacet')", "solid x\n" + facet.substr(0, facet.size() - 9)},
      {"facet 0: expected 'vertex', got 'vertx'", "solid x\nfacet normal 0 0 1\nouter loop\nvertx 0 0 0\n"},
      {"facet 0: 'one' is not a number", "solid x\nfacet normal 0 0 1\nouter loop\nvertex one 0 0\n"},
      {"facet 1: expected 'facet' or 'endsolid', got 'face'", "solid x\n" + facet + "face\n"},
      {"after 'endsolid': expected 'solid' or the end of the file, got 'junk'", "solid x\n" + facet + "endsolid x\njunk\n"},
      {"face 0 repeats a vertex", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nvertex 0 1 0\n"
                                   "endloop\nendfacet\nendsolid x\n"},
      {"(nor is it binary STL: its 84-byte header declares", "solid x\n" + facet + facet + "oops\n"},
  };
  int number = 0;
  for (const auto& entry : bad) {
    const std::string name = "bad" + std::to_string(number++) + ".stl";
    const std::string path = dir.write(name, entry.second);
    try {
      (void)read_triangle_soup(path);
      BOOST_ERROR("no exception for " << entry.first);
    } catch (const InvalidInput& e) {
      const std::string message = e.what();
      BOOST_TEST(message.rfind("mesh file '" + path + "': ", 0) == 0u, message);
      BOOST_TEST(message.find(entry.first) != std::string::npos, entry.first << " | " << message);
    }
    BOOST_CHECK_THROW(read_mesh(path), InvalidInput);
  }
}

// Faces of more than three vertices are triangulated each on its own, in place, keeping its
// orientation; triangles and points stay as they are.  A degenerate polygon is refused.
BOOST_AUTO_TEST_CASE(polygons_are_triangulated_in_place) {
  PolygonSoup pyramid;
  pyramid.points = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 1, 0), Point3(0, 1, 0), Point3(0.5, 0.5, 1)};
  for (const std::vector<std::size_t>& face :
       std::vector<std::vector<std::size_t>>{{0, 1, 4}, {0, 3, 2, 1}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}}) {
    pyramid.corners.insert(pyramid.corners.end(), face.begin(), face.end());
    pyramid.offsets.push_back(pyramid.corners.size());
  }
  const TriangleSoup soup = triangulate_polygons(pyramid, "pyramid.off");
  BOOST_TEST((soup.points == pyramid.points));
  BOOST_REQUIRE(soup.triangles.size() == 6u);
  BOOST_TEST((soup.triangles[0] == std::array<std::size_t, 3>{0, 1, 4}));
  BOOST_TEST((soup.triangles[3] == std::array<std::size_t, 3>{1, 2, 4}));
  BOOST_TEST((soup.triangles[5] == std::array<std::size_t, 3>{3, 0, 4}));
  // The quadrilateral's two triangles cover its four corners and face down, as it does.
  std::set<std::size_t> corners;
  for (int t = 1; t <= 2; ++t) {
    const auto& tri = soup.triangles[t];
    corners.insert(tri.begin(), tri.end());
    const Vector3 n = CGAL::cross_product(soup.points[tri[1]] - soup.points[tri[0]], soup.points[tri[2]] - soup.points[tri[0]]);
    BOOST_TEST(n.z() < 0);
  }
  BOOST_TEST(corners.size() == 4u);
  const MeshReport report = check_mesh(soup.points, soup.triangles);
  BOOST_TEST((report.closed && report.manifold));
  BOOST_TEST(report.oriented);

  PolygonSoup flat;
  flat.points = {Point3(0, 0, 0), Point3(1, 0, 0), Point3(2, 0, 0), Point3(3, 0, 0)};
  flat.corners = {0, 1, 2, 3};
  flat.offsets.push_back(4);
  try {
    (void)triangulate_polygons(flat, "flat.off");
    BOOST_ERROR("a degenerate polygon was triangulated");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("mesh file 'flat.off': face 0 (4 vertices) could not be triangulated") !=
               std::string::npos, e.what());
  }
}

BOOST_AUTO_TEST_CASE(reads_a_binary_ply) {
  TempDir dir;
  // Two triangles, little-endian floats for the vertices and uchar/int lists for the faces.
  std::ostringstream out(std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5f}};
  out.write(reinterpret_cast<const char*>(v), sizeof v);
  const unsigned char three = 3;
  const int f[2][3] = {{0, 1, 2}, {2, 1, 3}};
  for (const auto& face : f) {
    out.write(reinterpret_cast<const char*>(&three), 1);
    out.write(reinterpret_cast<const char*>(face), sizeof face);
  }
  const std::string path = dir.write("b.ply", out.str());
  const TriangleSoup soup = read_triangle_soup(path);
  BOOST_TEST(soup.points.size() == 4u);
  BOOST_TEST(soup.triangles.size() == 2u);
  BOOST_TEST(soup.points[3].z() == 0.5);
  BOOST_TEST(check_mesh(read_mesh(path)).boundary_edges == 4u);
}

BOOST_AUTO_TEST_CASE(corrupt_files_are_invalid_input) {
  TempDir dir;
  const std::string good = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  BOOST_CHECK_NO_THROW(read_triangle_soup(dir.write("good.off", good)));
  const std::pair<const char*, std::string> bad[] = {
      {"missing.off", ""},  // not written
      {"empty.off", ""},
      {"garbage.off", "this is not a mesh\n"},
      {"truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"},
      {"truncated_face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"},
      {"huge_count.off", "OFF\n4000000000 1 0\n0 0 0\n"},
      {"quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"},
      {"index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"},
      {"repeat.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n"},
      {"inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n"},
      {"no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"},
      {"index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
      {"quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"},
      {"truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
                        "property double z\nelement face 1\nproperty list uchar int vertex_indices\n"
                        "end_header\n0 0 0\n1 0 0\n"},
      {"no_header_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"},
      {"huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 999999999999\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n"},
      {"mesh.stl", good},
      {"mesh", good},
  };
  for (const auto& [name, content] : bad) {
    const std::string path = dir.file(name);
    if (std::string(name) != "missing.off") dir.write(name, content);
    try {
      (void)read_triangle_soup(path);
      BOOST_ERROR("no exception for " << name);
    } catch (const InvalidInput& e) {
      // The message names the file.
      BOOST_TEST(std::string(e.what()).find(name) != std::string::npos, name << ": " << e.what());
    } catch (const std::exception& e) {
      BOOST_ERROR("wrong exception type for " << name << ": " << e.what());
    }
    BOOST_CHECK_THROW(read_mesh(path), InvalidInput);
  }
}

// When a reader refuses a file, the message says what is wrong with it, where.
BOOST_AUTO_TEST_CASE(corrupt_files_are_explained) {
  TempDir dir;
  const std::pair<const char*, std::string> cases[][1] = {
      {{"word.off", "OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n"}},
      {{"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\n"}},
      {{"face.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"}},
      {{"count.off", "OFF\n-3 1 0\n0 0 0\n"}},
      {{"relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n"}},
      {{"empty.obj", "# nothing\n"}},
      {{"none.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"}},
  };
  const char* expected[] = {
      "vertex 1: 'zz' is not a number",
      "truncated: the file ends in vertex 2 of the 3 declared",
      "truncated: the file ends before face 1 of the 2 declared",
      "the header declares a negative vertex count (-3)",
      "line 4: a face refers to vertex -4, but 3 vertices are defined before it",
      "has no faces",
      "has no faces",
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    const auto& [name, content] = cases[i][0];
    try {
      (void)read_triangle_soup(dir.write(name, content));
      BOOST_ERROR("no exception for " << name);
    } catch (const InvalidInput& e) {
      BOOST_TEST(std::string(e.what()).find(expected[i]) != std::string::npos, name << ": " << e.what());
    }
  }
}

// The OFF variants the reader accepts: colours (of any value: they are skipped), normals,
// homogeneous coordinates, comments, counts on the keyword's line, and the binary layout.
BOOST_AUTO_TEST_CASE(off_variants_are_read) {
  TempDir dir;
  const std::pair<const char*, std::string> files[] = {
      {"colours.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 999999 -5 0.5 1e300\n0 1 0 0 0 0\n3 0 1 2 300 -1 0\n"},
      {"normals.off", "NOFF 3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n"},
      {"homogeneous.off", "4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n3 0 1 2\n"},
      {"comments.off", "# header\nOFF # keyword\n3 1 0 # counts\n0 0 0\n1 0 0 # v1\n0 1 0\n# a face\n3 0 1 2\n"},
      {"keywordless.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"ndim.off", "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
  };
  for (const auto& [name, content] : files) {
    const TriangleSoup soup = read_triangle_soup(dir.write(name, content));
    BOOST_TEST(soup.points.size() == 3u, name);
    BOOST_TEST((soup.triangles == std::vector<std::array<std::size_t, 3>>{{0, 1, 2}}), name);
    BOOST_TEST((soup.points[1] == Point3(1, 0, 0)), name);
    BOOST_TEST((soup.points[2] == Point3(0, 1, 0)), name);
  }
  // Geomview's binary OFF: big-endian int32 counts and indices, float32 coordinates, a colour count
  // after each face.
  std::string binary = "OFF BINARY\n";
  const auto put32 = [&](std::uint32_t word) {
    for (int shift = 24; shift >= 0; shift -= 8) binary += static_cast<char>((word >> shift) & 0xff);
  };
  const auto put_float = [&](float value) {
    std::uint32_t word;
    std::memcpy(&word, &value, 4);
    put32(word);
  };
  for (std::uint32_t count : {3u, 1u, 0u}) put32(count);
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.25f}) put_float(c);
  for (std::uint32_t word : {3u, 2u, 1u, 0u, 0u}) put32(word);
  const TriangleSoup soup = read_triangle_soup(dir.write("binary.off", binary));
  BOOST_TEST((soup.triangles == std::vector<std::array<std::size_t, 3>>{{2, 1, 0}}));
  BOOST_TEST((soup.points[2] == Point3(0, 1, 0.25)));
}

// Polygons of any size are read as they are, in all three formats and both encodings: a square
// pyramid has one quadrilateral and four triangles.  read_triangle_soup refuses the quadrilateral.
BOOST_AUTO_TEST_CASE(polygon_faces_are_read_as_polygons) {
  TempDir dir;
  const std::string points = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n";
  const std::string faces = "4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
  std::string binary_ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
      "property float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1}};
  binary_ply.append(reinterpret_cast<const char*>(v), sizeof v);
  const std::vector<std::vector<int>> lists = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  for (const auto& list : lists) {
    binary_ply += static_cast<char>(list.size());
    binary_ply.append(reinterpret_cast<const char*>(list.data()), list.size() * sizeof(int));
  }
  std::string binary_off = "OFF BINARY\n";
  const auto put32 = [&](std::uint32_t word) {
    for (int shift = 24; shift >= 0; shift -= 8) binary_off += static_cast<char>((word >> shift) & 0xff);
  };
  for (std::uint32_t count : {5u, 5u, 0u}) put32(count);
  for (const auto& p : v)
    for (float c : p) {
      std::uint32_t word;
      std::memcpy(&word, &c, 4);
      put32(word);
    }
  for (const auto& list : lists) {
    put32(static_cast<std::uint32_t>(list.size()));
    for (int i : list) put32(static_cast<std::uint32_t>(i));
    put32(0);  // no colour
  }
  const std::pair<const char*, std::string> files[] = {
      {"pyramid.off", "OFF\n5 5 0\n" + points + faces},
      {"pyramid.ply", "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n" +
                          points + faces},
      {"pyramid.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nf 1 4 3 2\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n"},
      {"binary.ply", binary_ply},
      {"binary.off", binary_off},
  };
  for (const auto& [name, content] : files) {
    BOOST_TEST_CONTEXT(name) {
      const std::string path = dir.write(name, content);
      const PolygonSoup soup = read_polygon_soup(path);
      BOOST_TEST(soup.points.size() == 5u);
      BOOST_TEST(soup.polygons() == (std::vector<std::vector<std::size_t>>{{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4},
                                                                           {2, 3, 4}, {3, 0, 4}}));
      BOOST_TEST((soup.points[4] == Point3(0.5, 0.5, 1)));
      try {
        (void)read_triangle_soup(path);
        BOOST_ERROR("read_triangle_soup read a quadrilateral");
      } catch (const InvalidInput& e) {
        BOOST_TEST(std::string(e.what()).find("face 0 has 4 vertices; only triangle meshes are supported") !=
                   std::string::npos);
      }
    }
  }
  // Faces of fewer than three vertices, and a polygon that repeats a vertex, are refused.
  const std::pair<const char*, std::string> bad[] = {
      {"edge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n"},
      {"edge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"},
      {"repeat.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 1\n"},
  };
  const char* why[] = {"face 0 has 2 vertices (a face needs at least three)", "a face needs at least three",
                       "face 0 repeats a vertex"};
  for (std::size_t i = 0; i < std::size(bad); ++i) {
    try {
      (void)read_polygon_soup(dir.write(bad[i].first, bad[i].second));
      BOOST_ERROR("no exception for " << bad[i].first);
    } catch (const InvalidInput& e) {
      BOOST_TEST(std::string(e.what()).find(why[i]) != std::string::npos, bad[i].first << ": " << e.what());
    }
  }
}

// The PLY variants the reader accepts: other properties and elements before, between and after
// the ones it reads, every type name, big-endian binary.
BOOST_AUTO_TEST_CASE(ply_variants_are_read) {
  TempDir dir;
  const std::string ascii =
      "ply\r\nformat ascii 1.0\r\ncomment colours and normals\r\nelement material 1\r\nproperty uchar red\r\n"
      "element vertex 3\r\nproperty float32 nx\r\nproperty double x\r\nproperty float y\r\nproperty int16 z\r\n"
      "property list uint8 int32 extra\r\nelement face 1\r\nproperty uchar flags\r\n"
      "property list uchar uint vertex_index\r\nelement edge 1\r\nproperty int vertex1\r\nend_header\r\n"
      "7\n0.5 0 0 0 2 9 9\n0.5 1 0 0 0\n0.5 0 1 0 1 -4\n0 3 0 1 2\n5\n";
  const TriangleSoup soup = read_triangle_soup(dir.write("ascii.ply", ascii));
  BOOST_TEST(soup.points.size() == 3u);
  BOOST_TEST((soup.triangles == std::vector<std::array<std::size_t, 3>>{{0, 1, 2}}));
  BOOST_TEST((soup.points[2] == Point3(0, 1, 0)));
  std::string big = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&](const void* data, int n) {
    for (int i = n - 1; i >= 0; --i) big += static_cast<const char*>(data)[i];  // little- to big-endian
  };
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.5f}) put(&c, 4);
  big += '\3';
  for (std::int32_t i : {2, 0, 1}) put(&i, 4);
  const TriangleSoup b = read_triangle_soup(dir.write("big.ply", big));
  BOOST_TEST((b.triangles == std::vector<std::array<std::size_t, 3>>{{2, 0, 1}}));
  BOOST_TEST((b.points[2] == Point3(0, 1, 0.5)));
}

// The classes of input that crashed CGAL's OFF and PLY readers under the fuzzer (the inputs
// themselves are in fuzz/crashes/ and checked through `delmesh check` by tests/apps): each is now
// refused with a message that says what is wrong, or read when it is a valid file.
BOOST_AUTO_TEST_CASE(inputs_that_crashed_the_former_readers) {
  TempDir dir;
  std::string skipped_list = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement edge 1\nproperty list uint uchar ids\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  skipped_list.append(36, '\0');
  skipped_list += std::string("\x00\x28\x6b\xee", 4);  // a list of 4 000 000 000 bytes
  const std::pair<const char*, std::string> cases[] = {
      {"colour.off", "COFF\n3 1 0\n0 0 0 1e309 -1e309 nan\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"negative_size.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-3 0 1 2\n"},
      {"huge_size.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n42949672950 0 1 2\n"},
      {"float_size.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1e308 0 1 2\n"},
      {"negative_index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -4 2\n"},
      {"property_first.ply", "ply\nformat ascii 1.0\nproperty float x\nelement vertex 3\nend_header\n"},
      {"list_size.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n255 0 1 2\n"},
      {"skipped_list.ply", skipped_list},
      {"out_of_type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n1 0 0\n0 1 0\n3 0 1 4294967296\n"},
  };
  const char* expected[] = {
      nullptr,  // read: the colour is skipped
      "face 0: '-3' is not a vertex count",
      "face 0 lists fewer vertices than its count 42949672950 (truncated?)",
      "face 0: '1e308' is not a vertex count",
      "face 0 refers to vertex -4, but the file has 3 vertices (numbered 0 to 2)",
      "header line 3: a property line comes before any element line",
      "truncated: the file ends in face 0 of the 1 declared",
      "truncated: the file ends in element 'edge' 0 of the 1 declared",
      "face 0: '4294967296' is not an integer of the declared type",
  };
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    const auto& [name, content] = cases[i];
    const std::string path = dir.write(name, content);
    if (!expected[i]) {
      BOOST_TEST(read_triangle_soup(path).triangles.size() == 1u, name);
      continue;
    }
    try {
      (void)read_triangle_soup(path);
      BOOST_ERROR("no exception for " << name);
    } catch (const InvalidInput& e) {
      BOOST_TEST(std::string(e.what()).find(expected[i]) != std::string::npos, name << ": " << e.what());
    }
  }
}

BOOST_AUTO_TEST_CASE(non_manifold_soup_reads_as_soup_only) {
  TempDir dir;
  // Two triangles sharing one vertex plus a third through the same edge as the first: an edge in
  // three triangles cannot be a Surface_mesh.
  const std::string path = dir.write(
      "nm.off", "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  const TriangleSoup soup = read_triangle_soup(path);
  BOOST_TEST(check_mesh(soup.points, soup.triangles).nonmanifold_edges == 1u);
  BOOST_CHECK_THROW(read_mesh(path), InvalidInput);
}

BOOST_AUTO_TEST_SUITE_END()
