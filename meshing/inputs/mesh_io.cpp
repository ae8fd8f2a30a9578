#include "meshing/inputs/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <filesystem>
#include <fstream>
#include <locale>
#include <new>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include "common/errors.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/inputs/detail/mesh_readers.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;

//! Significant digits that make every double round-trip through text.
constexpr int full_double_precision = 17;

//! The extension of path, in lower case ("" if none).
std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

//! The format of a file to read: the formats written but .vtp.
MeshFormat read_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".off") return MeshFormat::off;
  if (ext == ".ply") return MeshFormat::ply;
  if (ext == ".obj") return MeshFormat::obj;
  if (ext == ".stl") return MeshFormat::stl;
  throw InvalidInput("mesh file '" + path + "': unknown extension '" + ext + "' (expected .off, .ply, .obj or .stl" +
                     (ext == ".vtp" ? std::string("; .vtp files are written, not read)") : ")"));
}

//! The soup as VTK XML PolyData, ASCII: the points, the triangles as Polys (connectivity and
//! offsets) and, if given, the point data "Normals" (Float64, three components, the attribute
//! Normals) and "certified_distance" (Float64, one component, the attribute Scalars).
void write_vtp(const TriangleSoup& soup, std::ostream& out, const PointNormals& normals,
               const PointDistances& distances) {
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << soup.points.size() << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      << "NumberOfStrips=\"0\" NumberOfPolys=\"" << soup.triangles.size() << "\">\n";
  if (!normals.empty() || !distances.empty()) {
    out << "      <PointData" << (normals.empty() ? "" : " Normals=\"Normals\"")
        << (distances.empty() ? "" : " Scalars=\"certified_distance\"") << ">\n";
    if (!normals.empty()) {
      out << "        <DataArray type=\"Float64\" Name=\"Normals\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (const auto& n : normals) out << "          " << n[0] << ' ' << n[1] << ' ' << n[2] << '\n';
      out << "        </DataArray>\n";
    }
    if (!distances.empty()) {
      out << "        <DataArray type=\"Float64\" Name=\"certified_distance\" NumberOfComponents=\"1\" "
             "format=\"ascii\">\n";
      for (double d : distances) out << "          " << d << '\n';
      out << "        </DataArray>\n";
    }
    out << "      </PointData>\n";
  }
  out << "      <Points>\n"
      << "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Point3& p : soup.points) out << "          " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  out << "        </DataArray>\n"
      << "      </Points>\n"
      << "      <Polys>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& t : soup.triangles) out << "          " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (std::size_t f = 1; f <= soup.triangles.size(); ++f) out << "          " << 3 * f << '\n';
  out << "        </DataArray>\n"
      << "      </Polys>\n"
      << "    </Piece>\n"
      << "  </PolyData>\n"
      << "</VTKFile>\n";
}

[[noreturn]] void corrupt(const std::string& path, const std::string& why) { detail::mesh_file_error(path, why); }

using detail::printable;
using detail::vertex_range;

//! The reason CGAL's reader refused an OBJ file, found by reading its v and f lines again (the
//! first problem met), or "" if none is found.  Indices are quoted as in the file (1-based,
//! negative ones relative to the last vertex defined).
std::string diagnose_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  in.imbue(std::locale::classic());
  std::string line;
  long long vertices = 0, faces = 0;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line);
    std::string keyword;
    fields >> keyword;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (keyword == "v") {
      for (int k = 0; k < 3; ++k) {
        std::string w;
        if (!(fields >> w)) return where + "a vertex needs three coordinates";
        char* end = nullptr;
        const double value = std::strtod(w.c_str(), &end);
        if (end != w.c_str() + w.size()) return where + "'" + printable(w) + "' is not a number";
        if (!std::isfinite(value)) return where + "a vertex has a non-finite coordinate";
      }
      ++vertices;
    } else if (keyword == "f") {
      std::string w;
      int corners = 0;
      while (fields >> w) {
        const std::string head = w.substr(0, w.find('/'));
        char* end = nullptr;
        const long long index = std::strtoll(head.c_str(), &end, 10);
        if (head.empty() || end != head.c_str() + head.size()) return where + "'" + printable(w) + "' is not a vertex index";
        const long long resolved = index < 0 ? vertices + index + 1 : index;
        if (index == 0 || resolved < 1 || resolved > vertices)
          return where + "a face refers to vertex " + head + ", but " +
                 (vertices == 0 ? std::string("no vertex is defined before it")
                                : std::to_string(vertices) + " vertices are defined before it (indices 1 to " +
                                      std::to_string(vertices) + ", or -1 to -" + std::to_string(vertices) +
                                      " counting back)");
        ++corners;
      }
      if (corners < 3) return where + "a face needs at least three vertices";
      ++faces;
    }
  }
  if (faces == 0) return "has no faces";
  return "";
}

//! An OBJ file read by CGAL's reader (which bounds its allocations by the lines it reads).
PolygonSoup read_obj(const std::string& path) {
  std::vector<Point3> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    ok = CGAL::IO::read_OBJ(path, points, polygons);
  } catch (const std::bad_alloc&) {
    corrupt(path, "out of memory while reading");
  } catch (const std::exception& e) {
    corrupt(path, std::string("the reader failed: ") + e.what());
  }
  if (!ok) {
    const std::string reason = diagnose_obj(path);
    corrupt(path, reason.empty() ? std::string("cannot be parsed (truncated or corrupt)") : reason);
  }
  PolygonSoup soup;
  soup.points = std::move(points);
  soup.offsets.reserve(polygons.size() + 1);
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& polygon = polygons[f];
    if (polygon.size() < 3) detail::too_few_corners(path, f, std::to_string(polygon.size()));
    soup.corners.insert(soup.corners.end(), polygon.begin(), polygon.end());
    soup.offsets.push_back(soup.corners.size());
  }
  return soup;
}

}  // namespace

MeshFormat mesh_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".vtp") return MeshFormat::vtp;
  if (ext == ".off" || ext == ".ply" || ext == ".obj" || ext == ".stl") return read_format(path);
  throw InvalidInput("mesh file '" + path + "': unknown extension '" + ext +
                     "' (expected .off, .ply, .obj, .stl or .vtp)");
}

void write_triangle_soup(const TriangleSoup& soup, std::ostream& out, MeshFormat format, const PointNormals& normals,
                         const PointDistances& distances) {
  for (const auto& t : soup.triangles)
    for (std::size_t v : t)
      if (v >= soup.points.size()) throw PreconditionViolation("write_triangle_soup: vertex index out of range");
  if (!normals.empty() && normals.size() != soup.points.size())
    throw PreconditionViolation("write_triangle_soup: " + std::to_string(normals.size()) + " normals for " +
                                std::to_string(soup.points.size()) + " points");
  if (!distances.empty() && distances.size() != soup.points.size())
    throw PreconditionViolation("write_triangle_soup: " + std::to_string(distances.size()) + " distances for " +
                                std::to_string(soup.points.size()) + " points");
  for (double d : distances)
    if (!(std::isfinite(d) && d >= 0)) throw PreconditionViolation("write_triangle_soup: a distance is not finite and >= 0");
  out.imbue(std::locale::classic());
  out.precision(full_double_precision);
  const auto np = CGAL::parameters::stream_precision(full_double_precision);
  switch (format) {
    case MeshFormat::off:
      CGAL::IO::write_OFF(out, soup.points, soup.triangles, np);
      break;
    case MeshFormat::ply:
      CGAL::IO::set_mode(out, CGAL::IO::ASCII);
      CGAL::IO::write_PLY(out, soup.points, soup.triangles, np);
      break;
    case MeshFormat::obj:
      CGAL::IO::write_OBJ(out, soup.points, soup.triangles, np);
      break;
    case MeshFormat::stl:
      CGAL::IO::set_mode(out, CGAL::IO::BINARY);
      CGAL::IO::write_STL(out, soup.points, soup.triangles);
      break;
    case MeshFormat::vtp:
      write_vtp(soup, out, normals, distances);
      break;
  }
}

void write_mesh(const SurfaceMesh& mesh, std::ostream& out, MeshFormat format, const PointNormals& normals,
                const PointDistances& distances) {
  TriangleSoup soup;
  mesh_to_soup(mesh, soup.points, soup.triangles);
  write_triangle_soup(soup, out, format, normals, distances);
}

void write_triangle_soup(const TriangleSoup& soup, const std::string& path) {
  const MeshFormat format = mesh_format(path);
  const fs::path target(path);
  const fs::path temporary =
      target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()));
  bool ok = false;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
    try {
      write_triangle_soup(soup, out, format);
    } catch (...) {
      out.close();
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw;
    }
    out.flush();
    ok = out.good();
  }
  std::error_code ignored;
  if (!ok) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': the write failed (disk full?)");
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
}

void write_mesh(const SurfaceMesh& mesh, const std::string& path) {
  mesh_format(path);  // reject an unknown extension before any work
  TriangleSoup soup;
  mesh_to_soup(mesh, soup.points, soup.triangles);
  write_triangle_soup(soup, path);
}

PolygonSoup read_polygon_soup(const std::string& path) {
  const MeshFormat format = read_format(path);
  std::error_code error;
  if (fs::is_directory(path, error)) corrupt(path, "is a directory, not a mesh file");
  if (!fs::exists(path, error)) corrupt(path, "no such file");
  if (!fs::is_regular_file(path, error)) corrupt(path, "is not a regular file");
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (error) corrupt(path, "cannot read its size: " + error.message());
  if (bytes == 0) corrupt(path, "is empty");
  PolygonSoup soup;
  if (format == MeshFormat::obj) {
    soup = read_obj(path);
  } else {
    // OFF, PLY and STL: our own readers, on the whole file (no declared count reaches an allocation).
    std::ifstream in(path, std::ios::binary);
    if (!in) corrupt(path, "cannot be opened for reading");
    std::string contents(static_cast<std::size_t>(bytes), '\0');
    if (!in.read(contents.data(), static_cast<std::streamsize>(bytes))) corrupt(path, "cannot be read");
    soup = format == MeshFormat::off   ? detail::read_off(path, contents)
           : format == MeshFormat::ply ? detail::read_ply(path, contents)
                                       : detail::read_stl(path, contents);
  }
  if (soup.faces() == 0) corrupt(path, "has no faces");
  std::vector<std::size_t> sorted;
  for (std::size_t f = 0; f < soup.faces(); ++f) {
    const std::size_t* first = soup.face(f);
    const std::size_t* last = first + soup.face_size(f);
    for (const std::size_t* it = first; it != last; ++it) {
      const std::size_t v = *it;
      if (v >= soup.points.size()) {
        // The readers store a negative index of the file as its wrapped-around unsigned value.
        const std::string index = v > std::numeric_limits<std::size_t>::max() / 2
                                      ? "-" + std::to_string(std::numeric_limits<std::size_t>::max() - v + 1)
                                      : std::to_string(format == MeshFormat::obj ? v + 1 : v);
        corrupt(path, "face " + std::to_string(f) + " refers to vertex " + index + ", but " +
                          vertex_range(soup.points.size(), format == MeshFormat::obj ? 1 : 0));
      }
    }
    sorted.assign(first, last);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      corrupt(path, "face " + std::to_string(f) + " repeats a vertex");
  }
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const Point3& p = soup.points[i];
    if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))) {
      corrupt(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  return soup;
}

TriangleSoup read_triangle_soup(const std::string& path) {
  PolygonSoup polygons = read_polygon_soup(path);
  TriangleSoup soup;
  soup.triangles.reserve(polygons.faces());
  for (std::size_t f = 0; f < polygons.faces(); ++f) {
    if (polygons.face_size(f) != 3) detail::not_a_triangle(path, f, std::to_string(polygons.face_size(f)));
    const std::size_t* c = polygons.face(f);
    soup.triangles.push_back({c[0], c[1], c[2]});
  }
  soup.points = std::move(polygons.points);
  return soup;
}

TriangleSoup triangulate_polygons(const PolygonSoup& soup, const std::string& source) {
  for (std::size_t index : soup.corners)
    if (index >= soup.points.size()) throw PreconditionViolation("triangulate_polygons: vertex index out of range");
  // The faces of more than three vertices, each with its own copies of its points, in one mesh;
  // each is triangulated on its own, and its triangles replace it in the face order.
  SurfaceMesh polygons;
  std::vector<std::size_t> point_of;  // the soup's point of each vertex of `polygons`
  std::vector<SurfaceMesh::Face_index> face_of(soup.faces());
  std::vector<SurfaceMesh::Vertex_index> corners;
  for (std::size_t f = 0; f < soup.faces(); ++f) {
    if (soup.face_size(f) == 3) continue;
    corners.clear();
    for (const std::size_t* c = soup.face(f); c != soup.face(f) + soup.face_size(f); ++c) {
      corners.push_back(polygons.add_vertex(soup.points[*c]));
      point_of.push_back(*c);
    }
    face_of[f] = polygons.add_face(corners);
  }
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<std::vector<std::array<std::size_t, 3>>> triangles_of(soup.faces());
  for (std::size_t f = 0; f < soup.faces(); ++f) {
    if (soup.face_size(f) == 3) continue;
    if (!PMP::triangulate_face(face_of[f], polygons))
      corrupt(source, "face " + std::to_string(f) + " (" + std::to_string(soup.face_size(f)) +
                          " vertices) could not be triangulated (a degenerate polygon)");
  }
  // A vertex belongs to one face of the soup: the first corner of a triangle names its face.
  std::vector<std::size_t> face_of_vertex(point_of.size());
  for (std::size_t f = 0, v = 0; f < soup.faces(); ++f)
    if (soup.face_size(f) != 3)
      for (std::size_t k = 0; k < soup.face_size(f); ++k) face_of_vertex[v++] = f;
  for (SurfaceMesh::Face_index t : polygons.faces()) {
    std::array<std::size_t, 3> triangle{};
    std::size_t k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(polygons.halfedge(t), polygons))
      triangle[k++] = static_cast<std::size_t>(v);
    const std::size_t f = face_of_vertex[triangle[0]];
    for (std::size_t& v : triangle) v = point_of[v];
    triangles_of[f].push_back(triangle);
  }
  TriangleSoup out;
  out.points = soup.points;
  for (std::size_t f = 0; f < soup.faces(); ++f) {
    if (soup.face_size(f) == 3) {
      const std::size_t* c = soup.face(f);
      out.triangles.push_back({c[0], c[1], c[2]});
    } else {
      out.triangles.insert(out.triangles.end(), triangles_of[f].begin(), triangles_of[f].end());
    }
  }
  return out;
}

SurfaceMesh read_mesh(const std::string& path) {
  TriangleSoup soup = read_triangle_soup(path);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
  namespace PMP = CGAL::Polygon_mesh_processing;
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    corrupt(path, "the triangles do not form a consistently oriented 2-manifold (with or without "
                  "boundary); read it with read_triangle_soup to check it");
  }
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(soup.points, polygons, mesh);
  return mesh;
}

}  // namespace delmesh
