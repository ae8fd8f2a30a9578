#include "meshing/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
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
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include "common/errors.h"
#include "meshing/mesh_checker.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;

enum class Format { off, ply, obj };

//! Significant digits that make every double round-trip through text.
constexpr int full_double_precision = 17;

Format format_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".off") return Format::off;
  if (ext == ".ply") return Format::ply;
  if (ext == ".obj") return Format::obj;
  throw InvalidInput("mesh file '" + path + "': unknown extension '" + ext +
                     "' (expected .off, .ply or .obj)");
}

[[noreturn]] void corrupt(const std::string& path, const std::string& why) {
  throw InvalidInput("mesh file '" + path + "': " + why);
}

//! A loose upper bound on the element counts a file of this size can hold, so that a header that
//! claims billions of elements is rejected before the CGAL readers allocate for them.
void check_declared_counts(const std::string& path, Format format, std::uintmax_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<std::uintmax_t> counts;
  if (format == Format::off) {
    // Header: optional "[ST][C][N][4][n]OFF" keyword, then "V F E" on the first non-comment line.
    std::string word;
    while (in >> word) {
      if (word[0] == '#') {
        std::getline(in, line);
        continue;
      }
      if (word.find("OFF") != std::string::npos) continue;
      try {
        counts.push_back(std::stoull(word));
      } catch (const std::exception&) {
        corrupt(path, "malformed OFF header near '" + word + "'");
      }
      if (counts.size() == 2) break;
    }
    if (counts.size() != 2) corrupt(path, "OFF header has no vertex and face counts");
  } else if (format == Format::ply) {
    // "element NAME COUNT" lines until end_header.
    bool ended = false;
    for (int i = 0; i < 10000 && std::getline(in, line); ++i) {
      if (line.rfind("end_header", 0) == 0) {
        ended = true;
        break;
      }
      if (line.rfind("element", 0) == 0) {
        const auto at = line.find_last_of(' ');
        try {
          counts.push_back(std::stoull(line.substr(at + 1)));
        } catch (const std::exception&) {
          corrupt(path, "malformed PLY element line '" + line + "'");
        }
      }
    }
    if (!ended) corrupt(path, "PLY header has no end_header");
  }
  // Every vertex and every face takes at least 3 bytes in any of the encodings.
  for (std::uintmax_t count : counts) {
    if (count > bytes / 3 + 1) {
      corrupt(path, "the header declares " + std::to_string(count) + " elements but the file has only " +
                        std::to_string(bytes) + " bytes (truncated or corrupt)");
    }
  }
}

}  // namespace

void write_triangle_soup(const TriangleSoup& soup, const std::string& path) {
  const Format format = format_of(path);
  for (const auto& t : soup.triangles)
    for (std::size_t v : t)
      if (v >= soup.points.size()) throw InvalidInput("write_mesh: vertex index out of range");

  const fs::path target(path);
  const fs::path temporary =
      target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()));
  bool ok = false;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("write_mesh: cannot open '" + temporary.string() + "' for writing");
    out.imbue(std::locale::classic());
    out.precision(full_double_precision);
    const auto np = CGAL::parameters::stream_precision(full_double_precision);
    switch (format) {
      case Format::off:
        ok = CGAL::IO::write_OFF(out, soup.points, soup.triangles, np);
        break;
      case Format::ply:
        CGAL::IO::set_mode(out, CGAL::IO::ASCII);
        ok = CGAL::IO::write_PLY(out, soup.points, soup.triangles, np);
        break;
      case Format::obj:
        ok = CGAL::IO::write_OBJ(out, soup.points, soup.triangles, np);
        break;
    }
    out.flush();
    ok = ok && out.good();
  }
  std::error_code ignored;
  if (!ok) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("write_mesh: writing '" + temporary.string() + "' failed");
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("write_mesh: cannot rename '" + temporary.string() + "' to '" + path +
                             "': " + error.message());
  }
}

void write_mesh(const SurfaceMesh& mesh, const std::string& path) {
  format_of(path);  // reject an unknown extension before any work
  TriangleSoup soup;
  mesh_to_soup(mesh, soup.points, soup.triangles);
  write_triangle_soup(soup, path);
}

TriangleSoup read_triangle_soup(const std::string& path) {
  const Format format = format_of(path);
  std::error_code error;
  if (!fs::is_regular_file(path, error)) corrupt(path, "no such file");
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (error) corrupt(path, "cannot read its size: " + error.message());
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) corrupt(path, "cannot be opened for reading");
  }
  check_declared_counts(path, format, bytes);

  std::vector<Point3> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    switch (format) {
      case Format::off:
        ok = CGAL::IO::read_OFF(path, points, polygons);
        break;
      case Format::ply:
        ok = CGAL::IO::read_PLY(path, points, polygons);
        break;
      case Format::obj:
        ok = CGAL::IO::read_OBJ(path, points, polygons);
        break;
    }
  } catch (const std::bad_alloc&) {
    corrupt(path, "out of memory while reading (corrupt element counts?)");
  } catch (const std::exception& e) {
    corrupt(path, std::string("the reader failed: ") + e.what());
  }
  if (!ok) corrupt(path, "cannot be parsed (truncated or corrupt)");
  if (polygons.empty()) corrupt(path, "has no faces");

  TriangleSoup soup;
  soup.points = std::move(points);
  soup.triangles.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& polygon = polygons[f];
    if (polygon.size() != 3) {
      corrupt(path, "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) +
                        " vertices; only triangle meshes are supported");
    }
    for (std::size_t v : polygon) {
      if (v >= soup.points.size()) {
        corrupt(path, "face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + " of " +
                          std::to_string(soup.points.size()));
      }
    }
    if (polygon[0] == polygon[1] || polygon[1] == polygon[2] || polygon[0] == polygon[2]) {
      corrupt(path, "face " + std::to_string(f) + " repeats a vertex");
    }
    soup.triangles.push_back({polygon[0], polygon[1], polygon[2]});
  }
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const Point3& p = soup.points[i];
    if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))) {
      corrupt(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  return soup;
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
